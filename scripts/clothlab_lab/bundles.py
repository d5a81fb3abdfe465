"""The Gradescope bundle: setup.sh, run_autograder and the grader's kit (the generated student
copy, the stubs, the lab's manifest and this package), never the solution."""
import re
import shutil
import tempfile
import zipfile
from pathlib import Path

from . import grading
from .manifest import ROOT

SETUP_SH = """#!/usr/bin/env bash
# Gradescope runs this once, when it builds the autograder's image: the Debian/Ubuntu packages
# of clothlab, then the student copy's question tests, built once (clothlab-grade/copy).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
apt-get install -y -q --no-install-recommends ninja-build bubblewrap git @PACKAGES@
python3 "$here/clothlab-grade/grade" --kit "$here/clothlab-grade" --prepare
"""


RUN_AUTOGRADER = """#!/usr/bin/env bash
# Gradescope runs this for each submission: the student's files from /autograder/submission
# (a copy of the project, an archive of one, or the files themselves), graded by the teacher's
# tests, the result in /autograder/results/results.json. AUTOGRADER_ROOT moves /autograder (for
# a trial run elsewhere); CLOTHLAB_GRADE_KIT names an already built kit.
set -uo pipefail
root=${AUTOGRADER_ROOT:-/autograder}
# Gradescope copies this file to /autograder/run_autograder; the bundle is in /autograder/source.
here=$root/source
[ -d "$here/clothlab-grade" ] || here=$(cd "$(dirname "$0")" && pwd)
kit=${CLOTHLAB_GRADE_KIT:-$here/clothlab-grade}
mkdir -p "$root/results"
python3 "$here/clothlab-grade/grade" --kit "$kit" "$root/submission" --name submission \\
  --out "$root/results/clothlab" --gradescope-results "$root/results/results.json"
"""


def debian_packages():
    text = (ROOT / "scripts/setup.sh").read_text()
    block = re.search(r"^packages=\((.*?)^\)", text, re.MULTILINE | re.DOTALL)
    return " ".join(word for line in block.group(1).splitlines()
                    for word in line.split("#")[0].split()) if block else ""


def make_bundle(path):
    with tempfile.TemporaryDirectory(prefix="clothlab-bundle-") as tmp:
        kit = Path(tmp) / "clothlab-grade"
        grading.generate_kit(kit)
        shutil.copy2(ROOT / "scripts/grade", kit / "grade")
        shutil.copytree(Path(__file__).resolve().parent, kit / "clothlab_lab",
                        ignore=shutil.ignore_patterns("__pycache__"))
        files = {"setup.sh": SETUP_SH.replace("@PACKAGES@", debian_packages()),
                 "run_autograder": RUN_AUTOGRADER}
        with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as bundle:
            for name, text in files.items():
                info = zipfile.ZipInfo(name)
                info.external_attr = 0o100755 << 16
                bundle.writestr(info, text)
            for file in sorted(kit.rglob("*")):
                if file.is_file():
                    info = zipfile.ZipInfo(file.relative_to(Path(tmp)).as_posix())
                    info.external_attr = (0o100000 | (file.stat().st_mode & 0o777)) << 16
                    info.compress_type = zipfile.ZIP_DEFLATED
                    bundle.writestr(info, file.read_bytes())
    print(f"Gradescope autograder written to {path}: upload it as the assignment's "
          "autograder (setup.sh, run_autograder, clothlab-grade/)")
