#!/usr/bin/env bash
# Sets clothlab up (missing packages: apt-get on Debian and Ubuntu, Homebrew on macOS; Release
# build in build/) and runs the demo:
# the window when a display is available, else a tour of the stages rendered to PNG in out/.
#   ./run.sh [clothlab options]     e.g. ./run.sh --stage spring --K 50
#   ./run.sh --web [--port PORT]    the lab in a browser (docs/web.md): installs emscripten,
#                                   builds the page into build-web/site/ and serves it on
#                                   http://127.0.0.1:PORT/ (8000 or the next free port)
#   ./run.sh --web-build-only       the same page, built but not served
set -euo pipefail
root=$(cd "$(dirname "$0")" && pwd)

case "${1:-}" in
  --web)
    shift
    "$root/scripts/setup-web.sh"
    exec "$root/scripts/serve-web" "$@"
    ;;
  --web-build-only)
    shift
    if [ $# -gt 0 ]; then
      echo "run.sh: --web-build-only takes no other option (got: $*)" >&2
      exit 2
    fi
    exec "$root/scripts/setup-web.sh"
    ;;
esac
"$root/scripts/setup.sh" Release

# (macOS always has its display, without DISPLAY.)
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ] || [ "$(uname -s)" = Darwin ]; then
  exec "$root/build/clothlab" "$@"
fi

echo "clothlab: no display (DISPLAY is not set): rendering each stage off-screen instead."
echo "          For the window, run ./run.sh from a desktop session, or: xvfb-run -a ./run.sh"
mkdir -p "$root/out"
tour=(
  "spring:--stage spring --steps 100"
  "coupled:--stage coupled --steps 150"
  "cloth:--stage cloth --steps 1500"
  "cloth-wind:--stage cloth --steps 1500 --wind-strength 20 --wind-dir 0,1,0.2"
  "cloth-gpu:--stage cloth --backend gpu --steps 1500"
)
for entry in "${tour[@]}"; do
  name=${entry%%:*}
  read -r -a args <<<"${entry#*:}"
  "$root/build/clothlab" --headless "${args[@]}" "$@" --png "$root/out/$name.png"
  echo "  wrote out/$name.png  (clothlab --headless ${entry#*:} --png out/$name.png)"
done
