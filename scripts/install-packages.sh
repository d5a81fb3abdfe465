#!/usr/bin/env bash
# Installs those of the given packages that are missing, named as Debian names them, on the
# platform this runs on (scripts/packages.txt gives each one's name there):
#   Debian, Ubuntu (WSL2's too): apt-get, as root or with password-less sudo;
#   macOS: Homebrew (brew install);
#   elsewhere: prints what to install, and goes on.
# It says what to run when it cannot install, and what a package that the platform lacks means
# (Ubuntu's chromium is a snap package; Debian after 13 has no OSMesa). Used by scripts/setup.sh
# and scripts/setup-web.sh.
#   scripts/install-packages.sh PACKAGE...
#   scripts/install-packages.sh --platform     prints debian, ubuntu, macos or other
# CLOTHLAB_PLATFORM=ubuntu (or another) makes it act as on that platform, to check what it does.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)

platform() {
  if [ -n "${CLOTHLAB_PLATFORM:-}" ]; then
    echo "$CLOTHLAB_PLATFORM"
    return
  fi
  if [ "$(uname -s)" = Darwin ]; then
    echo macos
    return
  fi
  local id="" like=""
  if [ -r /etc/os-release ]; then
    id=$(. /etc/os-release && echo "${ID:-}")
    like=$(. /etc/os-release && echo "${ID_LIKE:-}")
  fi
  case " $id $like " in
    *" ubuntu "*) echo ubuntu ;;
    *" debian "*) echo debian ;;
    *) echo other ;;
  esac
}

if [ "${1:-}" = --platform ]; then
  platform
  exit 0
fi
where=$(platform)

# The name of Debian package $1 on this platform ("?": none there), and what lacking it means.
column() {
  awk -v p="$1" -v c="$2" '!/^#/ && $1 == p {print $c; found = 1} END {if (!found) print p}' \
    "$here/packages.txt"
}
explain() {
  case "$1" in
    imgui-sources) echo "Dear ImGui: scripts/setup.sh compiles it from its sources" ;;
    stb-sources) echo "stb: scripts/setup.sh compiles it from its sources" ;;
    osmesa) echo "OSMesa: off-screen runs and tests use EGL (or, with no EGL, a hidden window)" ;;
    egl) echo "EGL: off-screen runs and tests use a hidden GLFW window (a display is needed)" ;;
    xvfb) echo "Xvfb and xdotool: the window tests (label window) are skipped" ;;
    bwrap) echo "bubblewrap: the grader runs submissions without its sandbox" ;;
    web) echo "emscripten: no browser build here (use Linux, WSL2 or the dev container)" ;;
    browser) if [ "$where" = ubuntu ]; then
        echo "chromium: on Ubuntu it is a snap package, not an apt one: the browser tests" \
             "(label web) are skipped; the page itself works in any browser"
      else
        echo "chromium: the browser tests (label web) are skipped"
      fi ;;
    *) echo "$1" ;;
  esac
}

case "$where" in
  debian) name_column=1 ;;
  ubuntu) name_column=2 ;;
  macos) name_column=3 ;;
  *)
    echo "clothlab: this system is not Debian, Ubuntu or macOS; install the equivalents of these" \
         "Debian packages yourself (docs/platforms.md): $*" >&2
    exit 0
    ;;
esac

# Each package's name here; those the platform lacks are said once, by what they mean.
wanted=()
said=" "
for p in "$@"; do
  name=$(column "$p" "$name_column")
  case "$name" in
    "?")
      key=$(column "$p" 4)
      if [[ "$said" != *" $key "* ]]; then
        echo "clothlab: not on $where: $(explain "$key")"
        said+="$key "
      fi
      ;;
    -) ;;
    *) wanted+=("$name") ;;
  esac
done

if [ "$where" = macos ]; then
  if ! command -v brew >/dev/null 2>&1; then
    echo "clothlab: Homebrew (https://brew.sh) is needed, then run: brew install ${wanted[*]}" >&2
    exit 1
  fi
  missing=()
  for p in ${wanted[@]+"${wanted[@]}"}; do
    brew list --versions "$p" >/dev/null 2>&1 || missing+=("$p")
  done
  [ ${#missing[@]} -gt 0 ] || exit 0
  echo "clothlab: installing missing Homebrew packages: ${missing[*]}"
  brew install "${missing[@]}"
  exit 0
fi

# Debian and Ubuntu. What the build can do without is left out where the release has no package
# of it: OSMesa (Mesa 25.1 removed it: Debian unstable, and the releases after Debian 13), Dear
# ImGui and stb (scripts/setup.sh then compiles them from their sources).
optional=" libosmesa6-dev libimgui-dev libstb-dev "
apt_knows() { apt-cache show --no-all-versions "$1" >/dev/null 2>&1; }
drop_unknown_optional() {
  local kept=() p
  apt_knows cmake || return 0  # (the package lists are empty: nothing can be told yet)
  for p in "${missing[@]}"; do
    if [[ "$optional" == *" $p "* ]] && ! apt_knows "$p"; then
      echo "clothlab: this release has no $p: $(explain "$(column "$p" 4)")"
    else
      kept+=("$p")
    fi
  done
  missing=(${kept[@]+"${kept[@]}"})
}
missing=()
for p in ${wanted[@]+"${wanted[@]}"}; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
drop_unknown_optional
[ ${#missing[@]} -gt 0 ] || exit 0

echo "clothlab: installing missing $where packages: ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  sudo=(sudo)
else
  echo "clothlab: cannot install packages (not root, no password-less sudo). Run:" >&2
  echo "  sudo apt-get update && sudo apt-get install -y ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -q
drop_unknown_optional
[ ${#missing[@]} -gt 0 ] || exit 0
"${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
