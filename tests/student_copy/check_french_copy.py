#!/usr/bin/env python3
"""The student copy in French (scripts/make-student-version --lang fr), and the English one
left as the sources write it.

    check_french_copy.py PROJECT_ROOT [--build]

At both hint levels: every TODO of the French copy is French (its title and the no-break space
of French before the colon, no English TODO of the same level left, lines within the 100
columns of .clang-format), README.md's tasks are "Vos tâches", and the copy's catalogues hold
no TODO (the other level's hints are not the student's to read). The English copy's TODOs are
the sources' STUDENT(handout)| lines, word for word, under "Your tasks". With --build, the
handout-level French copy is configured and its program built, a headless run of the GPU path
compiles the shaders whose comments are French, and the tests of question 8, unanswered, fail
with their hints in French under LANG=fr_FR.UTF-8. Exit 1 with each problem found.
"""
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

NO_BREAK_SPACE = "\u00a0"
# The first line of a TODO: "TODO Q8 (ressorts structurels) : ..." in French.
TODO_LINE = re.compile(r"^\s*(?://|#) TODO (Q\d+) \(([^)]*)\)(\s?):")
STUDENT_LINE = re.compile(r"^\s*(?://|#) STUDENT\((handout|guided)\)\| ?(.*)$")
# Words a French TODO uses (the handout's vocabulary, and French's small words), and those of an
# English one, which a French TODO must not hold.
FRENCH_WORDS = re.compile(r"\b(ressorts?|sommets?|tissu|sol|vent|masses?|le|la|les|du|des|de|"
                          r"et|avec|pour|dans|chaque|même|où)\b")
ENGLISH_WORDS = re.compile(r"\b(the|and|with|for|when|each|add|of|is)\b")
problems = []


def check(condition, message):
    if not condition:
        problems.append(message)
        print("FAILED: " + message, flush=True)
    return condition


def make_copy(root, dest, *options):
    made = subprocess.run([str(root / "scripts/make-student-version"), str(dest), *options],
                          capture_output=True, text=True)
    check(made.returncode == 0, f"make-student-version {' '.join(options)} failed:\n"
                                f"{made.stdout}{made.stderr}")
    return made.returncode == 0


def student_files(copy):
    return [p for folder in ("src/core", "shaders") for p in sorted((copy / folder).glob("*"))
            if p.is_file()]


def todo_blocks(copy):
    """{(file, line): [the TODO's comment lines]} of the copy's student files."""
    blocks = {}
    for path in student_files(copy):
        lines = path.read_text(encoding="utf-8").split("\n")
        for i, line in enumerate(lines):
            if TODO_LINE.match(line):
                block = [line]
                indent = line[:len(line) - len(line.lstrip())]
                for following in lines[i + 1:]:
                    if not re.match(re.escape(indent) + r"(//|#) ", following) or \
                            TODO_LINE.match(following):
                        break
                    block.append(following)
                blocks[(path.relative_to(copy).as_posix(), i + 1)] = block
    return blocks


def english_first_lines(root, level):
    """The first lines of the sources' TODOs at that hint level, without their indentation."""
    found = set()
    for folder in ("src/core", "shaders"):
        for path in sorted((root / folder).glob("*")):
            for line in path.read_text(encoding="utf-8").split("\n") if path.is_file() else []:
                student = STUDENT_LINE.match(line)
                if student and student.group(1) == level and "TODO Q" in student.group(2):
                    found.add(student.group(2).strip())
    return found


def check_french(root, copy, level):
    blocks = todo_blocks(copy)
    check(len(blocks) >= 11, f"the French copy ({level}) has {len(blocks)} TODOs, not the "
                             "eleven regions' (Q5 to Q13)")
    english = english_first_lines(root, level)
    for (name, line), block in blocks.items():
        where = f"{name}:{line} ({level})"
        first = TODO_LINE.match(block[0])
        check(first.group(3) == NO_BREAK_SPACE,
              f"{where}: the TODO's colon has no no-break space before it, as French writes it: "
              f"{block[0].strip()}")
        check(block[0].strip() not in english, f"{where}: the TODO is the English one: "
                                               f"{block[0].strip()}")
        words = " ".join(block)
        check(len(FRENCH_WORDS.findall(words)) >= 2 and not ENGLISH_WORDS.search(words),
              f"{where}: the TODO does not read as French: {words[:200]}")
        for text in block:
            check(len(text) <= 100, f"{where}: a line of {len(text)} characters, more than "
                                    f"the 100 of .clang-format: {text.strip()}")
    readme = (copy / "README.md").read_text(encoding="utf-8")
    check("## Vos tâches" in readme and "## Your tasks" not in readme,
          f"README.md of the French copy ({level}) has no section 'Vos tâches' (or still "
          "'Your tasks')")
    check("| question | quoi | fichier | fonction | vérification |" in readme,
          f"README.md of the French copy ({level}): the table of the tasks is not French")
    for q in ("q5", "q6", "q7", "q8", "q9", "q12", "q13"):
        check(f"./test.sh -L {q}`" in readme, f"README.md's tasks ({level}) do not name {q}")
    for catalogue in sorted((copy / "po").glob("*.po*")):
        check('msgctxt "TODO"' not in catalogue.read_text(encoding="utf-8"),
              f"the copy's {catalogue.name} holds the TODOs of the sources (both levels)")
    # docs/lab.md, the walk through the lab, is the French one (docs/lab.fr.md's text, without
    # its pointer to an English twin the copy no longer has).
    lab = (copy / "docs/lab.md").read_text(encoding="utf-8")
    check(lab.startswith("# Le TP, question par question") and "English:" not in lab and
          lab == (copy / "docs/lab.fr.md").read_text(encoding="utf-8"),
          f"docs/lab.md of the French copy ({level}) is not docs/lab.fr.md's French")


def check_english(root, copy):
    """The English copy's TODO lines are the sources' STUDENT(handout)| lines."""
    expected = []
    for path in student_files(root):
        for line in path.read_text(encoding="utf-8").split("\n"):
            student = STUDENT_LINE.match(line)
            if student and student.group(1) == "handout":
                expected.append(student.group(2).strip())
    found = [line.strip() for block in todo_blocks(copy).values() for line in block]
    check(sorted(found) == sorted(expected),
          "the English copy's TODOs are not the sources' STUDENT(handout)| lines: "
          f"{sorted(set(found) ^ set(expected))[:6]}")
    readme = (copy / "README.md").read_text(encoding="utf-8")
    check("## Your tasks" in readme, "README.md of the English copy has no 'Your tasks'")
    check((copy / "docs/lab.md").read_text(encoding="utf-8").startswith(
        "# The lab, question by question"), "docs/lab.md of the English copy is not English")


def check_build(copy, work):
    build = work / "build-fr"
    for command in (["cmake", "-S", copy, "-B", build, "-DCMAKE_BUILD_TYPE=Release"],
                    ["cmake", "--build", build, "-j", "2", "--target", "clothlab", "lab_runner",
                     "lab_q8_tests"],
                    [build / "clothlab", "--headless", "--stage", "cloth", "--backend", "gpu",
                     "--steps", "5", "--lang", "fr"]):
        done = subprocess.run([str(c) for c in command], capture_output=True, text=True,
                              timeout=3000)
        if not check(done.returncode == 0, f"the French copy: {' '.join(map(str, command))} "
                                           f"failed:\n{(done.stdout + done.stderr)[-3000:]}"):
            return
    # Question 8 unanswered, under a French locale: its tests fail with the hints in French.
    environment = {k: v for k, v in os.environ.items()
                   if k not in ("LANGUAGE", "LC_ALL", "LC_MESSAGES", "LANG")}
    q8 = subprocess.run(["ctest", "--test-dir", str(build), "-L", "q8", "--output-on-failure"],
                        capture_output=True, text=True, timeout=600,
                        env=dict(environment, LANG="fr_FR.UTF-8"))
    output = q8.stdout + q8.stderr
    check(q8.returncode != 0, "the French copy's Q8 tests pass on the stub")
    for words in ("Q8, ressorts structurels\u00a0: s(2, 1), écarté de 0.5 m de s(1, 1)",
                  "attendu ("):
        check(words in output, f"the French copy's Q8 hints do not say '{words}':\n"
                               f"{output[-3000:]}")


def main():
    root = Path(sys.argv[1]).resolve()
    with tempfile.TemporaryDirectory(prefix="clothlab-french-copy-") as folder:
        work = Path(folder)
        for level in ("handout", "guided"):
            if make_copy(root, work / f"fr-{level}", "--lang", "fr", "--hints", level):
                check_french(root, work / f"fr-{level}", level)
        if make_copy(root, work / "en"):
            check_english(root, work / "en")
        refused = subprocess.run([str(root / "scripts/make-student-version"), str(work / "xx"),
                                  "--lang", "xx"], capture_output=True, text=True)
        check(refused.returncode != 0 and "po/xx.po" in refused.stderr,
              f"--lang xx is not refused naming po/xx.po: {refused.stderr}")
        if "--build" in sys.argv[2:] and not problems:
            check_build(work / "fr-handout", work)
    print(f"{len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
