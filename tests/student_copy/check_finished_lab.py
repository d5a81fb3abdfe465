#!/usr/bin/env python3
"""A finished lab ends green. Usage: check_finished_lab.py PROJECT_ROOT

Writes a student copy with every question answered (scripts/make-student-version --keep, every
question), runs its own ./test.sh on the tests that depend on the student's code (the question
labels q5 ... q13 and the labels ending in -solution: the tests of the table's rows) and
requires exit 0 and the table's every row "done". The other tests do not depend on the
student's code: check_student_copy.py runs them in the copy with every question a stub and in
the states of the lab.

The copy's build reuses the compiler cache of the teacher's build and of check_student_copy.py
(ccache): only the files that hold a question's region compile again.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(sys.argv[1]).resolve() if len(sys.argv) > 1 else Path(__file__).resolve().parents[2]
sys.dont_write_bytecode = True
sys.path.insert(0, str(ROOT / "scripts"))
from clothlab_lab import manifest  # noqa: E402 (the lab's facts: grading/lab.json)

QUESTIONS = list(manifest.load(ROOT / manifest.MANIFEST).ids)  # "Q5", ... in the lab's order
# The table's rows: the question labels and the labels of the tests that need every answer.
TABLE_LABELS = r"^q[0-9]+$|-solution$"


def main():
    root = ROOT
    work = Path(tempfile.mkdtemp(prefix="clothlab-finished-lab-"))
    dest = work / "clothlab-student"
    problems = []
    start = time.monotonic()
    try:
        made = subprocess.run([root / "scripts/make-student-version", dest] +
                              [a for q in QUESTIONS for a in ("--keep", q)],
                              capture_output=True, text=True)
        if made.returncode != 0:
            print(made.stdout + made.stderr)
            return 1
        tested = subprocess.run([dest / "test.sh", "-L", TABLE_LABELS], cwd=dest,
                                capture_output=True, text=True, timeout=2400)
        output = tested.stdout + tested.stderr
        table = output[output.find("The lab, question by question"):]
        print(table)
        rows = [line for line in table.splitlines()[2:] if re.match(r"^(Q\d+|all)\s", line)]
        if tested.returncode != 0:
            failed = re.findall(r"^\s*\d+ - (\S+) \(", tested.stdout, re.MULTILINE)
            problems.append(f"./test.sh exits {tested.returncode} in a copy with every question "
                            f"answered; failed: {', '.join(failed) or '?'}\n{output[-3000:]}")
        if len(rows) != len(QUESTIONS) + 1:
            problems.append(f"the table has {len(rows)} rows, expected one per question and "
                            f"'all':\n{table}")
        for row in rows:
            if not row.rstrip().endswith(" done"):
                problems.append(f"a row of the table is not done: {row.strip()}")
        print(f"the finished copy written, built and tested in {time.monotonic() - start:.0f} s")
    finally:
        if not problems:
            shutil.rmtree(work, ignore_errors=True)
        else:
            print(f"(the copy is left in {work} to look at)")
    for problem in problems:
        print("FAILED: " + problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
