#!/usr/bin/env python3
"""Every text the program shows a person goes through the catalogue (docs/translating.md).

    check_wrapped.py PROJECT_ROOT [FILE ...]

Reads the C++ of src/ (or the files given) and flags each string literal that is shown to a
person but not wrapped in tr(), trn(), N_() or ui_label(): the labels and texts of Dear ImGui's
calls and of the panel's widgets, what is printed (printf, fprintf, puts, std::cout, std::cerr,
report), the messages of errors (usage_error, an `error` string, an exception), the question
tests' hints (LAB_EXPECT_*, LAB_ASSERT_*, tests/lab/) and the command line's descriptions (CLI11's add_option, add_flag). A heuristic: a literal is text when it holds a
word (two letters or more) that is not a name of the code's world: an option (--dt), a file
(spring_mesh.cpp), a GL or C++ name (GL_RGBA32F, std::chrono, spring_mesh::step), a unit, a
format directive. Left alone, on purpose:
- the window's log (window_log) and the names the layout probe prints (log_widget): programs read
  them, in English;
- a programming error (std::logic_error, std::out_of_range, and an std::invalid_argument whose
  message starts with the function's name, "gpu_cloth::step: ..."): a developer reads it;
- a line that ends with the comment `// (not translated: WHY)`.
Exit 1 with each literal found, by file and line.
"""
import re
import sys
from pathlib import Path

# Calls whose string literals are shown. (The name, as written before its parenthesis.)
SHOWN = [
    # Dear ImGui: labels, texts, tooltips, window titles, table headers, drawn text
    r"ImGui::(?:Text\w*|BulletText|LabelText|Button|SmallButton|Checkbox|RadioButton|"
    r"Slider\w*|Drag\w*|Input\w*|Combo|BeginCombo|Selectable|CollapsingHeader|TreeNode\w*|"
    r"SetTooltip|Begin|MenuItem|BeginMenu|ProgressBar|TableSetupColumn|ColorButton|"
    r"PlotLines|PlotHistogram)",
    r"(?:->|\.)AddText",
    # the panel's widgets (src/window/widgets.hpp, stage_editors.cpp)
    r"fixed_lines", r"section", r"slider", r"parameter_slider",
    # printed (fprintf and fputs: on stdout or stderr; into a file, a format for programs)
    r"(?:std::)?printf", r"(?:std::)?puts", r"(?:std::)?snprintf", r"report", r"format",
    # errors
    r"usage_error", r"std::runtime_error", r"std::invalid_argument",
    # the question tests' hints (tests/lab/lab_check.hpp)
    r"LAB_(?:EXPECT|ASSERT)_\w+",
    # the command line's descriptions
    r"(?:\w+(?:\.|->))?add_option", r"(?:\w+(?:\.|->))?add_flag",
    r"(?:\w+(?:\.|->))?set_version_flag", r"(?:\w+(?:\.|->))?set_help_flag",
]
# fprintf and fputs name their stream: shown when it is stdout or stderr.
TO_TERMINAL = re.compile(r"(?:std::)?fprintf\s*\(\s*(?:stderr|stdout)\b|"
                         r"(?:std::)?fputs\s*\((?:[^;]*),\s*(?:stderr|stdout)\s*\)")
# Streams and assignments whose literals are shown.
SHOWN_STREAM = re.compile(r"std::(?:cout|cerr)\s*<<")
ERROR_ASSIGNMENT = re.compile(r"\b(?:error|why|reason|message|explanation|advice|legend)\w*\s*[+]?=\s*")
WRAPPERS = ("tr", "trn", "N_", "ui_label")
NOT_SHOWN_CALLS = ("window_log", "log_widget")
MARKER = "// (not translated:"

# A word of the code's world, not of a language.
CODE_WORD = re.compile(
    r"^(?:--[\w-]+|[\w./-]+\.(?:cpp|hpp|h|vert|frag|comp|glsl|png|csv|obj|json|mo|po|md|txt|ttf)"
    r"|GL_\w+|EGL_\w+|GLFW_\w+|\w+::[\w:]+|\w*_\w*|[A-Z]{2,}\w*|%\S*|\w+\(\)|https?://\S+)$")
# Units and symbols that are the same in every language.
UNITS = {"s", "ms", "us", "ns", "m", "kg", "N", "J", "px", "Hz", "rad", "x", "dt", "mu", "K",
         "Kw", "rgb", "xyz", "gpu", "cpu", "egl", "osmesa", "auto", "none", "corners",
         "clothlab", "clothlab-window", "OpenGL", "WebGL2", "GLEW", "GLFW", "OSMesa", "EGL",
         "Mesa", "Xvfb", "omega"}


def literals_and_code(text):
    """The code with comments blanked and each string literal replaced by a placeholder; and the
    literals (line, text, start offset in the blanked code)."""
    out, found, i, line = [], [], 0, 1
    while i < len(text):
        c = text[i]
        if text.startswith("//", i):
            end = text.find("\n", i)
            end = len(text) if end < 0 else end
            comment = text[i:end]
            out.append(comment if comment.startswith(MARKER) else " " * len(comment))
            i = end
        elif text.startswith("/*", i):
            end = text.find("*/", i) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            line += text[i:end].count("\n")
            i = end
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) + len(m.group(1)) + 2
            out.append('""')
            line += text[i:end].count("\n")
            i = end
        elif c == '"' and (i == 0 or text[i - 1] != "'"):
            j = i + 1
            while text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            found.append((line, text[i + 1:j], sum(len(s) for s in out)))
            out.append('"' + "S" * (j - i - 1) + '"')
            i = j + 1
        elif c == "'" and text.startswith("'\"'", i):
            out.append("'x'")
            i += 3
        else:
            if c == "\n":
                line += 1
            out.append(c)
            i += 1
    return "".join(out), found


def is_text(literal):
    words = re.findall(r"[^\s,;:()\[\]{}'\"=<>|/+*]+", literal.replace("\\n", " "))
    for word in words:
        if CODE_WORD.match(word) or word in UNITS:
            continue
        if re.search(r"[A-Za-zÀ-ÿ]{2,}", word):
            return True
    return False


def enclosing_calls(code, offset):
    """The names of the calls whose parentheses hold `offset`, innermost first."""
    names, depth, i = [], 0, offset
    while i > 0:
        i -= 1
        c = code[i]
        if c in ")]}":
            depth += 1
        elif c in "([{":
            if depth > 0:
                depth -= 1
                continue
            m = re.search(r"((?:\w+(?:\.|->|::))*\w+)\s*$", code[:i])
            names.append((m.group(1) if m else "", code[i]))
        elif c == ";" and depth == 0:
            break
    return names


def statement_start(code, offset):
    start = max(code.rfind(";", 0, offset), code.rfind("{", 0, offset), code.rfind("}", 0, offset))
    return code[start + 1:offset]


def first_literal(found, start, end):
    for _, literal, offset in found:
        if start <= offset < end:
            return literal
    return ""


def check(path, text):
    code, found = literals_and_code(text)
    problems = []
    for line, literal, offset in found:
        if not is_text(literal):
            continue
        end_of_line = code.find("\n", offset)
        statement = statement_start(code, offset)
        if MARKER in statement or MARKER in code[offset:end_of_line if end_of_line >= 0 else
                                                  len(code)]:
            continue
        calls = enclosing_calls(code, offset)
        names = [name for name, _ in calls]
        if any(name.split("::")[-1].split(".")[-1] in WRAPPERS for name in names):
            continue
        if any(name.split("::")[-1] in NOT_SHOWN_CALLS for name in names):
            continue
        if re.search(r"throw\s+std::(?:logic_error|out_of_range)", statement):
            continue
        thrown = re.search(r"throw\s+std::invalid_argument", statement)
        if thrown and re.match(r"\w+(?:::\w+)*: ", first_literal(
                found, offset - len(statement) + thrown.start(), offset + 1)):
            continue  # a programming error, named by its function
        shown = any(re.fullmatch(pattern, name) for name in names for pattern in SHOWN)
        shown = shown or bool(SHOWN_STREAM.search(statement) or TO_TERMINAL.search(statement))
        shown = shown or bool(ERROR_ASSIGNMENT.search(statement)) or "throw" in statement
        shown = shown or "CLI::App" in statement
        if shown:
            problems.append(f"{path}:{line}: \"{literal}\" is shown but not in the catalogue: "
                            "wrap it in tr() (or say why not: // (not translated: ...))")
    return problems


def main():
    root = Path(sys.argv[1]).resolve()
    files = [Path(f) for f in sys.argv[2:]] or sorted(
        p for p in (root / "src").rglob("*") if p.suffix in (".cpp", ".hpp"))
    problems = []
    for path in files:
        problems += check(path.relative_to(root) if path.is_absolute() else path,
                          path.read_text(encoding="utf-8"))
    for problem in problems:
        print("FAILED: " + problem)
    print(f"{len(files)} files read, {len(problems)} text(s) shown but not in the catalogue")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
