#!/usr/bin/env python3
"""scripts/grade, checked on a small class (issue 18). Usage: check_grade.py PROJECT_ROOT

The class is made from the solution and the student copy (scripts/make-student-version):
  alice  every question right, handed in as a bare git repository
  bob    the student copy as handed out: every question a stub
  carol  Q5, Q6, Q7 wrong in a plausible way (Newton's third law forgotten, the mass ignored,
         the middle of an edge pinned)
  dave   Q8, Q9, Q12, Q13 wrong (shear springs as stiff as structural ones, the ground does not
         stop the fall, one stiffness on the GPU, the GPU wind blowing backwards)
  erin   right, but coupled_springs.cpp does not compile
  frank  hostile: an endless loop (Q5), a flood of output (Q6), system() and a file written
         outside its folder (Q7), NaN forces (Q8), a crash (Q9)
  grace  the stubs, with the question tests, the CMake files and lab-report edited to pass
  heidi  right, as a .zip, from "another version" of the copy (its version stamp differs)
  judy   a .tar.gz with no student file in it
and each grade, grades.csv, students/NAME/results.json (Gradescope's fields), students/NAME/
junit.xml and report.html (with its links to them) are checked; then the Gradescope bundle's run_autograder grades carol's files, uploaded loose, in a
folder laid out like Gradescope's. One shared build (the grader's
own), each submission an incremental rebuild of its own files.
"""
import csv
import html.parser
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile
import time
import xml.etree.ElementTree as ElementTree
import zipfile
from pathlib import Path

BEGIN = re.compile(r"^\s*(//|#)\s*BEGIN SOLUTION (Q\d+)")
END = re.compile(r"^\s*(//|#)\s*END SOLUTION (Q\d+)")
# make-student-version's STUDENT| lines: STUDENT(handout)| and STUDENT(guided)| are a hint level's.
STUDENT = re.compile(r"^(\s*)(?://|#) STUDENT(?:\((\w+)\))?\|(?: (.*))?$")
problems = []


def check(condition, message):
    if not condition:
        problems.append(message)
        print("FAILED: " + message, flush=True)
    return condition


def run(command, **kwargs):
    print("$ " + " ".join(str(c) for c in command), flush=True)
    return subprocess.run([str(c) for c in command], capture_output=True, text=True, **kwargs)


def regions(teacher_file):
    """[(question, solution text, stub text)] of a teacher's source file."""
    found, current = [], None
    for line in teacher_file.read_text().splitlines():
        if BEGIN.match(line):
            current = (BEGIN.match(line).group(2), [], [])
        elif END.match(line) and current:
            found.append((current[0], "\n".join(current[1]), "\n".join(current[2])))
            current = None
        elif current:
            student = STUDENT.match(line)
            if student:
                if student.group(2) in (None, "handout"):
                    current[2].append(student.group(1) + (student.group(3) or ""))
            else:
                current[1].append(line)
    return found


class Maker:
    """Submissions made from the solution copy, one region changed at a time."""

    def __init__(self, root, work):
        self.root = root
        self.solution = work / "solution"
        self.stubs = work / "stubs"
        questions = sorted({q for f in self.student_files() for q, _, _ in regions(root / f)})
        made = run([root / "scripts/make-student-version", self.solution,
                    *[a for q in questions for a in ("--keep", q)]])
        check(made.returncode == 0, "make-student-version --keep (every question) failed: " +
              made.stderr)
        made = run([root / "scripts/make-student-version", self.stubs])
        check(made.returncode == 0, "make-student-version failed: " + made.stderr)

    def student_files(self):
        return sorted(p.relative_to(self.root).as_posix() for folder in ("src", "shaders")
                      for p in (self.root / folder).rglob("*") if p.is_file() and any(
                          BEGIN.match(l) for l in p.read_text(errors="replace").splitlines()))

    def copy(self, name, dest, base=None):
        shutil.copytree(base or self.solution, dest / name)
        return dest / name

    def change(self, folder, question, old, new):
        """Replaces old by new inside question's region; where the region no longer holds
        old (the solution was rewritten), the region becomes its stub: still wrong."""
        for name in self.student_files():
            path = folder / name
            text = path.read_text()
            for q, solution, stub in regions(self.root / name):
                if q == question and solution in text and old in solution:
                    path.write_text(text.replace(solution, solution.replace(old, new)))
                    return
        self.stub(folder, question)
        print(f"(note: '{old.strip()}' is no longer in {question}'s solution: the region is "
              "made a stub instead)")

    def stub(self, folder, question):
        for name in self.student_files():
            path = folder / name
            text = path.read_text()
            for q, solution, stub in regions(self.root / name):
                if q == question and solution in text:
                    text = text.replace(solution, stub)
            path.write_text(text)

    def prepend(self, folder, question, code, headers=()):
        """Puts code at the start of question's first region (and headers atop its file)."""
        for name in self.student_files():
            path = folder / name
            text = path.read_text()
            for q, solution, _ in regions(self.root / name):
                if q == question and solution in text and name.endswith(".cpp"):
                    indent = re.match(r"\s*", solution).group(0)
                    text = text.replace(solution, indent + code + "\n" + solution, 1)
                    path.write_text("".join(f"#include <{h}>\n" for h in headers) + text)
                    return
        check(False, f"no C++ region of {question} to put hostile code in")


def make_class(maker, dest, outside):
    subs = []
    # alice: a bare git repository of the solution.
    alice_tree = maker.copy("alice-tree", dest.parent)
    git = ["git", "-c", "user.name=Alice", "-c", "user.email=alice@example.org"]
    run(["git", "init", "-q", alice_tree])
    run(git + ["-C", alice_tree, "add", "-A"])
    run(git + ["-C", alice_tree, "commit", "-q", "-m", "lab"])
    run(["git", "clone", "-q", "--bare", alice_tree, dest / "alice.git"])
    subs.append(dest / "alice.git")
    subs.append(maker.copy("bob", dest, maker.stubs))
    carol = maker.copy("carol", dest)
    maker.change(carol, "Q5", "add(i - 1, -F);", "")
    maker.change(carol, "Q6", "get_force(k) / m + g", "get_force(k) + g")
    maker.change(carol, "Q7", "index(n - 1, 0, n)", "index(n / 2, 0, n)")  # not a corner
    subs.append(carol)
    dave = maker.copy("dave", dest)
    maker.change(dave, "Q8", "K_shear, L0", "K_structural, L0")
    maker.change(dave, "Q9", "v.z = std::max(v.z, 0.0);", "")
    maker.change(dave, "Q12", "stiffness[family]", "stiffness[0]")
    maker.change(dave, "Q13", "force += wind_strength", "force -= wind_strength")
    subs.append(dave)
    erin = maker.copy("erin", dest)
    with open(erin / "src/core/coupled_springs.cpp", "a") as f:
        f.write("\nstatic int half_written = ;\n")
    subs.append(erin)
    frank = maker.copy("frank", dest)
    maker.prepend(frank, "Q5", "for (volatile unsigned spin = 0;; spin = spin + 1) {\n}")
    maker.prepend(frank, "Q6", 'for (int line = 0; line < 4000000; ++line)\n  std::fputs('
                  '"all work and no play makes jack a dull boy\\n", stdout);', ["cstdio"])
    maker.prepend(frank, "Q7", f'if (std::system("echo pwned > {outside}/system.txt") == 0) {{\n'
                  f'}}\nif (std::FILE* f = std::fopen("{outside}/fopen.txt", "w"))\n'
                  '  std::fclose(f);', ["cstdio", "cstdlib"])
    maker.prepend(frank, "Q8", 'f += glm::dvec3(std::nan(""));', ["cmath"])
    maker.prepend(frank, "Q9", "{\n  volatile int* volatile nowhere = nullptr;\n  *nowhere = 1;\n}")
    subs.append(frank)
    grace = maker.copy("grace", dest, maker.stubs)
    for test in (grace / "tests/lab").glob("q*_test.cpp"):
        names = re.findall(r"^TEST(?:_F)?\((\w+), (\w+)\)", test.read_text(), re.MULTILINE)
        test.write_text("#include <gtest/gtest.h>\n" + "".join(
            f"TEST({suite}, {name}) {{}}\n" for suite, name in names))
    for edited in ("tests/lab/CMakeLists.txt", "CMakeLists.txt", "scripts/lab-report"):
        with open(grace / edited, "a") as f:
            f.write("\n# every question done\n")
    subs.append(grace)
    heidi = maker.copy("heidi-clothlab", dest.parent)
    marker = heidi / ".student-copy"
    marker.write_text(re.sub(r"version: \S+", "version: 0123456789abcdef", marker.read_text()))
    with zipfile.ZipFile(dest / "heidi.zip", "w") as archive:
        for path in sorted(heidi.rglob("*")):
            if path.is_file():
                archive.write(path, path.relative_to(heidi.parent).as_posix())
    subs.append(dest / "heidi.zip")
    judy = dest.parent / "judy"
    judy.mkdir()
    (judy / "notes.txt").write_text("I did not understand the lab.\n")
    with tarfile.open(dest / "judy.tar.gz", "w:gz") as archive:
        archive.add(judy, "judy")
    subs.append(dest / "judy.tar.gz")
    return subs


class Table(html.parser.HTMLParser):
    """The rows of report.html's tables, by table id."""

    def __init__(self):
        super().__init__()
        self.tables, self.table, self.row, self.cell = {}, None, None, None

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.table = self.tables.setdefault(dict(attrs).get("id"), [])
        elif tag == "tr" and self.table is not None:
            self.row = []
            self.table.append(self.row)
        elif tag in ("td", "th") and self.row is not None:
            self.cell = ""

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self.row is not None and self.cell is not None:
            self.row.append(self.cell.strip())
            self.cell = None
        elif tag == "table":
            self.table = None

    def handle_data(self, data):
        if self.cell is not None:
            self.cell += data


def main():
    root = Path(sys.argv[1]).resolve()
    work = Path(tempfile.mkdtemp(prefix="clothlab-grade-check-"))
    outside = work / "outside"  # where frank tries to write
    outside.mkdir()
    started = time.monotonic()
    try:
        maker = Maker(root, work)
        (work / "class").mkdir()
        subs = make_class(maker, work / "class", outside)
        lab = json.loads((root / "grading/lab.json").read_text())
        points = {q["id"]: q["points"] for q in lab["questions"]}
        questions = list(points)
        out = work / "out"
        graded = run([root / "scripts/grade", "--out", out, "--work", work / "kit",
                      "--timeout", "2", "--test-budget", "30", "--", *subs])
        print(graded.stdout + graded.stderr[-6000:])
        if not check(graded.returncode == 0, "scripts/grade failed"):
            return 1
        sandboxed = "bubblewrap:" in graded.stderr
        names = ["alice", "bob", "carol", "dave", "erin", "frank", "grace", "heidi", "judy"]
        results = {n: json.loads((out / "students" / n / "results.json").read_text())
                   for n in names}
        score = {n: {t["name"].split(":")[0]: t["score"] for t in r["tests"]}
                 for n, r in results.items()}
        notes = {n: r["output"] for n, r in results.items()}
        full = {q: float(p) for q, p in points.items()}

        def expect(name, wanted, why):
            for q, rule in wanted.items():
                got = score[name].get(q)
                ok = (got == full[q] if rule == "full" else got == 0 if rule == 0 else
                      got is not None and got < full[q])
                check(ok, f"{name} ({why}): {q} should be {rule}, got {got}\n" +
                      next((t["output"] for t in results[name]["tests"]
                            if t["name"].startswith(q + ":")), "")[:1500])

        every = dict.fromkeys(questions, "full")
        nothing = dict.fromkeys(questions, 0)
        expect("alice", every, "the solution, a bare git repository")
        expect("bob", nothing, "the stubs")
        expect("carol", {"Q5": "less", "Q6": "less", "Q7": "less", "Q12": "full"}, "Q5-Q7 wrong")
        expect("dave", {"Q5": "full", "Q8": "less", "Q9": "less", "Q12": "less", "Q13": "less"},
               "Q8, Q9, Q12, Q13 wrong")
        expect("erin", {**every, "Q5": 0}, "coupled_springs.cpp does not compile")
        check("does not compile" in notes["erin"] and "expected primary-expression" in
              json.dumps(results["erin"]), "erin: the compiler's first error is not reported")
        expect("frank", {"Q5": 0, "Q12": "full"}, "hostile")
        # In the notes (the grader's words), or in the question's messages (the checker's words,
        # where tests/lab's checker reports the runner's crash or flood as a failed check).
        everything_of_frank = json.dumps(results["frank"])
        for words in ("did not finish", "crashed", ("printed too much", "printed more than")):
            words = (words,) if isinstance(words, str) else words
            check(any(w in everything_of_frank for w in words),
                  f"frank: '{words[0]}' is not reported: {notes['frank']}")
        if sandboxed:
            check(not list(outside.iterdir()), "frank wrote outside its folder despite the "
                                               f"sandbox: {list(outside.iterdir())}")
        expect("grace", nothing, "edited tests: gains nothing")
        check("that are not the student's own, ignored" in notes["grace"] and
              "tests/lab/q5_coupled_springs_test.cpp" in notes["grace"],
              f"grace: the edited tests are not reported: {notes['grace']}")
        expect("heidi", every, "the solution, a .zip")
        check("another version" in notes["heidi"], f"heidi: 'another version' is not reported: "
                                                    f"{notes['heidi']}")
        expect("judy", nothing, "no student file")
        check("no student file" in notes["judy"], f"judy: not reported: {notes['judy']}")

        # Gradescope's fields.
        for name, r in results.items():
            check(isinstance(r.get("score"), (int, float)) and isinstance(r.get("tests"), list)
                  and len(r["tests"]) == len(questions),
                  f"{name}/results.json lacks Gradescope's score or one test per question")
            for t in r["tests"]:
                check({"name", "score", "max_score", "output", "status"} <= set(t) and
                      t["status"] in ("passed", "failed") and 0 <= t["score"] <= t["max_score"],
                      f"{name}/results.json: a test entry is not Gradescope's: {t}")
            check(abs(sum(t["score"] for t in r["tests"]) - r["score"]) < 1e-6,
                  f"{name}/results.json: score is not the sum of its tests'")
        # JUnit.
        for name in names:
            suites = ElementTree.parse(out / "students" / name / "junit.xml").getroot()
            cases = list(suites.iter("testcase"))
            bad = [c for c in cases if c.find("failure") is not None or c.find("error") is not
                   None]
            wrong = [q for q in questions if score[name][q] < full[q]]
            check(suites.tag == "testsuites" and len(cases) == len(questions) and
                  len(bad) == len(wrong), f"{name}/junit.xml: {len(cases)} cases, {len(bad)} "
                                          f"failed, {len(wrong)} questions short of full marks")
        # grades.csv.
        with open(out / "grades.csv", newline="") as f:
            rows = list(csv.reader(f))
        check(rows[0][:len(questions) + 2] == ["student", *questions, "total"],
              f"grades.csv header: {rows[0]}")
        for row in rows[1:]:
            name = row[0]
            check(name in score and [float(v) for v in row[1:len(questions) + 1]] ==
                  [score[name][q] for q in questions] and abs(float(row[len(questions) + 1]) -
                                                              results[name]["score"]) < 1e-6,
                  f"grades.csv row {row[:len(questions) + 2]} differs from results.json")
        check(len(rows) == len(names) + 1, f"grades.csv: {len(rows) - 1} rows")
        # report.html.
        report = (out / "report.html").read_text()
        table = Table()
        table.feed(report)
        body = table.tables.get("class", [])[1:]
        check([r[0] for r in body] == names, f"report.html's class table: {[r[0] for r in body]}")
        for r in body:
            cells = [("0" if c == "build" else c) for c in r[1:len(questions) + 1]]
            check([float(c) for c in cells] == [score[r[0]][q] for q in questions],
                  f"report.html's row of {r[0]} differs from its grades: {r}")
        per_question = table.tables.get("questions", [])[1:]
        check(len(per_question) == len(questions) and per_question[0][1].endswith(
            f"/{len(names)} ({sum(score[n]['Q5'] == full['Q5'] for n in names) / len(names):.0%})"),
            f"report.html's pass rates: {per_question[:1]}")
        for name in names:
            check(f"href='students/{name}/results.json'" in report,
                  f"report.html does not link to {name}'s results.json")
        check("What the class got wrong" in report and "Newton" in report and
              "<script" not in report and "http" not in report,
              "report.html: no frequent failure of Q5 (Newton's third law), or a script or link")

        # Gradescope: the bundle, and its run_autograder in a folder laid out like Gradescope's.
        bundle = work / "autograder.zip"
        made = run([root / "scripts/grade", "--gradescope-bundle", bundle])
        if check(made.returncode == 0, f"--gradescope-bundle failed: {made.stderr}"):
            source = work / "autograder" / "source"
            with zipfile.ZipFile(bundle) as archive:
                names_in = archive.namelist()
                archive.extractall(source)
            check({"setup.sh", "run_autograder", "clothlab-grade/grade",
                   "clothlab-grade/manifest.json"} <= set(names_in) and not any(
                "docs/answers.md" in n or "make-student-version" in n for n in names_in),
                "the bundle lacks setup.sh, run_autograder or the kit, or holds a teacher file")
            for script in ("setup.sh", "run_autograder"):
                os.chmod(source / script, 0o755)
                check(run(["bash", "-n", source / script]).returncode == 0, f"{script}: syntax")
            kit_manifest = json.loads((source / "clothlab-grade/manifest.json").read_text())
            check(kit_manifest == json.loads((work / "kit/manifest.json").read_text()),
                  "the bundle's manifest differs from the grader's")
            # Carol's files uploaded loose, as Gradescope's file upload hands them in.
            (work / "autograder" / "submission").mkdir()
            for name in maker.student_files():
                shutil.copy(work / "class" / "carol" / name, work / "autograder" / "submission")
            # setup.sh would install the packages and build the kit (minutes): the kit built
            # above stands in for it (the same copy: same manifest).
            # Gradescope runs /autograder/run_autograder, a copy of the bundle's.
            shutil.copy2(source / "run_autograder", work / "autograder" / "run_autograder")
            ran = run([work / "autograder" / "run_autograder"], env=dict(
                os.environ, AUTOGRADER_ROOT=str(work / "autograder"),
                CLOTHLAB_GRADE_KIT=str(work / "kit")))
            produced = work / "autograder" / "results" / "results.json"
            if check(ran.returncode == 0 and produced.exists(), "run_autograder wrote no "
                     f"results.json: {ran.stdout[-1500:]}{ran.stderr[-1500:]}"):
                check(json.loads(produced.read_text())["score"] == results["carol"]["score"],
                      "run_autograder's score of carol's files, uploaded loose, differs from "
                      "scripts/grade's of her copy")

        # The GitHub workflow: tests/grade/check_classroom.py (grade.classroom_workflow).
    finally:
        print(f"check_grade: {time.monotonic() - started:.0f} s")
        if not problems:
            shutil.rmtree(work, ignore_errors=True)
        else:
            print(f"(the class and its grades are left in {work} to look at)")
    if problems:
        print(f"\n{len(problems)} problem(s) with scripts/grade:")
        for p in problems:
            print("  - " + p.splitlines()[0])
        return 1
    print("scripts/grade grades the class right, in every format")
    return 0


if __name__ == "__main__":
    sys.exit(main())
