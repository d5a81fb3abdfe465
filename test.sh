#!/usr/bin/env bash
# Sets clothlab up (missing Debian packages, Release build in build/) and runs every test with
# ctest: physics, command line, off-screen screenshots, GPU path, the window under Xvfb, and the
# lab's grader (labels q5 ... q13), then prints the table of the lab's questions.
#   ./test.sh [ctest options]       e.g. ./test.sh -L q8   (one question of the lab)
set -euo pipefail
root=$(cd "$(dirname "$0")" && pwd)
"$root/scripts/setup.sh" Release
cd "$root/build"
status=0
ctest --output-on-failure --timeout 300 -j 2 --output-junit "$root/build/test-results.xml" "$@" ||
  status=$?
python3 "$root/scripts/lab-report" "$root/build" "$root/build/test-results.xml"
exit "$status"
