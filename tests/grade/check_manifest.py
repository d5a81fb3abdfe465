#!/usr/bin/env python3
"""The lab's facts are written once, in grading/lab.json, and the project agrees with them.
Usage: check_manifest.py PROJECT_ROOT

1. The solution regions of src/ and shaders/ are those of the manifest: the same questions, each
   in the files the manifest names.
2. tests/lab/CMakeLists.txt builds one test program per question of the manifest, and no other.
3. Every teacher's file and folder the manifest names exists (a name that drifts is seen here),
   and every script reads the manifest through the package (none writes the list again).
4. A points file given to scripts/grade --points may change the points, never invent a question.
Seconds: no build.
"""
import re
import sys
import tempfile
from pathlib import Path

root = Path(sys.argv[1]).resolve()
sys.dont_write_bytecode = True
sys.path.insert(0, str(root / "scripts"))
from clothlab_lab import manifest, regions  # noqa: E402

problems = []


def check(condition, message):
    if not condition:
        problems.append(message)
        print("FAILED: " + message, flush=True)


lab = manifest.load(root / manifest.MANIFEST)
found = regions.scan_regions(root)
check(sorted(found) == sorted(lab.ids),
      f"the regions' questions {sorted(found)} are not the manifest's {sorted(lab.ids)}")
for q in lab.questions:
    check(sorted(found.get(q.id, [])) == sorted(q.files),
          f"{q.id}: regions in {sorted(found.get(q.id, []))}, the manifest says {sorted(q.files)}")

cmake = (root / "tests/lab/CMakeLists.txt").read_text()
named = set(re.findall(r"\b(q\d+_[a-z_]+?)(?:_test\.cpp|_runner|_checker)?\b", cmake))
named = {n for n in named if not n.endswith(("_tests", "_test"))}
check("clothlab_read_lab_manifest()" in cmake and not named,
      f"tests/lab/CMakeLists.txt does not build its checkers from the manifest "
      f"(cmake/lab_manifest.cmake), or names tests of its own: {sorted(named)}")
for q in lab.questions:
    check((root / "tests/lab" / f"{q.test}_test.cpp").is_file() or
          any((root / "tests/lab").glob(f"{q.test}*")), f"{q.id}: no tests/lab/{q.test}*")

for name in lab.teacher_files:
    check((root / name).is_file(), f"the manifest's teacher file {name} does not exist")
for folder in lab.teacher_folders:
    check((root / folder).is_dir() or folder == "grading/gradescope/",
          f"the manifest's teacher folder {folder} does not exist")
for script in ("grade", "make-student-version", "mutate-grader", "lab-report"):
    text = (root / "scripts" / script).read_text()
    check("from clothlab_lab import" in text, f"scripts/{script} does not import the package")
    check(not re.search(r"\(\s*\"Q5\"\s*,\s*\"Q6\"", text) and "q5_coupled" not in text,
          f"scripts/{script} writes the list of the questions again")

with tempfile.NamedTemporaryFile("w", suffix=".json") as points:
    points.write('{"questions": {"Q8": 40}, "partial_credit": false}')
    points.flush()
    changed = manifest.with_points(lab, points.name)
    check(changed.points["Q8"] == 40 and not changed.partial_credit and
          changed.points["Q5"] == lab.points["Q5"], "--points does not change Q8's points")
with tempfile.NamedTemporaryFile("w", suffix=".json") as points:
    points.write('{"questions": {"Q99": 1}}')
    points.flush()
    try:
        manifest.with_points(lab, points.name)
        check(False, "a points file naming Q99 is accepted")
    except manifest.ManifestError:
        pass

if problems:
    print(f"\n{len(problems)} problem(s) with grading/lab.json")
    sys.exit(1)
print(f"grading/lab.json: {len(lab.questions)} questions, their regions, their tests and "
      f"{len(lab.teacher_files)} teacher files agree with the project")
