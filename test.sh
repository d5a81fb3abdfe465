#!/usr/bin/env bash
# Sets clothlab up (missing Debian packages, Release build in build/) and runs every test with
# ctest: physics, command line, off-screen screenshots, GPU path, and the window under Xvfb.
#   ./test.sh [ctest options]       e.g. ./test.sh -R cli
set -euo pipefail
root=$(cd "$(dirname "$0")" && pwd)
"$root/scripts/setup.sh" Release
cd "$root/build"
ctest --output-on-failure --timeout 300 -j 2 "$@"
