#!/usr/bin/env bash
# Starts clothlab-window in a virtual X server (Xvfb), drives it with xdotool and checks what it
# does. Every wait has a timeout, so that the test fails instead of hanging.
#   window_test.sh PATH/TO/clothlab-window keys|divergence|gpu_switch|frames|steady_panel|paused_idle
set -euo pipefail

program=$(realpath "$1")
scenario=${2:-keys}

fail() {
  echo "window test ($scenario): FAIL: $*" >&2
  if [ -f window.log ]; then
    echo "--- clothlab-window's output:" >&2
    cat window.log >&2
  fi
  exit 1
}

# Outside the virtual X server: check the tools, then run this script again inside one, in a
# temporary working directory (the screenshots land there).
if [ -z "${CLOTHLAB_WINDOW_TEST_INSIDE_XVFB:-}" ]; then
  for tool in xvfb-run xauth xdotool identify; do
    command -v "$tool" >/dev/null ||
      fail "$tool is missing: install xvfb, xauth, xdotool and imagemagick (scripts/setup.sh does)"
  done
  workdir=$(mktemp -d)
  trap 'rm -rf "$workdir"' EXIT
  cd "$workdir"
  status=0
  CLOTHLAB_WINDOW_TEST_INSIDE_XVFB=1 timeout 200 \
    xvfb-run -a -s "-screen 0 1280x800x24" bash "$(realpath "$0")" "$program" "$scenario" ||
    status=$?
  [ "$status" -eq 124 ] && fail "timed out after 200 s"
  exit "$status"
fi

# --frames COUNT: the window runs COUNT frames, prints the mean frame time and the steps per
# second, and exits 0 by itself (no key needed).
if [ "$scenario" = frames ]; then
  status=0
  "$program" --frames 0 >window.log 2>&1 || status=$?
  [ "$status" -eq 2 ] || fail "--frames 0 was accepted (exit $status, expected 2)"
  status=0
  timeout 120 "$program" --frames 40 >window.log 2>&1 || status=$?
  [ "$status" -eq 0 ] || fail "--frames 40 exited with status $status (expected 0)"
  line=$(grep -E "^clothlab-window: 40 frames in [0-9.]+ s: mean frame time [0-9.]+ ms \([0-9.]+ frames/s\), [0-9]+ steps/s$" window.log) ||
    fail "--frames 40 printed no line 'N frames in T s: mean frame time ... ms (... frames/s), ... steps/s'"
  echo "window test: $line"
  steps=$(echo "$line" | sed -E 's/.* ([0-9]+) steps\/s$/\1/')
  [ "$steps" -gt 0 ] || fail "the cloth took no steps during --frames 40"
  echo "window test ($scenario): PASS"
  exit 0
fi

arguments=()
if [ "$scenario" = divergence ]; then
  # Explicit Euler without damping grows by sqrt(1 + (dt omega)^2) = 3.7 per step here.
  arguments=(--stage spring --integrator explicit --K 5000 --dt 0.05 --mu 0)
elif [ "$scenario" = gpu_switch ]; then
  arguments=(--stage cloth --wind-strength 10)  # the cloth flaps in the wind onto the ground
fi
# Every run prints where the dt slider is whenever it or the run's state changes.
CLOTHLAB_PRINT_LAYOUT=1 "$program" "${arguments[@]}" >window.log 2>&1 &
pid=$!

window=$(timeout 30 xdotool search --sync --onlyvisible --name '^clothlab$' | head -n 1) ||
  fail "no window named clothlab appeared within 30 s"
[ -n "$window" ] || fail "no window named clothlab appeared"
timeout 10 xdotool windowfocus --sync "$window" || fail "cannot focus the window"
sleep 1

still_running() {
  kill -0 "$pid" 2>/dev/null || fail "clothlab-window exited (or crashed) after: $1"
}

press() {
  timeout 10 xdotool key --clearmodifiers "$1" || fail "xdotool key $1 failed"
  sleep 0.7
  still_running "key $1"
}

# Waits up to 10 s for a line of the program's output (the window runs at a few frames per
# second on a loaded machine).
wait_for_log() {
  for _ in $(seq 40); do
    grep -q "$1" window.log && return 0
    sleep 0.25
  done
  return 1
}

# The screenshot key P writes clothlab-YYYYMMDD-HHMMSS-<stage>.png; waits for it.
screenshot_of() {
  local stage=$1 before after file
  before=$(ls clothlab-*-"$stage"*.png 2>/dev/null | wc -l)
  press p
  for _ in $(seq 40); do
    after=$(ls clothlab-*-"$stage"*.png 2>/dev/null | wc -l)
    [ "$after" -gt "$before" ] && break
    sleep 0.25
  done
  file=$(ls -t clothlab-*-"$stage"*.png 2>/dev/null | head -n 1)
  [ -n "$file" ] && [ "$after" -gt "$before" ] || fail "P wrote no clothlab-*-$stage.png"
  echo "$file"
}

# A PNG of width x height that shows something: at least min_colours colours and a spread of
# intensities (a blank or black frame has one colour and no spread).
check_image() {
  local file=$1 width=$2 height=$3 min_colours=$4 size colours spread
  size=$(identify -format "%w %h" "$file") || fail "$file is not a readable image"
  [ "$size" = "$width $height" ] || fail "$file is $size, expected the window's $width $height"
  colours=$(identify -format "%k" "$file")
  [ "$colours" -ge "$min_colours" ] || fail "$file looks blank: only $colours colours"
  spread=$(identify -format "%[fx:standard_deviation]" "$file")
  awk -v s="$spread" 'BEGIN { exit !(s > 0.02) }' || fail "$file looks blank: deviation $spread"
  echo "window test: $file: $size, $colours colours, deviation $spread"
}

# The cloth is in the picture: the red squares of its texture cover at least 1 % of the scene
# right of the panel (the ground and the sky have no saturated red).
check_cloth_drawn() {
  local file=$1 red
  red=$(convert "$file" -crop 840x800+440+0 +repage -fx "r > 0.55 && g < 0.35 && b < 0.35" \
    -format "%[fx:mean]" info:) || fail "cannot read $file"
  awk -v f="$red" 'BEGIN { exit !(f > 0.01) }' || fail "$file shows no cloth (red fraction $red)"
  echo "window test: $file: the cloth's red covers $red of the scene"
}

# The panel is steady: for one stage, the dt slider is at the same height whatever the status
# (running, paused, diverged, a message about the cloth's path) in every layout line so far.
# At least min_states different states must have been seen.
check_steady_panel() {
  local stage=$1 min_states=$2 lines positions states
  lines=$(grep "^clothlab-window: layout: $stage stage," window.log) ||
    fail "no layout line for the $stage stage (CLOTHLAB_PRINT_LAYOUT)"
  positions=$(echo "$lines" | sed -E 's/.*dt slider at y = //' | sort -u | wc -l)
  states=$(echo "$lines" | sed -E 's/: dt slider at.*//' | sort -u | wc -l)
  [ "$positions" -eq 1 ] || fail "the dt slider moved when the status changed:
$lines"
  [ "$states" -ge "$min_states" ] || fail "only $states states seen, expected $min_states:
$lines"
  echo "window test: the $stage stage's dt slider stayed put through $states states"
}

# The panel's sliders (x 0-390, y 280-760: the Q4 to Q9 sections of the cloth) are the same
# pixels in two screenshots.
check_same_panel() {
  local first=$1 second=$2 different
  convert "$first" -crop 390x480+0+280 +repage first-panel.png || fail "cannot crop $first"
  convert "$second" -crop 390x480+0+280 +repage second-panel.png || fail "cannot crop $second"
  different=$(compare -metric AE first-panel.png second-panel.png null: 2>&1) || true
  [ "$different" = 0 ] || fail "the panel's sliders moved between $first and $second ($different pixels differ)"
  echo "window test: the panel's sliders are the same pixels in $first and $second"
}

case "$scenario" in
  paused_idle)
    # Paused, the window sleeps between events instead of drawing the same frame again: under a
    # quarter of a core over 3 s (running, it takes one or two cores on llvmpipe).
    press space
    sleep 1
    ticks_before=$(awk '{print $14 + $15}' /proc/$pid/stat)
    sleep 3
    ticks_after=$(awk '{print $14 + $15}' /proc/$pid/stat)
    percent=$(( (ticks_after - ticks_before) * 100 / (3 * $(getconf CLK_TCK)) ))
    [ "$percent" -lt 25 ] || fail "the paused window used $percent % of a core (expected under 25 %)"
    echo "window test: paused, the window used $percent % of a core"
    # It still answers keys while idle: a step (N), then a screenshot (P).
    press n
    check_image "$(screenshot_of cloth)" 1280 800 200
    ;;
  steady_panel)
    # The cloth: running, paused, running, switched to the GPU (a message), stepped.
    sleep 1
    running=$(screenshot_of cloth)
    press space
    paused=$(screenshot_of cloth)
    check_same_panel "$running" "$paused"
    press space
    press g
    wait_for_log "cloth: CPU -> GPU at step" || fail "G did not switch the cloth to the GPU"
    press n
    check_steady_panel cloth 4
    ;;
  keys)
    press 1
    check_image "$(screenshot_of spring)" 1280 800 200
    press 2
    check_image "$(screenshot_of coupled)" 1280 800 200
    press 3
    press space  # pause
    press n      # one step
    press w      # wireframe
    press h      # key help
    press v      # reset view
    press g      # the cloth to the GPU (paused: it must not move)
    wait_for_log "cloth: CPU -> GPU at step" || fail "G did not switch the cloth to the GPU"
    timeout 10 xdotool windowsize --sync "$window" 900 600 || fail "cannot resize the window"
    sleep 1
    still_running "resize to 900 x 600"
    check_image "$(screenshot_of cloth)" 900 600 200
    ;;
  divergence)
    wait_for_log "the spring stage diverged at step" ||
      fail "explicit Euler with K = 5000, dt = 0.05 did not report a divergence"
    still_running "the divergence"
    # Nothing is drawn for the diverged stage: the panel (with its red message) on the background.
    check_image "$(screenshot_of spring)" 1280 800 20
    press r  # reset: the run starts again, and diverges again
    for _ in $(seq 40); do
      [ "$(grep -c "diverged at step" window.log)" -ge 2 ] && break
      sleep 0.25
    done
    [ "$(grep -c "diverged at step" window.log)" -ge 2 ] || fail "R did not restart the run"
    check_steady_panel spring 2  # running, then diverged: the slider did not move
    ;;
  gpu_switch)
    # The cloth runs a while on the CPU, goes to the GPU while running, is drawn from the GPU's
    # textures, and comes back to the CPU, still running.
    sleep 1
    press g
    wait_for_log "cloth: CPU -> GPU at step" || fail "G did not switch the cloth to the GPU"
    sleep 1
    on_gpu=$(screenshot_of cloth)
    check_image "$on_gpu" 1280 800 200
    check_cloth_drawn "$on_gpu"
    press g
    wait_for_log "cloth: GPU -> CPU at step" || fail "G did not bring the cloth back"
    sleep 1
    grep -q "diverged" window.log && fail "the cloth diverged across the switches"
    on_cpu=$(screenshot_of cloth)
    check_image "$on_cpu" 1280 800 200
    check_cloth_drawn "$on_cpu"
    ;;
  *)
    fail "unknown scenario $scenario (keys, divergence, gpu_switch, frames, steady_panel or paused_idle)"
    ;;
esac

timeout 10 xdotool key --clearmodifiers Escape || fail "xdotool key Escape failed"
for _ in $(seq 40); do
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.25
done
kill -0 "$pid" 2>/dev/null && { kill "$pid"; fail "Esc did not close the window within 10 s"; }
status=0
wait "$pid" || status=$?
[ "$status" -eq 0 ] || fail "clothlab-window exited with status $status after Esc (expected 0)"
echo "window test ($scenario): PASS"
