#!/usr/bin/env bash
# Sets clothlab up (missing packages, Release build in build/) and runs every test with
# ctest: physics, command line, off-screen screenshots, GPU paths, the window under Xvfb, and the
# lab's grader (labels q5 ... q13), then prints the table of the lab's questions.
# BEGIN TEACHER
# A plain run leaves out the long checks (label long): the browser build and its tests in
# headless chromium (label web, docs/web.md), the grader on whole classes, honest and hostile,
# the Classroom workflow's run, the student copy in every state of the lab, the mutation and
# variant samples. `./test.sh --long` runs those, then the sanitizer builds; CI runs both
# (.ci/run, docs/testing.md). `./test.sh -L web` builds the page and runs its tests.
#   ./test.sh [ctest options]             e.g. ./test.sh -L q8 (one question)
#   ./test.sh --long                      the long checks, then the sanitizer part: the core, cli,
#                                         model, stability and fuzz labels built with
#                                         AddressSanitizer and UndefinedBehaviorSanitizer
# END TEACHER
# COPY| #   ./test.sh [ctest options]             e.g. ./test.sh -L q8 (one question)
#   ./test.sh --sanitize [ctest options]  the sanitizer build only, every test unless options
#                                         say otherwise, e.g. ./test.sh --sanitize -L cli
set -euo pipefail
root=$(cd "$(dirname "$0")" && pwd)
. "$root/scripts/messages.sh"  # say: the words in the user's language

# The sanitizer build: ASan + UBSan, every finding fatal (CLOTHLAB_SANITIZE in CMakeLists.txt).
sanitize() {
  cmake -S "$root" -B "$root/build-sanitize" -DCMAKE_BUILD_TYPE=None -DCLOTHLAB_SANITIZE=ON \
    -UCMAKE_CXX_FLAGS -UCMAKE_EXE_LINKER_FLAGS -UCMAKE_SHARED_LINKER_FLAGS >/dev/null
  cmake --build "$root/build-sanitize" -j "$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)" \
    ${targets[@]+"${targets[@]}"}
  # A finding exits 86, which no test expects from clothlab (0, 1, 2, 3, 128 + signal), so that
  # it cannot pass for an expected failure. Leaks inside Mesa are suppressed (lsan.supp).
  export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:exitcode=86:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=86"
  export LSAN_OPTIONS="suppressions=$root/tests/sanitize/lsan.supp:print_suppressions=0:exitcode=86"
  cd "$root/build-sanitize"
  if [ $# -gt 0 ]; then
    ctest --output-on-failure --timeout 600 -j 2 "$@"
    return
  fi
  # Every test. The window (GLX under Xvfb) leaves two 56-byte blocks allocated from a library
  # that is unloaded before exit (the stack points past clothlab-window's end; presumably
  # Mesa's DRI driver), which LeakSanitizer can neither symbolise nor so suppress: the window
  # tests run without leak checking, every other check on.
  local status=0
  ctest --output-on-failure --timeout 600 -j 2 -LE "window|student_copy|long" || status=$?
  ASAN_OPTIONS=${ASAN_OPTIONS/detect_leaks=1/detect_leaks=0} \
    ctest --output-on-failure --timeout 600 -j 2 -L window || status=$?
  return $status
}

# BEGIN TEACHER
# The browser build, for the tests that open it in headless chromium (label web, tests/web):
# started in the background (its output in build-web/build.log) while the tests run; the
# browser tests wait for it to end (build-web/build.status). Debian only (Ubuntu's chromium is a
# snap package). Sets web_build to its process, or leaves it empty.
web_build=
start_web_build() {
  [ "$("$root/scripts/install-packages.sh" --platform)" = debian ] || return 0
  mkdir -p "$root/build-web"
  rm -f "$root/build-web/build.status"
  "$root/scripts/setup-web.sh" --with-browser >"$root/build-web/build.log" 2>&1 &
  web_build=$!
  echo "$web_build" >"$root/build-web/build.pid"  # (before any test can look for it)
}
wait_web_build() {  # the browser build's end; 1 (and the end of its log) if it failed
  [ -n "$web_build" ] || return 0
  wait "$web_build" && return 0
  say "clothlab: the browser build failed; the end of build-web/build.log:" >&2
  tail -n 30 "$root/build-web/build.log" >&2
  return 1
}
# END TEACHER

if [ "${1:-}" = "--sanitize" ]; then
  shift
  "$root/scripts/setup.sh" Release
  targets=()
  sanitize "$@"
  exit
fi

# BEGIN TEACHER
if [ "${1:-}" = "--long" ]; then
  shift
  "$root/scripts/setup.sh" Release
  start_web_build
  long_options=(-L '^long$')
  if [ -z "$web_build" ]; then
    say "clothlab: no browser build on this platform: the tests labelled web are skipped (docs/platforms.md)"
    long_options+=(-LE '^web$')
  fi
  status=0
  (cd "$root/build" &&
    ctest --output-on-failure --timeout 3600 -j 2 "${long_options[@]}" "$@") || status=$?
  wait_web_build || status=1
  # The labels that need no OpenGL context also under the sanitizers. (Not the run through EGL:
  # Mesa's EGL driver leaves two 56-byte blocks from a library it unloads before exit, which
  # LeakSanitizer can neither symbolise nor so suppress.)
  targets=(--target clothlab core_tests cli_tests stability_tests fuzz_tests)
  sanitize -L "^(core|cli|model|stability|fuzz|stability-solution)$" -E "gl_egl" || status=$?
  exit "$status"
fi
# END TEACHER

# With ctest options (./test.sh -L q8) and a build already there, only the programs that the
# chosen tests run are built: after a one-line edit of spring_mesh.cpp, the question's checker
# and the lab's runner, in seconds. A question's label alone is looked up in the build's map
# (tests/lab/CMakeLists.txt writes it), other options are asked of ctest (scripts/test-targets).
# Otherwise, or when that cannot tell, scripts/setup.sh installs what is missing and builds
# everything.
programs=()
if [ $# -gt 0 ] && [ -f "$root/build/programs.txt" ]; then
  if [ $# -eq 2 ] && [ "$1" = -L ] && [ -f "$root/build/label-programs.txt" ]; then
    label=${2#^}
    read -r -a programs <<<"$(awk -v label="${label%\$}" '$1 == label { print $2 }' \
      "$root/build/label-programs.txt")"
  fi
  if [ ${#programs[@]} -eq 0 ]; then
    read -r -a programs <<<"$("$root/scripts/test-targets" "$root/build" "$@" || true)"
  fi
fi
if [ ${#programs[@]} -gt 0 ]; then
  cmake --build "$root/build" -j "$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)" \
    --target "${programs[@]}"
else
  "$root/scripts/setup.sh" Release
fi
# BEGIN TEACHER
if [[ "$*" == *web* ]]; then
  start_web_build
fi
# END TEACHER
# Where the platform lacks what a label needs (docs/platforms.md), a plain run leaves it out and
# says so: the browser tests need Debian's chromium (Ubuntu's is a snap package), the window tests
# Xvfb (macOS has none).
platform=$("$root/scripts/install-packages.sh" --platform)
left_out=()
if [ "$platform" != debian ]; then
  left_out+=(web)
fi
if [ "$platform" = macos ]; then
  left_out+=(window)
fi
run_tests() {  # JUNIT_FILE [ctest options]
  local results=$1
  shift
  (cd "$root/build" &&
    ctest --output-on-failure --timeout 300 -j 2 --output-junit "$results" "$@")
}
status=0
results=("$root/build/test-results.xml")
rm -f "$root/build/test-results-solution.xml"
if [ $# -gt 0 ]; then
  run_tests "${results[0]}" "$@" || status=$?
else
  if [ ${#left_out[@]} -gt 0 ]; then
    say "clothlab: on %s, the tests labelled %s are skipped (docs/platforms.md)" "$platform" \
      "${left_out[*]}"
  fi
  # BEGIN TEACHER
  left_out+=(long)  # ./test.sh --long
  # END TEACHER
  # COPY| say "clothlab: the tests of the lab's questions (lab.q5.* ... lab.q13.*) fail until you"
  # COPY| say "answer them; the table at the end says which is next (docs/lab.md)."
  # A plain run: every test but the left-out labels, then, once all of them pass, the tests of
  # the finished lab (labels *-solution: the pictures of the hanging cloth, the GPU against the
  # CPU, ...), which fail as long as a question is left: before that they would only repeat the
  # question tests' failures, under names that read like a broken install.
  left_out_regex="^($(IFS='|' && echo "${left_out[*]}"))(-solution)?\$"
  excluded="solution\$"
  if [ ${#left_out[@]} -gt 0 ]; then
    excluded="$left_out_regex|$excluded"
  fi
  run_tests "${results[0]}" -LE "$excluded" || status=$?
  finished=$([ "$status" = 0 ] && echo 1 || echo 0)
  # BEGIN TEACHER
  finished=1  # the teacher's copy holds every answer: its finished lab always runs
  # END TEACHER
  if [ "$finished" = 1 ]; then
    results+=("$root/build/test-results-solution.xml")
    solution_options=(-L "solution\$")
    if [ ${#left_out[@]} -gt 0 ]; then
      solution_options+=(-LE "$left_out_regex")
    fi
    run_tests "${results[1]}" "${solution_options[@]}" || status=$?
  else
    say "clothlab: the tests of the finished lab (labels ending in -solution: the pictures of the"
    say "hanging cloth, the GPU against the CPU) run once every test above passes."
  fi
fi
# BEGIN TEACHER
wait_web_build || status=1
# END TEACHER
python3 "$root/scripts/lab-report" "$root/build" "${results[@]}"
exit "$status"
