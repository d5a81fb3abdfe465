#!/usr/bin/env python3
"""The documents point at what exists. Usage: check_paths.py PROJECT_ROOT

For README.md and docs/*.md: every relative path they name (a Markdown link, or a path written
as code, like `src/core/spring_mesh.cpp`) exists in the project. No file of the project (the
documents, the sources and their comments, the text the programs print, the scripts, the CMake
files) points at the lab's shared/ folder, which is not part of the project. Paths of things a
run creates (build/, out/, files named by the user) are not checked."""
import os
import re
import sys
from pathlib import Path

root = Path(sys.argv[1]).resolve()
documents = [root / "README.md"] + sorted((root / "docs").glob("*.md"))
GENERATED = ("build/", "build-", "out/", "Testing/", "share/", "/", "~", "$", "../",
             # what scripts/grade makes: in its --out, its --work (the kit) and the scratch
             "students/", "checkers/", "verdicts/", "logs/", "staged/", "copy/", "run/",
             "unpack/")
problems = []
checked = 0
for document in documents:
    if not document.exists():
        problems.append(f"{document.relative_to(root)} is missing")
        continue
    text = document.read_text()
    name = document.relative_to(root)
    if re.search(r"(^|[\s`(\[])(\.\./)?shared/", text):
        problems.append(f"{name} points at shared/, which is not part of the project")
    for match in re.finditer(r"\]\(([^)#\s]+)(#[^)]*)?\)", text):  # [text](path)
        target = match.group(1)
        if re.match(r"[a-z]+:", target):
            continue  # a URL
        checked += 1
        if not (document.parent / target).exists():
            problems.append(f"{name}: link to {target}, which does not exist")
    for match in re.finditer(r"`([\w./-]+)`", text):  # `path/to/file`
        path = match.group(1)
        if "/" not in path or path.startswith(GENERATED) or path.endswith("/..."):
            continue
        if not re.search(r"\.(md|sh|py|cpp|hpp|frag|vert|txt|png|supp|json|comp|glsl)$|/$", path) and \
                not (root / path).is_dir():
            continue  # not a file name (an option value, a fraction...)
        checked += 1
        if not (root / path).exists():
            problems.append(f"{name}: `{path}` does not exist")
# Every other text file of the project: no shared/ either (this file names it to look for it).
SHARED = re.compile(r"(^|[\s`'\"(\[])(\.\./)?shared/")
SKIPPED = {".git", "node_modules", "__pycache__"}
for folder, subfolders, files in os.walk(root):
    here = Path(folder)
    subfolders[:] = sorted(s for s in subfolders if s not in SKIPPED and not (
        here == root and s.startswith(("build", "out"))))  # what a run creates
    for name in sorted(files):
        path = here / name
        if path in documents or path == Path(__file__).resolve():
            continue
        try:
            text = path.read_text()
        except (UnicodeDecodeError, OSError):
            continue  # not text
        for number, line in enumerate(text.splitlines(), 1):
            if SHARED.search(line):
                problems.append(f"{path.relative_to(root)}:{number} points at shared/, which is "
                                f"not part of the project: {line.strip()}")
for p in problems:
    print("FAILED: " + p)
print(f"{checked} paths checked in {len(documents)} documents, {len(problems)} problem(s)")
sys.exit(1 if problems else 0)
