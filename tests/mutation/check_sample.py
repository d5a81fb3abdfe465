#!/usr/bin/env python3
"""Runs `scripts/mutate-grader --ci-sample` and checks what it must report: every wrong answer of
the sample killed (by a test or a compile error), the control mutant (an equivalent answer)
SURVIVED, and so an exit status of 1. Usage: check_sample.py PATH/TO/mutate-grader"""
import re
import subprocess
import sys

harness = sys.argv[1]
result = subprocess.run([sys.executable, harness, "--ci-sample"], capture_output=True, text=True)
out = result.stdout + result.stderr
problems = []
table = out.split("\nmutant ", 1)[-1] if "\nmutant " in out else ""
rows = {m.group(1): m.group(2) for m in re.finditer(r"^(q\d+-\S+)\s+Q\d+\s+(.*)$", table, re.M)}
if not rows:
    problems.append("the harness printed no table of mutants")
for name, verdict in rows.items():
    control = "(control: must survive)" in verdict
    if control and not verdict.startswith("SURVIVED"):
        problems.append(f"the control {name} should SURVIVE (an equivalent answer): {verdict}")
    if not control and not verdict.startswith(("killed by", "compile error")):
        problems.append(f"the wrong answer {name} should be killed: {verdict}")
if not any("(control: must survive)" in v for v in rows.values()):
    problems.append("the sample has no control mutant")
if result.returncode != 1:
    problems.append(f"the harness should exit 1 (a mutant survived), not {result.returncode}")
if not re.search(r"^score: (\d+)/\1 mutants killed", out, re.M):
    problems.append("the score line should say every counted mutant is killed")
if problems:
    print(out)
    print("mutation sample:\n  " + "\n  ".join(problems))
    sys.exit(1)
print(out)
print("mutation sample: the wrong answers are killed, the control survives")
