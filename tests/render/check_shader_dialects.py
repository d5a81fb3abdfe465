#!/usr/bin/env python3
"""Every shader compiles in each GL dialect it is loaded in. Usage: check_shader_dialects.py ROOT

The files of shaders/ have no #version line: src/gl/shader.cpp puts one before them, GLSL 3.30
core on the desktop (4.30 core for the compute shaders) and GLSL ES 3.00 with its precision
lines in the web build (WebGL2). This check builds each shader's source as the loader does (the
header read from shader.cpp itself, "#line 1 0", the one-level #include expanded) and compiles it
with glslangValidator: every vertex and fragment shader as GLSL ES 3.00 and as GLSL 3.30 core,
every compute shader as GLSL 4.30 core. A failure names the file, the dialect and the compiler's
message, with the file's own line numbers."""
import ast
import re
import shutil
import subprocess
import sys
from pathlib import Path

root = Path(sys.argv[1]).resolve()
shaders = root / "shaders"
loader = root / "src" / "gl" / "shader.cpp"

validator = shutil.which("glslangValidator")
if validator is None:
    print("glslangValidator is not installed; scripts/setup.sh installs glslang-tools")
    sys.exit(1)


def header(name):
    """The text of the constant `name` in shader.cpp: its string literals, joined."""
    match = re.search(rf"\b{name}\s*=\s*((?:\"(?:[^\"\\]|\\.)*\"\s*)+);", loader.read_text())
    if match is None:
        sys.exit(f"{loader.relative_to(root)}: no constant {name} (the shaders' header)")
    return "".join(ast.literal_eval(literal) for literal in
                   re.findall(r"\"(?:[^\"\\]|\\.)*\"", match.group(1)))


# (dialect as a failure names it, header, stages) for each kind of file, as shader.cpp loads them.
DESKTOP = ("GLSL 3.30 core (desktop)", header("desktop_header"))
WEB = ("GLSL ES 3.00 (web)", header("web_header"))
COMPUTE = ("GLSL 4.30 core (desktop compute)", header("desktop_compute_header"))
DIALECTS = {".vert": ("vert", [DESKTOP, WEB]), ".frag": ("frag", [DESKTOP, WEB]),
            ".comp": ("comp", [COMPUTE])}


def expand_includes(path, text):
    """shader.cpp's expand_includes: a line `#include "FILE"` becomes FILE between #line lines,
    so that messages give the including file's line numbers (the included file is string 1)."""
    out = []
    for number, line in enumerate(text.splitlines(), start=1):
        match = re.match(r'#include "([^"]+)"', line)
        if match is None:
            out.append(line + "\n")
            continue
        included = (shaders / match.group(1)).read_text()
        if not included.endswith("\n"):
            included += "\n"
        out.append(f"#line 1 1\n{included}#line {number + 1} 0\n")
    return "".join(out)


problems = []
checked = 0
files = sorted(p for p in shaders.iterdir() if p.suffix in DIALECTS)
for path in files:
    name = path.relative_to(root)
    text = path.read_text()
    if text.startswith("#version"):
        problems.append(f"{name}: begins with a #version line, which the loader adds (remove it)")
        continue
    stage, dialects = DIALECTS[path.suffix]
    body = "#line 1 0\n" + expand_includes(path, text)
    for dialect, first_lines in dialects:
        checked += 1
        result = subprocess.run([validator, "--stdin", "-S", stage], input=first_lines + body,
                                capture_output=True, text=True)
        if result.returncode != 0:
            log = "\n".join("    " + line for line in (result.stdout + result.stderr).splitlines()
                            if line.strip() and line.strip() != "stdin")
            problems.append(f"{name} does not compile as {dialect}:\n{log}")

if not files:
    problems.append(f"no shader found in {shaders}")
if problems:
    print("\n".join(problems))
    sys.exit(1)
print(f"{checked} compilations of {len(files)} shaders, each in its dialects: all compile")
