#!/usr/bin/env bash
# Sets clothlab up (missing Debian packages, Release build in build/) and runs the demo:
# the window when a display is available, else a tour of the stages rendered to PNG in out/.
#   ./run.sh [clothlab options]     e.g. ./run.sh --stage spring --K 50
set -euo pipefail
root=$(cd "$(dirname "$0")" && pwd)
"$root/scripts/setup.sh" Release

if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
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
