#!/usr/bin/env python3
"""The table ./test.sh ends with (scripts/lab-report) in the user's language.

    check_lab_report.py PROJECT_ROOT BUILD_DIR

Writes the JUnit results of a run where one test of Q8 failed and every other test passed, and
reads lab-report's table under a French locale (LANG=fr_FR.UTF-8, and LANGUAGE=fr outside the
C locale): its title, statuses, questions' titles and last line are French; under the C locale
(and LANGUAGE=fr with it, which gettext ignores there) they are English. Exit 1 with each
problem found.
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from xml.sax.saxutils import quoteattr

problems = []


def check(condition, message):
    if not condition:
        problems.append(message)
        print("FAILED: " + message, flush=True)
    return condition


def main():
    root, build = Path(sys.argv[1]), Path(sys.argv[2])
    listing = json.loads(subprocess.run(["ctest", "--test-dir", str(build), "--show-only=json-v1"],
                                        check=True, capture_output=True, text=True).stdout)
    names = {t["name"]: {v for p in t.get("properties", []) if p["name"] == "LABELS"
                         for v in p["value"]} for t in listing["tests"]}
    q8 = sorted(name for name, labels in names.items() if "q8" in labels)
    if not check(q8, "no test is labelled q8 in " + str(build)):
        return 1
    cases = "".join(f'<testcase name={quoteattr(name)} status="run">'
                    + ("<failure message='x'/>" if name == q8[0] else "") + "</testcase>"
                    for name in names)
    with tempfile.TemporaryDirectory(prefix="clothlab-lab-report-") as folder:
        results = Path(folder) / "results.xml"
        results.write_text(f'<?xml version="1.0"?><testsuite>{cases}</testsuite>')
        base = {k: v for k, v in os.environ.items()
                if k not in ("LANGUAGE", "LC_ALL", "LC_MESSAGES", "LANG")}
        runs = {
            "LANG=fr_FR.UTF-8": ({"LANG": "fr_FR.UTF-8"}, "fr"),
            "LANGUAGE=fr, LC_ALL=C.UTF-8": ({"LANGUAGE": "fr", "LC_ALL": "C.UTF-8"}, "fr"),
            "LANG=C": ({"LANG": "C"}, "en"),
            "LANGUAGE=fr, LANG=C": ({"LANGUAGE": "fr", "LANG": "C"}, "en"),
        }
        expected = {
            "fr": ["Le TP, question par question (./test.sh -L q8 en vérifie une)\u00a0:",
                   "À FAIRE", "faite", "deux coins fixés",
                   "ressorts structurels, de cisaillement, de courbure",
                   "1 question à faire\u202f; la suivante\u00a0: Q8 (ressorts structurels",
                   "(docs/lab.fr.md)"],
            "en": ["The lab, question by question (./test.sh -L q8 checks one):", "TO DO",
                   "done", "two pinned corners",
                   "1 question to do; next: Q8 (structural, shear, bending springs)"],
        }
        for name, (environment, language) in runs.items():
            report = subprocess.run([sys.executable, str(root / "scripts/lab-report"),
                                     str(build), str(results)], capture_output=True, text=True,
                                    env=dict(base, **environment))
            output = report.stdout + report.stderr
            if language == "fr" and "LANG" in environment:
                print(output)
            check(report.returncode == 0, f"{name}: lab-report exits {report.returncode}")
            for words in expected[language]:
                check(words in output, f"{name}: the table does not say '{words}':\n{output}")
            other = expected["en" if language == "fr" else "fr"][0]
            check(other not in output, f"{name}: the table is not in {language}:\n{output}")
    print(f"{len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
