# The shell scripts' words in the user's language (docs/translating.md), sourced by run.sh and
# test.sh once $root is set: `say FORMAT [ARGUMENT...]` prints FORMAT as the build's catalogue
# translates it (GNU gettext's program), through printf, with a newline. The language is
# clothlab's choice (LANGUAGE, LC_ALL, LC_MESSAGES, LANG: scripts/clothlab_lab/messages.py),
# made at the first word, once the build has compiled the catalogues. English where there is
# no catalogue, no Python or no gettext program.
clothlab_language=
say() {
  local format=$1
  shift
  if [ -z "$clothlab_language" ]; then
    clothlab_language=$(PYTHONDONTWRITEBYTECODE=1 python3 -c '
import sys
sys.path.insert(0, sys.argv[1])
from clothlab_lab import messages
print(messages.start(sys.argv[2]))' "$root/scripts" "$root/build" 2>/dev/null || echo en)
  fi
  if [ "$clothlab_language" != en ] && command -v gettext >/dev/null; then
    # (C.UTF-8: gettext reads LANGUAGE in any locale but C, and no French locale need exist.)
    format=$(LC_ALL=C.UTF-8 LANGUAGE=$clothlab_language TEXTDOMAINDIR="$root/build/locale" \
      gettext -d clothlab -- "$format")
  fi
  # shellcheck disable=SC2059  # the format is the message
  printf -- "$format\n" "$@"
}
