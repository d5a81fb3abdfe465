#!/usr/bin/env python3
"""Every text the scripts show a person goes through the catalogue (docs/translating.md).

    check_scripts_wrapped.py FILE ...

Shell (run.sh, test.sh): a line that prints words with echo or printf instead of say
(scripts/messages.sh). Python (scripts/lab-report, scripts/clothlab_lab/reports.py's table): a
print() of a string literal not wrapped in _(), ngettext() or pgettext(). A literal is words
when it holds two words of two letters or more that are not a name of the code's world (a
variable, an option, a file). A line may say why it is left: `# (not translated: WHY)`. Exit 1
with each line found.
"""
import ast
import re
import sys
from pathlib import Path

MARKER = "# (not translated:"
WORD = re.compile(r"(?<![\w$%./-])[A-Za-z]{2,}(?![\w/(.-])")


def has_words(text):
    text = re.sub(r"\$\{[^}]*\}|\$\w+|--[\w-]+|\S+\.\w+", " ", text)
    return len(WORD.findall(text)) >= 2


def shell_problems(name, text):
    found = []
    for number, line in enumerate(text.split("\n"), 1):
        code = line.split(" #", 1)[0] if MARKER not in line else ""
        match = re.match(r"\s*(?:echo|printf)\s+(?:-\w+\s+)?\"([^\"]*)\"", code)
        if match and has_words(match.group(1)):
            found.append(f"{name}:{number}: '{match.group(1)}' is printed with echo or printf, "
                         "not say (scripts/messages.sh)")
    return found


def python_problems(name, text):
    found = []
    lines = text.split("\n")
    for node in ast.walk(ast.parse(text)):
        if not (isinstance(node, ast.Call) and getattr(node.func, "id", "") == "print"):
            continue
        for argument in node.args:
            for part in ast.walk(argument):
                if isinstance(part, ast.Call) and getattr(part.func, "id", "") in (
                        "_", "ngettext", "pgettext"):
                    break
            else:
                literals = [p.value for p in ast.walk(argument)
                            if isinstance(p, ast.Constant) and isinstance(p.value, str)]
                if any(has_words(literal) for literal in literals) and \
                        MARKER not in lines[node.lineno - 1]:
                    found.append(f"{name}:{node.lineno}: print() shows words outside _()")
    return found


def main():
    problems = []
    for argument in sys.argv[1:]:
        path = Path(argument)
        text = path.read_text(encoding="utf-8")
        if text.startswith("#!/usr/bin/env bash"):
            problems += shell_problems(path.name, text)
        else:
            problems += python_problems(path.name, text)
    for problem in problems:
        print("FAILED: " + problem)
    print(f"{len(sys.argv) - 1} files read, {len(problems)} text(s) shown outside the catalogue")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
