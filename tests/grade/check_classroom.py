#!/usr/bin/env python3
"""The GitHub workflow of the student copy (.github/workflows/classroom.yml): written from the
lab's questions and points, its actions and their inputs the real ones, its commands run here as
the runner runs them.

    check_classroom.py ROOT             every check (ctest: grade.classroom_workflow)
    check_classroom.py ROOT --static    the checks that build nothing (a second)
    check_classroom.py ROOT --write     rewrite the workflow (after a change of points)

The questions and points come from grading/lab.json where it exists (the lab's manifest), else
from grading/points.json with the titles of scripts/lab-report.

What "as the runner runs them" means here: a `run:` step runs as `bash -e FILE` (GitHub's
default shell where bash exists) in a clean clone of a fresh student copy; a grader's
`setup-command` and `command` run as the command grader runs them (Node's execSync: `/bin/sh -c`,
the environment reduced to PATH, HOME, FORCE_COLOR, DOTNET_CLI_HOME and DOTNET_NOLOGO). The
cache steps and the checkout are actions, not commands: the clean clone stands in for the
checkout, the restore of the cache is this machine's ccache folder linked as .ccache, and the
save is skipped (it only uploads that folder). On the stubs every
grader must fail; with every question's solution kept (make-student-version --keep) every grader
must pass, and the points add up to the lab's total.
"""
import importlib.machinery
import importlib.util
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.dont_write_bytecode = True  # lab-report is loaded by path: no __pycache__ in scripts/
WORKFLOW = Path(".github/workflows/classroom.yml")

# The actions the workflow may use, each with the inputs its action.yml declares (required ones
# apart), read in the action's own repository (the stored snapshot named). GitHub resolves
# every `uses:` before the job starts: a wrong name or version fails the whole job with no
# points, and neither actionlint nor action-validator checks that an action exists.
ACTIONS = {
    "actions/checkout@v7": {
        "inputs": {"allow-unsafe-pr-checkout", "clean", "fetch-depth", "fetch-tags", "filter",
                   "github-server-url", "lfs", "path", "persist-credentials", "ref",
                   "repository", "set-safe-directory", "show-progress", "sparse-checkout",
                   "sparse-checkout-cone-mode", "ssh-key", "ssh-known-hosts", "ssh-strict",
                   "ssh-user", "submodules", "token"},
        "required": set(),
        "read": "github.com/actions/checkout action.yml at tag v7 (3d3c42e, 2026-07-17; node24)"},
    "actions/cache/restore@v5": {
        "inputs": {"path", "key", "restore-keys", "enableCrossOsArchive", "fail-on-cache-miss",
                   "lookup-only"},
        "required": {"path", "key"},
        "outputs": {"cache-hit", "cache-primary-key", "cache-matched-key"},
        "read": "github.com/actions/cache restore/action.yml at tag v5 (27d5ce7, 2026-04-13)"},
    "actions/cache/save@v5": {
        "inputs": {"path", "key", "upload-chunk-size", "enableCrossOsArchive"},
        "required": {"path", "key"},
        "read": "github.com/actions/cache save/action.yml at tag v5 (27d5ce7, 2026-04-13)"},
    "classroom-resources/autograding-command-grader@v1": {
        "inputs": {"test-name", "setup-command", "command", "timeout", "max-score"},
        "required": {"test-name", "command"},
        "outputs": {"result"},
        "read": "github.com/classroom-resources/autograding-command-grader action.yml and "
                "src/main.js at tag v1 (d5b3fa6, 2024-05-01): timeout in minutes, max-score "
                "read with parseInt, commands run by execSync with PATH and HOME only"},
    "classroom-resources/autograding-grading-reporter@v1": {
        "inputs": {"token", "runners"},
        "required": {"runners"},
        "read": "github.com/classroom-resources/autograding-grading-reporter action.yml and "
                "src/main.js at tag v1 (d13b591, 2024-11-13): reads <RUNNER>_RESULTS for each "
                "id of `runners` (letters and digits), fails when one is missing"},
}
# What GitHub Classroom generates, and its reporter needs to upload the points (its README):
# the workflow's name, the one job's name, the triggers, the guard against the bot's first
# push, the permissions.
CLASSROOM = {"name": "Autograding Tests", "job": "run-autograding-tests",
             "on": {"push", "repository_dispatch"},
             "if": "github.actor != 'github-classroom[bot]'",
             "permissions": {"checks": "write", "actions": "read", "contents": "read"}}
GRADER = "classroom-resources/autograding-command-grader@v1"
REPORTER = "classroom-resources/autograding-grading-reporter@v1"


def lab_questions(root):
    """[(id "q5", "Q5", title, points)] from grading/lab.json, else grading/points.json."""
    manifest = root / "grading/lab.json"
    if manifest.is_file():
        data = json.loads(manifest.read_text())
        entries = data["questions"]
        if isinstance(entries, dict):
            entries = [dict(value, id=key) for key, value in entries.items()]
        found = []
        for entry in entries:
            q = str(entry.get("id") or entry.get("question") or entry.get("name")).upper()
            label = entry.get("label", q.lower())
            title = entry.get("title") or ", ".join(entry.get("titles", [])) or q
            found.append((label, q, title, entry["points"]))
        return found
    points = json.loads((root / "grading/points.json").read_text())["questions"]
    loader = importlib.machinery.SourceFileLoader("lab_report", str(root / "scripts/lab-report"))
    spec = importlib.util.spec_from_loader("lab_report", loader)
    report = importlib.util.module_from_spec(spec)
    loader.exec_module(report)
    return [(label, label.upper(), title, points[label.upper()])
            for label, title, _ in report.QUESTIONS if label.upper() in points]


HEADER = """\
# The lab's questions, checked on each push (GitHub Classroom's autograding, or any GitHub
# repository): the Debian 12 packages of scripts/setup.sh, the question tests built (ccache kept
# between runs), then one step per question: its tests (ctest -L '^q8$', as ./test.sh -L q8)
# earn its points when they all pass. The run's summary shows the table of the questions
# (scripts/lab-report). When a step before the tests fails (the packages, the build), every
# question reports 0 and says so.
# These points are your own feedback: they come from the tests of this repository, which you
# can edit. Your grade is your teacher's, by the teacher's own tests (scripts/grade of the
# teacher's copy, or Gradescope).
# BEGIN TEACHER
# Written by tests/grade/check_classroom.py --write from the lab's points: do not edit by hand
# (the test compares).
# The names are Classroom's own (its reporter uploads the points only from a workflow named
# "Autograding Tests" whose one job is run-autograding-tests). The container: Debian 12, where
# the project is built and tested (scripts/setup.sh's package names and versions), not
# ubuntu-latest, which moves. The graders run unless the run was cancelled, so that the
# reporter always has a result per question: 0 with the reason when the build did not succeed.
# END TEACHER
"""
# The guard of each grader's command: the build's outcome, else 0 with the reason in words.
BUILT = "${{ steps.build.outcome }}"
NOT_CANCELLED = "${{ !cancelled() }}"


def grader_guard(q):
    return (f'test "{BUILT}" = success || {{ echo "{q}: 0 points: the question tests were not '
            f'built (the step Build the question tests: {BUILT}); open the first failed step '
            'above"; exit 1; }; ')


def workflow_text(questions):
    ids = [label for label, _, _, _ in questions]
    graders = "".join(f"""\
      - name: "{q} {title}"
        id: {label}
        if: {NOT_CANCELLED}
        uses: {GRADER}
        with:
          test-name: "{q}: {title}"
          command: >-
            {grader_guard(q)}ctest --test-dir build -L '^{label}$' --no-tests=error
            --output-on-failure --timeout 60
          timeout: 5
          max-score: {points:g}
""" for label, q, title, points in questions)
    env = "".join(f"          {label.upper()}_RESULTS: \"${{{{ steps.{label}.outputs.result }}}}\"\n"
                  for label in ids)
    targets = " ".join(f"lab_{label}_tests" for label in ids)
    return HEADER + f"""\
name: Autograding Tests
'on':
  - push
  - repository_dispatch
  - workflow_dispatch
permissions:
  checks: write
  actions: read
  contents: read
jobs:
  run-autograding-tests:
    runs-on: ubuntu-latest
    if: github.actor != 'github-classroom[bot]'
    container: debian:12
    timeout-minutes: 30
    steps:
      - name: Tools to fetch the repository
        run: apt-get update -q && apt-get install -y -q --no-install-recommends git ca-certificates
      - name: Checkout code
        uses: actions/checkout@v7
      - name: Install the Debian packages of scripts/setup.sh
        run: |
          eval "$(sed -n '/^packages=(/,/^)/p' scripts/setup.sh)"
          scripts/install-packages.sh "${{packages[@]}}"
      # The compiler's cache: the last run's objects, so that a push recompiles only what
      # changed. Saved right after the build, whatever the grades (a failing question fails
      # the job, and actions/cache's combined step saves only on success).
      - name: Restore the compiler cache
        id: ccache
        uses: actions/cache/restore@v5
        with:
          path: .ccache
          key: ccache-debian12-${{{{ hashFiles('CMakeLists.txt', 'src/**', 'shaders/**', 'tests/**') }}}}
          restore-keys: ccache-debian12-
      - name: Build the question tests
        id: build
        continue-on-error: true
        run: |
          export CCACHE_DIR="$PWD/.ccache"
          ccache --zero-stats >/dev/null 2>&1 || true
          cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
          cmake --build build -j "$(nproc)" --target {targets}
          ccache --show-stats 2>/dev/null | grep -i -E 'hits|misses' || true
      - name: Save the compiler cache
        if: always() && steps.ccache.outputs.cache-hit != 'true'
        uses: actions/cache/save@v5
        with:
          path: .ccache
          key: ${{{{ steps.ccache.outputs.cache-primary-key }}}}
{graders}\
      - name: The table of the questions
        if: always()
        run: |
          ctest --test-dir build -L '^q[0-9]+$' --timeout 60 --output-junit "$PWD/build/lab.xml" >/dev/null || true
          python3 scripts/lab-report build build/lab.xml | tee -a "$GITHUB_STEP_SUMMARY"
      - name: Autograding Reporter
        if: always()
        uses: {REPORTER}
        env:
{env}\
        with:
          runners: {",".join(ids)}
"""


class Checks:
    def __init__(self):
        self.problems = []

    def __call__(self, condition, message):
        if not condition:
            self.problems.append(message)
            print("FAILED: " + message)
        return condition


def static_checks(root, check):
    """The file against the generator, Classroom's rules and the actions' real inputs."""
    import yaml  # python3-yaml
    questions = lab_questions(root)
    path = root / WORKFLOW
    if not check(path.is_file(), f"{WORKFLOW} is missing"):
        return None
    text = path.read_text()
    check(text == workflow_text(questions), f"{WORKFLOW} is not what the points give: run "
          f"python3 tests/grade/check_classroom.py . --write (and read the diff)")
    document = yaml.safe_load(text)
    check(document.get("name") == CLASSROOM["name"], "the workflow's name is not Classroom's")
    triggers = document.get("on", document.get(True))
    triggers = set(triggers if isinstance(triggers, (list, dict)) else [triggers])
    check(CLASSROOM["on"] <= triggers, f"triggers {sorted(triggers)}: push and "
          "repository_dispatch needed")
    check(document.get("permissions") == CLASSROOM["permissions"], "permissions differ from "
          f"{CLASSROOM['permissions']}")
    jobs = document.get("jobs", {})
    if not check(list(jobs) == [CLASSROOM["job"]], f"jobs {list(jobs)}: one job, "
                 f"{CLASSROOM['job']}"):
        return None
    job = jobs[CLASSROOM["job"]]
    check(job.get("if") == CLASSROOM["if"], "no guard against the Classroom bot's push")
    steps = job["steps"]
    ids = {}
    for step in steps:
        uses = step.get("uses")
        if uses is None:
            check("run" in step, f"step {step.get('name')}: neither run nor uses")
            continue
        if not check(uses in ACTIONS, f"step {step.get('name')}: {uses} is not an action whose "
                     "inputs were read (ACTIONS)"):
            continue
        given = set(step.get("with", {}))
        check(given <= ACTIONS[uses]["inputs"], f"step {step.get('name')}: inputs "
              f"{sorted(given - ACTIONS[uses]['inputs'])} are not {uses}'s")
        check(ACTIONS[uses]["required"] <= given, f"step {step.get('name')}: {uses} requires "
              f"{sorted(ACTIONS[uses]['required'] - given)}")
        if "id" in step:
            ids[step["id"]] = step
    graders = [s for s in steps if s.get("uses") == GRADER]
    by_label = {s["id"]: s for s in graders}
    for label, q, _, points in questions:
        step = by_label.get(label)
        if not check(step is not None, f"no grading step for {q}"):
            continue
        score = step["with"].get("max-score")
        check(isinstance(score, int) and score == points,
              f"{q}: max-score {score!r}, the points file says {points} (the grader reads an "
              "integer: parseInt)")
        check(f"-L '^{label}$'" in step["with"]["command"] and "--no-tests=error" in
              step["with"]["command"], f"{q}: the command does not run exactly the tests labelled "
              f"{label}, or passes when none is found")
        check(re.fullmatch(r"[A-Za-z0-9]+", label) is not None, f"{label}: the reporter takes "
              "letters and digits only")
        check(step.get("if") == NOT_CANCELLED and step["with"]["command"].startswith(
            grader_guard(q)), f"{q}: the grader does not run after a failed set-up, or does "
              "not report 0 with the reason then (the reporter would read no result)")
    check(len(graders) == len(questions), f"{len(graders)} grading steps for "
          f"{len(questions)} questions")
    reporters = [s for s in steps if s.get("uses") == REPORTER]
    if check(len(reporters) == 1 and steps[-1] is reporters[0], "the reporter is not the "
             "last step, once"):
        reporter = reporters[0]
        runners = reporter["with"]["runners"].split(",")
        check(runners == [s["id"] for s in graders], f"runners {runners} are not the graders")
        for runner in runners:
            check(reporter.get("env", {}).get(f"{runner.upper()}_RESULTS") ==
                  f"${{{{ steps.{runner}.outputs.result }}}}",
                  f"the reporter's env lacks {runner.upper()}_RESULTS")
        check(reporter.get("if") == "always()", "the reporter does not run when a grader fails")
    build = ids.get("build") or next((s for s in steps if s.get("id") == "build"), None)
    check(build is not None and build.get("continue-on-error") is True,
          "a build that fails must not skip the graders (each then scores 0, in words)")
    total = sum(p for _, _, _, p in questions)
    print(f"check_classroom: {len(steps)} steps, {len(graders)} graders, {total:g} points; "
          f"actions: {', '.join(sorted({s['uses'] for s in steps if 'uses' in s}))}")
    return steps


def run_step(step, folder, env, summary):
    """(exit status, output) of a `run:` step, as the runner runs it: bash -e FILE."""
    script = folder.parent / "step.sh"
    script.write_text(step["run"])
    environment = dict(env, GITHUB_STEP_SUMMARY=str(summary), GITHUB_WORKSPACE=str(folder),
                       CI="true", GITHUB_ACTIONS="true")
    done = subprocess.run(["bash", "-e", str(script)], cwd=folder, env=environment,
                          capture_output=True, text=True)
    return done.returncode, done.stdout + done.stderr


def grader_command(command, folder):
    """(exit status, output) of a grader's command, as the command grader runs it."""
    env = {"PATH": os.environ["PATH"], "HOME": os.environ.get("HOME", "/root"),
           "FORCE_COLOR": "true", "DOTNET_CLI_HOME": "/tmp", "DOTNET_NOLOGO": "true"}
    done = subprocess.run(["/bin/sh", "-c", command], cwd=folder, env=env, capture_output=True,
                          text=True)
    return done.returncode, done.stdout + done.stderr


def make_copy(root, dest, keep):
    arguments = [sys.executable, str(root / "scripts/make-student-version"), str(dest)]
    for q in keep:
        arguments += ["--keep", q]
    subprocess.run(arguments, check=True, capture_output=True)


def clean_clone(copy, dest):
    """The copy as a repository, cloned: only what the student would push."""
    git = ["git", "-c", "user.name=student", "-c", "user.email=student@example.invalid"]
    if not (copy / ".git").exists():
        subprocess.run(git + ["init", "-q", str(copy)], check=True)
    subprocess.run(git + ["-C", str(copy), "add", "-A"], check=True)
    subprocess.run(git + ["-C", str(copy), "commit", "-q", "--allow-empty", "-m", "push"],
                   check=True)
    shutil.rmtree(dest, ignore_errors=True)
    subprocess.run(["git", "clone", "-q", str(copy), str(dest)], check=True)


def run_workflow(steps, folder, summary, check, expect_pass, title, expect_built=True):
    """Every step in order, as the runner orders them (after a step that fails, only those
    that run always or unless cancelled); the graders' verdicts and points. expect_built
    False: the set-up is expected to fail, and every grader to say so."""
    earned = 0
    env = dict(os.environ)
    outcomes = {}  # step id -> success | failure | skipped (steps.<id>.outcome)
    failed = False  # a step failed (not continue-on-error): the job fails, the rest skips
    for step in steps:
        name = step.get("name", step.get("uses"))
        uses = step.get("uses", "")
        if failed and step.get("if") not in ("always()", NOT_CANCELLED) and \
                not str(step.get("if", "")).startswith("always()"):
            outcomes[step.get("id")] = "skipped"
            print(f"  [{title}] skipped after a failed step: {name}")
            continue
        if uses.startswith("actions/cache/restore"):
            # What a restore leaves: a ccache folder at .ccache; here this machine's own.
            cache = subprocess.run(["ccache", "--get-config", "cache_dir"], capture_output=True,
                                   text=True).stdout.strip()
            if cache and not (folder / ".ccache").exists():
                (folder / ".ccache").symlink_to(cache)
            print(f"  [{title}] {name}: .ccache is this machine's ccache folder")
            continue
        if uses.startswith("actions/cache/"):
            print(f"  [{title}] skipped: {name} (an action that only uploads .ccache)")
            continue
        if uses.startswith("actions/checkout"):
            print(f"  [{title}] {name}: the clean clone stands in for it")
            continue
        if uses == REPORTER:
            continue
        if "run" in step:
            if step["name"].startswith("Tools to fetch"):
                # apt-get in the container: here the tools are installed already.
                check(shutil.which("git") is not None, "git is missing here")
                continue
            started = time.monotonic()
            code, output = run_step(step, folder, env, summary)
            print(f"  [{title}] {name}: exit {code} in {time.monotonic() - started:.0f} s")
            outcomes[step.get("id")] = "success" if code == 0 else "failure"
            if step.get("continue-on-error"):
                # The build: it must pass on the solution, fail where the set-up is broken.
                wanted = (code != 0) if not expect_built else (code == 0 or not expect_pass)
                check(wanted, f"[{title}] {name}: exit {code}:\n{output[-2000:]}")
            elif step.get("if") != "always()":
                check(code == 0, f"[{title}] {name} failed:\n{output[-2000:]}")
                failed = failed or code != 0
            continue
        if uses == GRADER:
            inputs = step["with"]
            code = 0
            if inputs.get("setup-command"):
                code, output = grader_command(inputs["setup-command"], folder)
            if code == 0:
                code, output = grader_command(inputs["command"].replace(
                    BUILT, outcomes.get("build", "skipped")), folder)
            passed = code == 0
            earned += inputs.get("max-score", 0) if passed else 0
            print(f"  [{title}] {inputs['test-name']}: {'pass' if passed else 'fail'}")
            check(passed == expect_pass, f"[{title}] {inputs['test-name']}: "
                  f"{'failed' if expect_pass else 'passed'}, expected the opposite:\n"
                  f"{output[-1500:]}")
            if not expect_built:
                check("0 points: the question tests were not built" in output,
                      f"[{title}] {inputs['test-name']}: a failed set-up is not said:\n"
                      f"{output[-1500:]}")
    return earned


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    root = Path(sys.argv[1]).resolve()
    mode = sys.argv[2] if len(sys.argv) > 2 else ""
    if mode == "--write":
        (root / WORKFLOW).parent.mkdir(parents=True, exist_ok=True)
        (root / WORKFLOW).write_text(workflow_text(lab_questions(root)))
        print(f"{WORKFLOW} written")
        return 0
    try:
        import yaml  # noqa: F401
    except ImportError:
        print("check_classroom: python3-yaml is not installed (apt-get install python3-yaml): "
              "skipped")
        return 77
    check = Checks()
    started = time.monotonic()
    steps = static_checks(root, check)
    if steps is not None and mode != "--static":
        questions = lab_questions(root)
        total = sum(p for _, _, _, p in questions)
        work = Path(tempfile.mkdtemp(prefix="clothlab-classroom-"))
        try:
            copy = work / "copy"
            make_copy(root, copy, [])
            check((copy / WORKFLOW).is_file(), f"the student copy lacks {WORKFLOW}")
            clone = work / "clone"
            clean_clone(copy, clone)
            summary = work / "summary.md"
            earned = run_workflow(steps, clone, summary, check, False, "stubs")
            check(earned == 0, f"the stubs earn {earned:g} points")
            check("TO DO" in summary.read_text(), "the run's summary has no table of the "
                  "questions")
            # Every solution kept, pushed on top: the graders rebuild what changed and pass.
            make_copy(root, copy, [q for _, q, _, _ in questions])
            clean_clone(copy, clone)
            earned = run_workflow(steps, clone, summary, check, True, "solution")
            check(earned == total, f"the solution earns {earned:g} of {total:g} points")
            # A set-up that fails (the build, here its configuration): every question reports
            # 0 with the reason, none is left without a result.
            with open(clone / "CMakeLists.txt", "a") as f:
                f.write('\nmessage(FATAL_ERROR "a set-up that fails")\n')
            earned = run_workflow(steps, clone, summary, check, False, "set-up fails",
                                  expect_built=False)
            check(earned == 0, f"a failed set-up earns {earned:g} points")
        finally:
            if not check.problems:
                shutil.rmtree(work, ignore_errors=True)
            else:
                print(f"(the copies are left in {work})")
    print(f"check_classroom: {time.monotonic() - started:.0f} s")
    if check.problems:
        print(f"{len(check.problems)} problem(s) with {WORKFLOW}")
        return 1
    print(f"{WORKFLOW}: Classroom's names, real actions and inputs, the points of the lab" +
          ("" if mode == "--static" else ", and its commands pass here"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
