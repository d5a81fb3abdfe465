"""The solution regions of the teacher's sources, and the student copy written from them.

In the sources (C++, GLSL, CMake, shell) a solution region reads

    // BEGIN SOLUTION Q8: structural springs
    // STUDENT(handout)| // TODO Q8 (structural springs): the task, as the handout states it
    // STUDENT(guided)| // TODO Q8 (structural springs): the same, step by step
    // STUDENT| stub code that compiles and runs
    ...the teacher's code...
    // END SOLUTION Q8

and becomes, in the student copy, its STUDENT| lines and the STUDENT(LEVEL)| lines of the chosen
hint level (the prefix removed, the indentation kept). Lines between BEGIN TEACHER and END
TEACHER are left out, and so are the teacher's files (grading/lab.json); a line `// COPY| code`
outside a region is a comment in the teacher's copy and `code` in the student's. scripts/
make-student-version is the command; scripts/grade and scripts/mutate-grader read the regions
through this module.
"""
import gettext
import hashlib
import os
import re
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from .manifest import MARKER_FILE

HINT_LEVELS = ("handout", "guided")
TEXT_SUFFIXES = {".cpp", ".hpp", ".h", ".frag", ".vert", ".glsl", ".txt", ".cmake", ".md",
                 ".html", ".sh", ".py", ".json", ".yml", ".yaml", ""}
SEARCHED_FOR_LEFTOVERS = ("src/", "shaders/")  # where no solution line may survive

BEGIN = re.compile(r"^\s*(//|#)\s*BEGIN SOLUTION (Q\d+)\s*(?::\s*(.*))?$")
END = re.compile(r"^\s*(//|#)\s*END SOLUTION (Q\d+)\s*$")
STUDENT = re.compile(r"^(\s*)(?://|#) STUDENT(?:\((\w+)\))?\|(?: (.*))?$")
COPY = re.compile(r"^(\s*)(?://|#) COPY\|(?: (.*))?$")
# In Markdown, a line <!-- COPY| text --> is `text` in the copy.
COPY_MARKDOWN = re.compile(r"^(\s*)<!-- COPY\|(?: (.*?))? -->$")
TEACHER_BEGIN = re.compile(r"^\s*(<!--|//|#)\s*BEGIN TEACHER\b")
TEACHER_END = re.compile(r"^\s*(<!--|//|#)\s*END TEACHER\b")
TASKS_LINE = "<!-- YOUR TASKS -->"
# A hint's comment line: its indentation, its comment leader, its words.
HINT_COMMENT = re.compile(r"^(\s*)(//|#) ?(.*)$")
# The catalogues' context of the TODOs and the regions' titles (po/<lang>.po): the student copy
# in another language is written from them, and leaves them out of its own catalogues.
HINT_CONTEXT = "TODO"


class RegionError(Exception):
    pass


def project_files(root):
    """The project's files: what git tracks (its index), never a walk of the folder: a build,
    a compiler's cache (.ccache/), an object file or any other untracked file of the teacher's
    checkout stays out of the student copy and the Gradescope bundle, ignored or not. A new
    file of the teacher's joins the copy once `git add`ed. RegionError outside a git checkout."""
    try:
        out = subprocess.run(["git", "-C", str(root), "ls-files", "-z", "--cached"], check=True,
                             capture_output=True).stdout
    except (OSError, subprocess.CalledProcessError) as error:
        raise RegionError(f"{root}: not a git checkout (the student copy is made from what git "
                          f"tracks): {getattr(error, 'stderr', b'') or error}")
    names = sorted({n for n in out.decode("utf-8", "surrogateescape").split("\0") if n})
    return [n for n in names if (root / n).is_file() and not (root / n).is_symlink()]


def enclosing_function(lines, index):
    """The name of the function a region stands in: the nearest definition line above it (a line
    at column 0 that opens a parameter list), e.g. spring_mesh::compute_force or main."""
    for line in reversed(lines[:index]):
        if line[:1].strip() and not line.startswith(("//", "#", "}", " ", "\t")) and "(" in line:
            match = re.search(r"([\w:~]+)\s*\(", line)
            if match:
                return match.group(1)
    return "?"


def hint_text(lines):
    """A run of hint lines (comments) as the catalogues hold it: their words, a line each, the
    indentation and the comment leader left out; None when a line is not a comment."""
    matches = [HINT_COMMENT.match(line) for line in lines]
    if not lines or not all(matches):
        return None
    return "\n".join(m.group(3).rstrip() for m in matches)


def hint_lines(first_line, text):
    """The lines of a hint's words `text`, indented and led as `first_line` is."""
    indent, leader = HINT_COMMENT.match(first_line).group(1, 2)
    return [f"{indent}{leader} {words}".rstrip() for words in text.split("\n")]


def hint_runs(lines):
    """The runs of a region's STUDENT(LEVEL)| lines, each a list of its lines without the prefix:
    what one entry of the catalogues translates."""
    runs, current, level_of_run = [], [], None
    for line in lines + [""]:
        student = STUDENT.match(line)
        level = student.group(2) if student else None
        if current and level != level_of_run:
            runs.append(current)
            current = []
        if level is not None:
            current.append(student.group(1) + (student.group(3) or ""))
            level_of_run = level
    return runs


def hint_messages(root, folders=SEARCHED_FOR_LEFTOVERS):
    """(file, text) of every TODO and every region's title of root's src/ and shaders/: the
    texts a student copy in another language takes from the catalogues."""
    found = []
    for folder in folders:
        for path in sorted((root / folder).rglob("*")):
            if not path.is_file() or path.suffix not in TEXT_SUFFIXES:
                continue
            name = path.relative_to(root).as_posix()
            lines = path.read_text(encoding="utf-8").split("\n")
            region = []
            for line in lines:
                begin = BEGIN.match(line)
                if begin:
                    region = [line]
                    if begin.group(3):
                        found.append((name, begin.group(3).strip()))
                elif region:
                    region.append(line)
                    if END.match(line):
                        found += [(name, hint_text(run)) for run in hint_runs(region)
                                  if hint_text(run) is not None]
                        region = []
    return found


def transform(name, text, keep, regions, hints="handout", questions=None, translate=None):
    """The student version of one text file at the given hint level; appends (question, title,
    file, function, solution lines, stub lines) for every region to `regions`. The stub lines
    are those of the chosen level (and the common STUDENT| lines). `translate`, when given,
    takes a hint's words or a region's title (hint_text) and gives them in the copy's language."""
    lines = text.split("\n")
    out = []
    i = 0
    in_teacher = False
    while i < len(lines):
        line = lines[i]
        if TEACHER_BEGIN.match(line):
            if in_teacher:
                raise RegionError(f"{name}:{i + 1}: BEGIN TEACHER inside a teacher block")
            in_teacher = True
            i += 1
            continue
        if TEACHER_END.match(line):
            if not in_teacher:
                raise RegionError(f"{name}:{i + 1}: END TEACHER without BEGIN TEACHER")
            in_teacher = False
            i += 1
            continue
        if in_teacher:
            i += 1
            continue
        begin = BEGIN.match(line)
        if END.match(line):
            raise RegionError(f"{name}:{i + 1}: END SOLUTION without BEGIN SOLUTION")
        if STUDENT.match(line):
            raise RegionError(f"{name}:{i + 1}: a STUDENT| line outside a solution region")
        copy = COPY.match(line) or (name.endswith(".md") and COPY_MARKDOWN.match(line))
        if copy:
            out.append(copy.group(1) + (copy.group(2) or ""))
            i += 1
            continue
        if not begin:
            out.append(line)
            i += 1
            continue
        question, title = begin.group(2), (begin.group(3) or "").strip()
        if questions is not None and question not in questions:
            raise RegionError(f"{name}:{i + 1}: {question} is not a question that asks for code "
                              f"({', '.join(questions)})")
        if translate is not None and title:
            title = translate(title, f"{name}:{i + 1}")
        start = i
        stub, solution = [], []
        run = []  # the current run of the chosen level's hint lines
        levels_seen = set()
        i += 1
        while True:
            if i >= len(lines):
                raise RegionError(f"{name}:{start + 1}: BEGIN SOLUTION {question} never ends")
            inner = lines[i]
            end = END.match(inner)
            if end:
                if end.group(2) != question:
                    raise RegionError(f"{name}:{i + 1}: END SOLUTION {end.group(2)} closes "
                                      f"BEGIN SOLUTION {question} of line {start + 1}")
                break
            if BEGIN.match(inner):
                raise RegionError(f"{name}:{i + 1}: a solution region inside another")
            student = STUDENT.match(inner)
            if student:
                level = student.group(2)
                if level is not None and level not in HINT_LEVELS:
                    raise RegionError(f"{name}:{i + 1}: STUDENT({level})|: the hint levels are "
                                      f"{', '.join(HINT_LEVELS)}")
                levels_seen.add(level)
                line_of_stub = student.group(1) + (student.group(3) or "")
                if level is not None and level == hints and translate is not None:
                    run.append(line_of_stub)
                    following = STUDENT.match(lines[i + 1]) if i + 1 < len(lines) else None
                    if not following or following.group(2) != level:
                        words = hint_text(run)
                        if words is None:
                            raise RegionError(f"{name}:{i + 1}: a hint line that is not a "
                                              "comment: it cannot be translated")
                        stub += hint_lines(run[0], translate(words, f"{name}:{i + 1}"))
                        run = []
                elif level is None or level == hints:
                    stub.append(line_of_stub)
            elif COPY.match(inner):
                raise RegionError(f"{name}:{i + 1}: a COPY| line inside a solution region")
            else:
                solution.append(inner)
            i += 1
        if not stub:
            raise RegionError(f"{name}:{start + 1}: region {question} has no STUDENT| line: "
                              "the student would see nothing there")
        if levels_seen - {None} and levels_seen - {None} != set(HINT_LEVELS):
            raise RegionError(f"{name}:{start + 1}: region {question} has hints for "
                              f"{', '.join(sorted(levels_seen - {None}))} only: give every level "
                              f"({', '.join(HINT_LEVELS)})")
        if not any("TODO " + question in s for s in stub):
            raise RegionError(f"{name}:{start + 1}: the stub of {question} names no 'TODO "
                              f"{question}'")
        regions.append((question, title, name, enclosing_function(lines, start), solution, stub))
        out.extend(solution if question in keep else stub)
        i += 1  # past END
    if in_teacher:
        raise RegionError(f"{name}: BEGIN TEACHER never ends")
    return "\n".join(out)


def significant(line):
    """A solution line worth searching for: code, not a brace, a comment or a blank."""
    s = line.strip()
    keyword_only = re.fullmatch(r"[{}\s]*(else|continue|break|return)?[\s{};]*", s)
    return (len(s) >= 8 and not s.startswith(("//", "#", "*")) and re.search(r"[A-Za-z]", s)
            and not keyword_only)


def normalised_code(text, keep_comments=False):
    """Code as the answer patterns see it: comments removed (unless keep_comments), then every
    white space, and lower case."""
    if not keep_comments:
        text = re.sub(r"/\*.*?\*/", "", text, flags=re.DOTALL)
        text = re.sub(r"//[^\n]*", "", text)
        text = re.sub(r"(?m)^\s*#(?!\s*(version|include|define|if|endif|pragma|extension))[^\n]*",
                      "", text)
    return re.sub(r"\s+", "", text).lower()


def answers_in(text, questions, answers, todo_answers=(), keep_comments=False):
    """The (question, what) of every answer of `questions` found in text: `answers` are
    (question, pattern over normalised code, what it is); `todo_answers` the same in words,
    searched when keep_comments."""
    code = normalised_code(text, keep_comments)
    patterns = tuple(answers) + (tuple(todo_answers) if keep_comments else ())
    return [(q, what) for q, pattern, what in patterns
            if q in questions and re.search(pattern.lower(), code)]


def todo_texts(regions, question):
    """The stub lines of a question's regions, as one text."""
    return "\n".join(line for r in regions if r[0] == question for line in r[5])


def tasks_section(regions, questions, translations=gettext.NullTranslations()):
    """README's section of the tasks, in the language of `translations` (the catalogue's texts
    of context "TODO", like the TODOs: the copy's catalogues leave them out)."""
    pgettext = translations.pgettext

    order = {q: n for n, q in enumerate(questions)}
    rows = []
    seen = set()
    # Question by question, the C++ before the shaders.
    for question, title, name, function, _solution, _stub in sorted(
            regions, key=lambda r: (order[r[0]], r[2].startswith("shaders/"))):
        key = (question, title, name)
        if key in seen:
            continue
        seen.add(key)
        rows.append(f"| {question} | {title} | `{name}` | `{function}` | `./test.sh -L "
                    f"{question.lower()}` |")
    return "\n".join([
        "## " + pgettext("TODO", "Your tasks"),
        "",
        # TRANSLATORS: Markdown, wrapped at 100 columns; `TODO Qn` and the commands stay as they
        # are.
        pgettext("TODO", "The code of these questions is yours to write. Each place holds a "
                 "`TODO Qn` comment that\nstates the task and what is at hand, above a stub that "
                 "compiles and runs (so the program\nworks from the start: the cloth falls under "
                 "gravity alone until questions 6 and 8 are\ndone). `./test.sh -L q8` checks one "
                 "answer; `./test.sh` checks everything and ends with a\ntable of the questions, "
                 "done or to do. `docs/lab.md` walks through the lab."),
        "",
        # TRANSLATORS: the header of the table of the tasks, Markdown: keep the five columns.
        pgettext("TODO", "| question | what | file | function | check |"),
        "|---|---|---|---|---|",
        *rows,
    ])


def write_if_changed(path, data, mode):
    if path.exists() and path.read_bytes() == data:
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)
    os.chmod(path, mode)


def scan_regions(root, folders=SEARCHED_FOR_LEFTOVERS):
    """{question: [file, ...]} of the BEGIN SOLUTION lines of root's src/ and shaders/."""
    found = {}
    for folder in folders:
        for path in sorted((root / folder).rglob("*")):
            if not path.is_file():
                continue
            try:
                lines = path.read_text(encoding="utf-8").splitlines()
            except (UnicodeDecodeError, OSError):
                continue
            name = path.relative_to(root).as_posix()
            for line in lines:
                match = BEGIN.match(line)
                if match and name not in found.setdefault(match.group(2), []):
                    found[match.group(2)].append(name)
    return found


@dataclass
class Answers:
    """The answers that no copy may hold outside the student's places (the generator's)."""
    code: tuple = ()  # (question, pattern over normalised code, what)
    todo: tuple = ()  # (question, pattern over a TODO's words, what)
    scope: tuple = ()  # the folders and files searched
    allowed: dict = field(default_factory=dict)  # (question, file): why it may hold one


def catalogue(root, language):
    """The translations of po/<language>.po (Python's gettext over the catalogue msgfmt
    compiles), or None for English, the sources' own language. RegionError when there is no such
    catalogue or msgfmt is missing."""
    if language == "en":
        return None
    po = root / "po" / f"{language}.po"
    if not po.is_file():
        known = sorted(p.stem for p in (root / "po").glob("*.po"))
        raise RegionError(f"--lang {language}: no catalogue po/{language}.po (the languages: "
                          f"{', '.join(['en'] + known)})")
    with tempfile.TemporaryDirectory() as folder:
        mo = Path(folder) / "clothlab.mo"
        try:
            subprocess.run(["msgfmt", "--check", "-o", str(mo), str(po)], check=True,
                           capture_output=True, text=True)
        except OSError:
            raise RegionError("msgfmt is missing: install GNU gettext (Debian's package gettext)")
        except subprocess.CalledProcessError as error:
            raise RegionError(f"po/{language}.po does not compile:\n{error.stderr.strip()}")
        with mo.open("rb") as file:
            return gettext.GNUTranslations(file)


def without_hints(text):
    """A catalogue (.po, .pot) without its entries of HINT_CONTEXT: the copy's TODOs are written
    already, and those of the other hint level are not the student's to read."""
    blocks = text.rstrip("\n").split("\n\n")
    kept = [b for b in blocks if f'msgctxt "{HINT_CONTEXT}"' not in b]
    return "\n\n".join(kept) + "\n"


def in_language(outputs, language):
    """A copy in `language`: each document that has a twin in it (docs/lab.md and docs/lab.fr.md)
    is the twin's text, so that docs/lab.md is French in the French copy, and the twin's line that
    points to the English one (*English: `docs/lab.md`.*) is left out of both."""
    for name in list(outputs):
        twin = re.fullmatch(rf"(docs/.+)\.{re.escape(language)}\.md", name)
        if not twin or f"{twin.group(1)}.md" not in outputs:
            continue
        english = f"{twin.group(1)}.md"
        data, mode = outputs[name]
        lines = data.decode("utf-8").split("\n")
        pointer = re.compile(rf"^\*\w+\s*: `{re.escape(english)}`\.\*$")
        text = "\n".join(line for line in lines if not pointer.match(line))
        text = re.sub(r"\A(# [^\n]*\n)\n\n", r"\1\n", text)  # (the blank line it leaves)
        outputs[name] = outputs[english] = (text.encode("utf-8"), mode)


def generate(root, dest, lab, keep=(), hints="handout", answers=Answers(), language="en"):
    """Writes the student copy of root into dest, its TODOs and README's tasks in `language`
    (po/<language>.po); returns what it wrote, in words. RegionError names the file and line of
    a malformed region, a leftover solution line, an answer or a text the catalogue lacks."""
    questions = lab.ids
    regions = []
    outputs = {}
    translations = catalogue(root, language)
    untranslated = []
    translate = None
    if translations is not None:
        def translate(words, where):
            found = translations.pgettext(HINT_CONTEXT, words)
            if found == words:
                untranslated.append(f"{where}: {words.splitlines()[0]}")
            return found
    for name in project_files(root):
        if lab.is_teacher_file(name):
            continue
        source = root / name
        data = source.read_bytes()
        if Path(name).suffix in TEXT_SUFFIXES and b"\0" not in data:
            text = transform(name, data.decode("utf-8"), keep, regions, hints, questions,
                             translate)
            data = text.encode("utf-8")
        elif name.startswith("po/") and name.endswith((".po", ".pot")):
            data = without_hints(data.decode("utf-8")).encode("utf-8")
        outputs[name] = (data, source.stat().st_mode & 0o777)

    if untranslated:
        raise RegionError(f"po/{language}.po has no translation of these TODOs (scripts/"
                          "update-messages, then translate them):\n  " + "\n  ".join(untranslated))
    questions_found = {r[0] for r in regions}
    missing = [q for q in questions if q not in questions_found]
    if missing:
        raise RegionError(f"no solution region for {', '.join(missing)}")
    if language != "en":
        in_language(outputs, language)
    if "README.md" in outputs:
        readme = outputs["README.md"][0].decode("utf-8")
        if TASKS_LINE not in readme:
            raise RegionError(f"README.md has no line {TASKS_LINE}")
        readme = readme.replace(TASKS_LINE, tasks_section(
            regions, questions, translations or gettext.NullTranslations()))
        outputs["README.md"] = (readme.encode("utf-8"), outputs["README.md"][1])

    # No line of a removed solution may survive anywhere in the student's code.
    searched = {name: data.decode("utf-8", "replace").split("\n")
                for name, (data, _) in outputs.items() if name.startswith(SEARCHED_FOR_LEFTOVERS)}
    stripped = {name: {line.strip() for line in lines} for name, lines in searched.items()}
    leftovers = []
    for question, title, name, _, solution, stub in regions:
        if question in keep:
            continue
        allowed = {s.strip() for s in stub}
        for line in solution:
            if significant(line) and line.strip() not in allowed:
                for other, content in stripped.items():
                    if line.strip() in content:
                        leftovers.append(f"{other}: '{line.strip()}' ({question} {title}, "
                                         f"{name})")
    if leftovers:
        raise RegionError("solution lines survive in the copy:\n  " + "\n  ".join(leftovers))
    # No answer of a question outside the student's places, in any language; at the handout
    # level, none in the TODOs either.
    removed = set(questions) - set(keep)
    found = []
    for name, (data, _) in outputs.items():
        if not name.startswith(answers.scope) or Path(name).suffix not in TEXT_SUFFIXES:
            continue
        for question, what in answers_in(data.decode("utf-8", "replace"), removed,
                                         answers.code):
            if (question, name) not in answers.allowed:
                found.append(f"{name}: {what} ({question})")
    if hints == "handout":
        for question in sorted(removed):
            for answer_of, what in answers_in(todo_texts(regions, question), removed,
                                              answers.code, answers.todo, keep_comments=True):
                found.append(f"the TODO of {question}: {what} ({answer_of})")
    if found:
        raise RegionError("the copy holds answers outside the student's places:\n  " +
                          "\n  ".join(sorted(set(found))))
    for name, (data, _) in outputs.items():
        text = data.decode("utf-8", "replace")
        if re.search(r"BEGIN SOLUTION|END SOLUTION|STUDENT(\(\w+\))?\||COPY\|", text):
            if name.startswith(("src/", "shaders/", "tests/", "CMakeLists")):
                raise RegionError(f"a marker survives in {name}")

    dest.mkdir(parents=True, exist_ok=True)
    for name, (data, mode) in outputs.items():
        write_if_changed(dest / name, data, mode)
    # Files of an earlier copy that the project no longer has (a build folder stays).
    for path in sorted(dest.rglob("*"), reverse=True):
        rel = path.relative_to(dest).as_posix()
        if rel.startswith(("build", ".git", "out", "Testing")) or rel == MARKER_FILE:
            continue
        if path.is_file() and rel not in outputs:
            path.unlink()
        elif path.is_dir() and not any(path.iterdir()):
            path.rmdir()
    # The copy's version: a hash of every file but the student's own (those with regions), which
    # scripts/grade compares with a submission's to tell another version from an edit.
    version = hashlib.sha256()
    for name in sorted(set(outputs) - {r[2] for r in regions}):
        version.update(name.encode() + b"\0" + outputs[name][0] + b"\0")
    (dest / MARKER_FILE).write_text(
        "A student copy of clothlab, written by scripts/make-student-version"
        + f" (hints: {hints}" + (f"; language: {language}" if language != "en" else "")
        + (f"; kept: {', '.join(sorted(keep))}" if keep else "")
        + ").\n" + f"version: {version.hexdigest()[:16]}\n")
    kept = f", solutions kept: {', '.join(sorted(keep))}" if keep else ""
    return (f"student copy written to {dest}: {len(outputs)} files, {len(regions)} regions in "
            f"{len(questions_found)} questions replaced by their TODO stubs (hints: {hints}"
            f"{'' if language == 'en' else ', language: ' + language})"
            f"{kept}")
