#!/usr/bin/env python3
"""The lab's checkers against runners that misbehave (fake_runner.cpp): each case runs one
question test with a misbehaving runner and requires that the test FAILS, with the reason in
words, in bounded time, and that GoogleTest's XML report says so too. And: the checkers link
none of the student's code (their symbols), which the runner does.

    check_harness.py CASE CHECKER FAKE_RUNNER [REAL_RUNNER]
"""
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from xml.etree import ElementTree

# The test that runs: its first request is the spring_mesh constructor.
TEST = "Q7Pins.PinsNoneLeavesEveryVertexFree"
WHERE = "Q7: the student's code, in the spring_mesh constructor (load_model), "

# case: (environment, words the failure must hold, seconds it may take at most)
CASES = {
    "forge_stdout": ({"CLOTHLAB_FAKE_RUNNER": "forge-stdout"},
                     WHERE + "ended the program (exit status 0) before answering", 20),
    "forge_answer": ({"CLOTHLAB_FAKE_RUNNER": "forge-answer"},
                     WHERE + "answered something that is not the runner's answer", 20),
    "crash": ({"CLOTHLAB_FAKE_RUNNER": "crash"}, WHERE + "crashed: segmentation fault", 20),
    "hang": ({"CLOTHLAB_FAKE_RUNNER": "hang", "CLOTHLAB_LAB_TIMEOUT": "1"},
             WHERE + "did not answer within 1 s: an endless loop", 20),
    "flood": ({"CLOTHLAB_FAKE_RUNNER": "flood"}, WHERE + "printed more than 16 MB", 30),
    "flood_answer": ({"CLOTHLAB_FAKE_RUNNER": "flood-answer"},
                     WHERE + "sent more than 64 MB without ending its answer", 30),
    "exit": ({"CLOTHLAB_FAKE_RUNNER": "exit"},
             WHERE + "ended the program (exit status 0) before answering", 20),
    # The sandbox's words come before the runner: here they set the mode.
    "sandbox_prefix": ({"CLOTHLAB_LAB_SANDBOX": '["env", "CLOTHLAB_FAKE_RUNNER=crash"]'},
                       WHERE + "crashed: segmentation fault", 20),
    "sandbox_escapes": ({"CLOTHLAB_LAB_SANDBOX": ' [ "env" ,"CLOTHLAB_FAKE_RUNNER=cr\\u0061sh" ] '},
                        WHERE + "crashed: segmentation fault", 20),
    "sandbox_not_json": ({"CLOTHLAB_LAB_SANDBOX": '["env", '},
                         WHERE + "could not be started: CLOTHLAB_LAB_SANDBOX is not a JSON array",
                         20),
    "no_runner": ({"CLOTHLAB_LAB_RUNNER": "/nonexistent/lab_runner"},
                  WHERE + "could not be started: cannot start /nonexistent/lab_runner", 20),
}

# Functions of the student's files: defined in the runner, never in a checker.
STUDENT_SYMBOLS = ("clothlab::spring_mesh::compute_force", "clothlab::spring_mesh::apply_force",
                   "clothlab::coupled_springs::compute_force", "clothlab::apply_ground_contact",
                   "clothlab::gpu_cloth::step")


def fail(message):
    print("FAILED: " + message)
    sys.exit(1)


def defined_symbols(program):
    out = subprocess.run(["nm", "-C", "--defined-only", program], capture_output=True,
                         text=True, check=True).stdout
    return out


def check_symbols(checkers, runner):
    held = defined_symbols(runner)
    for symbol in STUDENT_SYMBOLS:
        if symbol not in held:
            fail(f"the runner {runner} does not define {symbol}: is the list of symbols right?")
    for checker in checkers:
        text = defined_symbols(checker)
        found = [s for s in STUDENT_SYMBOLS if s in text]
        if found:
            fail(f"{checker} holds the student's code ({', '.join(found)}): a checker must "
                 "link none of it")
    print(f"the {len(checkers)} checkers hold none of {len(STUDENT_SYMBOLS)} student functions; "
          "the runner holds them all")


def main():
    case = sys.argv[1]
    if case == "symbols":
        check_symbols(sys.argv[2:-1], sys.argv[-1])
        return
    checker, fake = sys.argv[2], sys.argv[3]
    extra, expected, limit = CASES[case]
    env = dict(os.environ, CLOTHLAB_LAB_RUNNER=fake, GTEST_COLOR="no")
    env.pop("CLOTHLAB_FAKE_RUNNER", None)
    env.pop("CLOTHLAB_LAB_SANDBOX", None)
    env.update(extra)
    with tempfile.TemporaryDirectory() as tmp:
        xml = Path(tmp) / "report.xml"
        started = time.monotonic()
        try:
            run = subprocess.run([checker, f"--gtest_filter={TEST}", f"--gtest_output=xml:{xml}"],
                                 env=env, capture_output=True, timeout=limit, stdin=subprocess.DEVNULL)
        except subprocess.TimeoutExpired:
            fail(f"the checker did not end within {limit} s: it must stop a runner that hangs")
        seconds = time.monotonic() - started
        output = run.stdout.decode(errors="replace") + run.stderr.decode(errors="replace")
        tail = output[-3000:]
        if run.returncode < 0:
            fail(f"the checker crashed (signal {-run.returncode}):\n{tail}")
        if run.returncode == 0:
            fail(f"the checker PASSED with a misbehaving runner ({case}):\n{tail}")
        if expected not in output:
            fail(f"the failure does not say '{expected}':\n{tail}")
        try:
            report = ElementTree.parse(xml).getroot()
        except (OSError, ElementTree.ParseError) as error:
            fail(f"no GoogleTest report ({error}):\n{tail}")
        failures = [f.get("message", "") for f in report.iter("failure")]
        if not any(expected in m for m in failures):
            fail(f"the XML report has no failure saying '{expected}': {failures}")
    print(f"{case}: the test failed in {seconds:.1f} s, saying: {expected}")


if __name__ == "__main__":
    main()
