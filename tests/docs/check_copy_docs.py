#!/usr/bin/env python3
"""The student copy's documents offer only what the copy has. Usage: check_copy_docs.py ROOT

In the teacher's tree (scripts/make-student-version is there) it writes the student copy into a
temporary folder and checks that copy; in the student copy it checks the tree itself. The
copy's README.md, docs/*.md and the header comments of test.sh and run.sh may not name:
- a file or folder that the copy leaves out (the teacher's files: answers, teaching notes, the
  grader's scripts, scripts/benchmark-web, the compute shader's step, ...);
- a path the copy does not have: `--backend gpu-compute` (no compute shader step) and
  `--backend cpu-parallel`, `--threads` (the parallel path is the teacher's);
- a note to the developers: an issue number, "What the README should change".
Each hit is listed with its file and line.
"""
import json
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

# The teacher's files and folders (what make-student-version leaves out), for a copy that
# cannot ask the generator.
LEFT_OUT = ("docs/answers.md", "docs/teaching.md", "scripts/make-student-version",
            "scripts/mutate-grader", "scripts/grade", "scripts/grade-benchmark",
            "scripts/benchmark-web", "shaders/gpu_compute_step.comp", "tests/student_copy",
            "tests/model", "tests/mutation", "tests/grade", "tests/web", "grading/gradescope/")
NOTES = re.compile(r"\b[Ii]ssues? \d+|What the README should change")


def generator_lists(root):
    """The teacher's files and folders that the lab's manifest (grading/lab.json) names."""
    lab = json.loads((root / "grading/lab.json").read_text())
    return tuple(lab.get("teacher_files", ())) + tuple(lab.get("teacher_folders", ()))


def header_comment(path):
    """The first comment block of a shell script (its usage), as text."""
    lines = []
    for line in path.read_text().splitlines()[1:]:
        if not line.startswith("#"):
            break
        lines.append(line)
    return "\n".join(lines)


def check(copy, left_out):
    documents = {"README.md": (copy / "README.md").read_text()}
    for document in sorted((copy / "docs").glob("*.md")):
        documents[f"docs/{document.name}"] = document.read_text()
    for script in ("test.sh", "run.sh"):
        documents[f"{script} (header)"] = header_comment(copy / script)
    names = [n.rstrip("/") for n in left_out if not (copy / n.rstrip("/")).exists()]
    options = []
    if not (copy / "shaders/gpu_compute_step.comp").exists():
        options.append("gpu-compute")
    if not (copy / "src/core/cloth_parallel.cpp").exists():  # the stand-in is built instead
        options += ["cpu-parallel", "--threads"]
    problems = []
    for name, text in documents.items():
        for number, line in enumerate(text.splitlines(), 1):
            for missing in names:
                if re.search(r"(?<![\w/.-])" + re.escape(missing) + r"(?![\w.-])", line):
                    problems.append(f"{name}:{number}: names {missing}, which the copy leaves "
                                    f"out: {line.strip()[:100]}")
            for option in options:
                if re.search(r"(?<![\w-])" + re.escape(option) + r"(?![\w-])", line):
                    problems.append(f"{name}:{number}: offers {option}, which the copy does "
                                    f"not have: {line.strip()[:100]}")
            note = NOTES.search(line)
            if note:
                problems.append(f"{name}:{number}: a note to the developers ('{note.group(0)}')"
                                f": {line.strip()[:100]}")
    return problems, len(documents)


def main():
    root = Path(sys.argv[1]).resolve()
    work = None
    try:
        if (root / "scripts/make-student-version").exists():
            left_out = tuple(sorted(set(LEFT_OUT + generator_lists(root))))
            work = Path(tempfile.mkdtemp(prefix="clothlab-copy-docs-"))
            made = subprocess.run([root / "scripts/make-student-version", work / "copy"],
                                  capture_output=True, text=True)
            if made.returncode != 0:
                print(made.stdout + made.stderr)
                return 1
            copy = work / "copy"
        else:
            left_out, copy = LEFT_OUT, root
        problems, count = check(copy, left_out)
    finally:
        if work:
            shutil.rmtree(work, ignore_errors=True)
    for problem in problems:
        print("FAILED: " + problem)
    print(f"{count} documents of the student copy checked, {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
