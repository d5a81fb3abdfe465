#!/usr/bin/env python3
"""The keys the README lists are the keys the window handles. Usage: check_keys.py PROJECT_ROOT

The README's "Keys and mouse" table is the one key table of the project: every key in its first
column (`1 / 2 / 3` is three keys) must be handled by the window's key callback
(`case GLFW_KEY_...:` in src/window/window_app.cpp), every key handled there must be listed,
and no other document may hold a second key table."""
import re
import sys
from pathlib import Path

root = Path(sys.argv[1]).resolve()
NAMES = {"space": "SPACE", "esc": "ESCAPE", "escape": "ESCAPE", "enter": "ENTER", "tab": "TAB"}
problems = []

readme = (root / "README.md").read_text()
section = re.search(r"^## Keys and mouse\n(.*?)(?=^## |\Z)", readme, re.MULTILINE | re.DOTALL)
documented = set()
if not section:
    problems.append("README.md has no section '## Keys and mouse'")
else:
    table = re.search(r"^\| key \| action \|\n\|[-| ]+\|\n((?:\|.*\|\n)+)", section.group(1),
                      re.MULTILINE)
    if not table:
        problems.append("README.md's 'Keys and mouse' has no '| key | action |' table")
    else:
        for row in table.group(1).splitlines():
            cell = row.strip("|").split("|")[0].strip()
            for key in cell.split("/"):
                key = key.strip()
                documented.add(NAMES.get(key.lower(), key.upper()))

source = (root / "src/window/window_app.cpp").read_text()
handled = set(re.findall(r"case GLFW_KEY_(\w+):", source))
for key in sorted(documented - handled):
    problems.append(f"README.md lists the key {key}, which the window does not handle "
                    "(no 'case GLFW_KEY_" + key + ":' in src/window/window_app.cpp)")
for key in sorted(handled - documented):
    problems.append(f"the window handles the key {key}, which README.md's key table does not "
                    "list")
for document in sorted((root / "docs").glob("*.md")):
    if re.search(r"^\| key \| action \|", document.read_text(), re.MULTILINE):
        problems.append(f"{document.relative_to(root)} holds a second key table: keep the one "
                        "of README.md")

for p in problems:
    print("FAILED: " + p)
print(f"{len(documented)} keys documented, {len(handled)} handled, {len(problems)} problem(s)")
sys.exit(1 if problems or not handled else 0)
