#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image (Ubuntu 22.04, its
# default base image): the packages clothlab needs, the user that runs the student's code, and
# the student copy's question tests built once, with the list of the tests that already pass on
# the stubs (clothlab-grade/guards.json), so that a submission only recompiles its own files.
# scripts/grade --gradescope-bundle fills in the package list from scripts/setup.sh.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
kit=$here/clothlab-grade
user=clothlab-student
export DEBIAN_FRONTEND=noninteractive
started=$(date +%s)

apt-get update -q
# Ubuntu 22.04 and Debian 12 give these packages the same names. ninja: the faster rebuild;
# util-linux and passwd: setpriv and useradd (in both base images; named, for what they give).
apt-get install -y -q --no-install-recommends ninja-build util-linux passwd @PACKAGES@

# The student's code (its unpacking, compile and tests) runs as this user: no home, no login, no
# group of the teacher's. The grader drops to it with setpriv where bubblewrap is refused
# (Docker's seccomp profile, as on Gradescope); CLOTHLAB_GRADE_UID names it to the grader.
id -u "$user" >/dev/null 2>&1 ||
  useradd --system --no-create-home --home-dir /nonexistent --shell /usr/sbin/nologin "$user"
export CLOTHLAB_GRADE_UID=$(id -u "$user")
python3 "$kit/grade" --kit "$kit" --prepare --jobs "$(nproc)"

# The teacher's files: root's alone (run_autograder repeats this before each submission).
chmod 0711 "$here"
chmod 0700 "$here/setup.sh" "$here/run_autograder"
echo "setup.sh: done in $(($(date +%s) - started)) s"
