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
. "$root/scripts/messages.sh"  # say: the words in the user's language

case "${1:-}" in
  --web)
    shift
    "$root/scripts/setup-web.sh"
    exec "$root/scripts/serve-web" "$@"
    ;;
  --web-build-only)
    shift
    if [ $# -gt 0 ]; then
      say "run.sh: --web-build-only takes no other option (got: %s)" "$*" >&2
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

say "clothlab: no display (DISPLAY is not set): rendering each stage off-screen instead."
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
  say "  wrote out/%s.png  (clothlab --headless %s --png out/%s.png)" "$name" "${shown%% --csv *}" \
    "$name"
done

# What the chain's picture shows, from its last step: the last mass hangs below the one above
# it ("hangs"), or fell away from it ("fell DISTANCE": farther than four rest lengths, 2 m, its
# spring does not hold it).
chain_state() {  # CSV
  awk -F, 'NR > 1 { if ($1 != step) { n = 0; step = $1 } n++; x[n] = $4; y[n] = $5; z[n] = $6 }
    END {
      if (n < 3) { print "unknown"; exit }
      d = sqrt((x[n] - x[n-1])^2 + (y[n] - y[n-1])^2 + (z[n] - z[n-1])^2)
      if (d > 2) printf "fell %.3g\n", z[n-1] - z[n]
      else print "hangs"
    }' "$1" 2>/dev/null || echo unknown
}
if [ -f "$states/chain.csv" ]; then
  read -r chain distance <<<"$(chain_state "$states/chain.csv")"
  case "$chain" in
    fell)
      say "clothlab: what the chain picture shows (out/coupled.png): its last mass fell away, %s m below the one above it." "$distance"
      say "          Its lower spring pulls no mass: question 5 (coupled_springs::compute_force)." ;;
    hangs) say "clothlab: what the chain picture shows (out/coupled.png): the chain hangs and sways." ;;
    *) say "clothlab: what the chain picture shows (out/coupled.png) is unknown." ;;
  esac
fi

# What the cloth of a picture does, from its last step: hangs, lies on the floor, or went
# through it (the floor at z = -1; the questions that hold the cloth up are 6 to 9): "fell HIGHEST",
# "part BELOW COUNT", "lies", "hangs" or "unknown".
cloth_state() {  # CSV
  awk -F, 'NR > 1 { step[NR] = $1; z[NR] = $6; last = $1 }
    END {
      n = 0; below = 0; low = 1e30; high = -1e30
      for (i in step) if (step[i] == last) {
        n++; if (z[i] < -1.05) below++
        if (z[i] < low) low = z[i]; if (z[i] > high) high = z[i]
      }
      if (n == 0) print "unknown"
      else if (below == n) printf "fell %.3g\n", high
      else if (below > 0) printf "part %d %d\n", below, n
      else if (high < -0.9) print "lies"
      else print "hangs"
    }' "$1" 2>/dev/null || echo unknown
}
# The state in words: what the cloth does (a predicate: "the cloth fell through the floor ...").
cloth_words() {  # STATE [NUMBERS]
  case "$1" in
    fell) say "fell through the floor, out of the picture (its highest point at z = %s m)" "$2" ;;
    part) say "hangs in part: %s of its %s particles went through the floor" "$2" "$3" ;;
    lies) say "lies on the floor: nothing holds it up" ;;
    hangs) say "hangs above the floor" ;;
    *) say "is in a state that cannot be read" ;;
  esac
}
if [ -f "$states/cpu.csv" ]; then
  read -r -a cpu <<<"$(cloth_state "$states/cpu.csv")"
  gpu=(unknown)
  if [ -f "$states/gpu.csv" ]; then
    read -r -a gpu <<<"$(cloth_state "$states/gpu.csv")"
  fi
  say "clothlab: what the cloth pictures show: on the CPU (out/cloth.png) the cloth %s;" \
    "$(cloth_words "${cpu[@]}")"
  say "          on the GPU (out/cloth-gpu.png) it %s." "$(cloth_words "${gpu[@]}")"
  case "${cpu[0]}" in
    fell)
      say "          The cloth's questions are still to do: 6 (apply_force), 7 (the pins), 8"
      say "          (the springs) and 9 (the ground); ./test.sh shows which (README: Your tasks)." ;;
    part) say "          Part of it falls: questions 8 (the springs) and 9 (the ground)." ;;
    lies) say "          Nothing holds it: question 7 (the two pinned corners)." ;;
  esac
  case "${gpu[0]}" in
    fell | part)
      if [ "${cpu[0]}" = hangs ]; then
        say "          On the GPU: questions 12 (the springs) and 9 (the ground, in shaders/gpu_cloth_common.glsl)."
      fi ;;
  esac
fi
say "          The pictures are still: for the window (the lab's panel, live), run ./run.sh from a"
say "          desktop session, or on this machine: xvfb-run -a ./run.sh"
