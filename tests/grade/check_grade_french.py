#!/usr/bin/env python3
"""scripts/grade --lang fr on a class handed the French copy (issue 37). Usage:
check_grade_french.py PROJECT_ROOT

  amelie  the French copy with every question answered (make-student-version --lang fr --keep)
  bruno   the French copy as handed out: every question a stub
  chris   the English copy as handed out, graded with the French kit: another version

What the students read must be French: each question's output in results.json (its count of
tests, each failure, the question tests' hints), the notes, junit.xml's messages; and the
class's report.html (lang="fr"). A French copy is the kit's own version (no note), an English
one is another version (a note, in French).
"""
import json
import re
import sys
import tempfile
from pathlib import Path

sys.dont_write_bytecode = True  # (no __pycache__ beside the tests)
sys.path.insert(0, str(Path(__file__).resolve().parent))
from check_grade import check, problems, run  # noqa: E402 (the class's checks, shared)

NBSP = "\u00a0"


def main():
    root = Path(sys.argv[1]).resolve()
    lab = json.loads((root / "grading/lab.json").read_text())
    questions = [q["id"] for q in lab["questions"]]
    points = {q["id"]: float(q["points"]) for q in lab["questions"]}
    with tempfile.TemporaryDirectory(prefix="clothlab-grade-fr-") as tmp:
        work = Path(tmp)
        copies = {"amelie": ["--lang", "fr", *[a for q in questions for a in ("--keep", q)]],
                  "bruno": ["--lang", "fr"], "chris": []}
        for name, options in copies.items():
            made = run([root / "scripts/make-student-version", work / name, *options])
            if not check(made.returncode == 0, f"make-student-version {name}: {made.stderr}"):
                return 1
        out = work / "out"
        graded = run([root / "scripts/grade", "--lang", "fr", "--out", out, "--work",
                      work / "kit", "--timeout", "2", "--test-budget", "30", "--",
                      *(work / name for name in copies)])
        print(graded.stdout + graded.stderr[-6000:])
        if not check(graded.returncode == 0, "scripts/grade --lang fr failed"):
            return 1
        results = {n: json.loads((out / "students" / n / "results.json").read_text())
                   for n in copies}
        score = {n: {t["name"].split(":")[0]: t["score"] for t in r["tests"]}
                 for n, r in results.items()}

        # amelie: every question right, her copy the kit's version.
        check(all(score["amelie"].get(q) == points[q] for q in questions),
              f"amelie (every answer, the French copy) should have every point: {score['amelie']}")
        check("version" not in results["amelie"]["output"],
              "amelie's French copy is the French kit's version, no note expected: "
              + results["amelie"]["output"])

        # bruno: the stubs; what he reads is French, the hints of the question tests too.
        check(all(score["bruno"].get(q) == 0 for q in questions),
              f"bruno (the stubs) should have no point: {score['bruno']}")
        q8 = next(t for t in results["bruno"]["tests"] if t["name"].startswith("Q8"))
        for words, what in (("tests réussis", "the count of tests"),
                            (f"ÉCHEC ", "a failed test"),
                            (f"Q8{NBSP}:", "the question test's hint, in French")):
            check(words in q8["output"], f"bruno's Q8 output lacks {what} ({words!r}):\n"
                  + q8["output"][:1500])
        check(not re.search(r"\btests passed\b|^FAILED ", q8["output"], re.MULTILINE),
              "bruno's Q8 output still has the English words:\n" + q8["output"][:1500])
        junit = (out / "students" / "bruno" / "junit.xml").read_text()
        check("en échec" in junit, "bruno's junit.xml: its failures' messages are not French")

        # chris: the English copy, another version than the French kit's: said in French.
        check("autre version" in results["chris"]["output"],
              "chris (the English copy) should be noted as another version, in French: "
              + results["chris"]["output"])

        report = (out / "report.html").read_text()
        check("<html lang='fr'>" in report, "report.html does not say lang='fr'")
        check(f"clothlab{NBSP}: notes de la classe" in report and "Chaque question" in report,
              "report.html's headings are not French")
    if problems:
        print(f"\n{len(problems)} problem(s) with scripts/grade --lang fr")
        return 1
    print("scripts/grade --lang fr: what the students and the teacher read is French")
    return 0


if __name__ == "__main__":
    sys.exit(main())
