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
mkdir -p "$root/out"
# The cloth's final state on each path (its last step only), to say what the pictures show.
states=$(mktemp -d)
trap 'rm -rf "$states"' EXIT
tour=(
  "spring:--stage spring --steps 100"
  "coupled:--stage coupled --steps 150 --csv $states/chain.csv --csv-every 150"
  "cloth:--stage cloth --steps 1500 --csv $states/cpu.csv --csv-every 1500"
  "cloth-wind:--stage cloth --steps 1500 --wind-strength 20 --wind-dir 0,1,0.2"
  "cloth-gpu:--stage cloth --backend gpu --steps 1500 --csv $states/gpu.csv --csv-every 1500"
)
for entry in "${tour[@]}"; do
  name=${entry%%:*}
  read -r -a args <<<"${entry#*:}"
  "$root/build/clothlab" --headless "${args[@]}" "$@" --png "$root/out/$name.png"
  shown=${entry#*:}
  echo "  wrote out/$name.png  (clothlab --headless ${shown%% --csv *} --png out/$name.png)"
done

# What the chain's picture shows, from its last step: the last mass hangs below the one above
# it, or fell away from it (farther than four rest lengths, 2 m: its spring does not hold it).
chain_state() {  # CSV
  awk -F, 'NR > 1 { if ($1 != step) { n = 0; step = $1 } n++; x[n] = $4; y[n] = $5; z[n] = $6 }
    END {
      if (n < 3) { print "unknown"; exit }
      d = sqrt((x[n] - x[n-1])^2 + (y[n] - y[n-1])^2 + (z[n] - z[n-1])^2)
      if (d > 2) printf "its last mass fell away, %.3g m below the one above it\n", z[n-1] - z[n]
      else print "the chain hangs and sways"
    }' "$1" 2>/dev/null || echo unknown
}
if [ -f "$states/chain.csv" ]; then
  chain=$(chain_state "$states/chain.csv")
  echo "clothlab: what the chain picture shows (out/coupled.png): $chain."
  case "$chain" in
    its\ last*) echo "          Its lower spring pulls no mass: question 5 (coupled_springs::compute_force)." ;;
  esac
fi

# What the cloth of a picture does, from its last step: hangs, lies on the floor, or went
# through it (the floor at z = -1; the questions that hold the cloth up are 6 to 9).
cloth_state() {  # CSV
  awk -F, 'NR > 1 { step[NR] = $1; z[NR] = $6; last = $1 }
    END {
      n = 0; below = 0; low = 1e30; high = -1e30
      for (i in step) if (step[i] == last) {
        n++; if (z[i] < -1.05) below++
        if (z[i] < low) low = z[i]; if (z[i] > high) high = z[i]
      }
      if (n == 0) print "unknown"
      else if (below == n) printf "fell through the floor, out of the picture (its highest point at z = %.3g m)\n", high
      else if (below > 0) printf "hangs in part: %d of its %d particles went through the floor\n", below, n
      else if (high < -0.9) print "lies on the floor: nothing holds it up"
      else print "hangs above the floor"
    }' "$1" 2>/dev/null || echo unknown
}
if [ -f "$states/cpu.csv" ]; then
  cpu=$(cloth_state "$states/cpu.csv")
  gpu=$( [ -f "$states/gpu.csv" ] && cloth_state "$states/gpu.csv" || echo unknown)
  echo "clothlab: what the cloth pictures show: on the CPU (out/cloth.png) the cloth $cpu;"
  echo "          on the GPU (out/cloth-gpu.png) it $gpu."
  case "$cpu" in
    fell*) echo "          The cloth's questions are still to do: 6 (apply_force), 7 (the pins), 8" \
                "(the springs) and 9 (the ground); ./test.sh shows which (README: Your tasks)." ;;
    "hangs in part"*) echo "          Part of it falls: questions 8 (the springs) and 9 (the ground)." ;;
    lies*) echo "          Nothing holds it: question 7 (the two pinned corners)." ;;
  esac
  case "$gpu" in
    fell* | "hangs in part"*)
      case "$cpu" in
        hangs\ above*) echo "          On the GPU: questions 12 (the springs) and 9 (the ground, in" \
                             "shaders/gpu_cloth_common.glsl)." ;;
      esac ;;
  esac
fi
echo "          The pictures are still: for the window (the lab's panel, live), run ./run.sh from a"
echo "          desktop session, or on this machine: xvfb-run -a ./run.sh"
