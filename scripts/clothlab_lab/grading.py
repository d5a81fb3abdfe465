"""Grading a class: the kit (the student copy, built once), then for each submission, in its
scratch folder and in the sandbox: its files unpacked, the student's own taken, built into a copy
of the kit, its question tests run; the scores and the outputs, whatever a submission holds.

The kit's folder (--work, or --kit):
    manifest.json   the lab (grading/lab.json) and the copy's version, as when the kit was made
    stubs/          the student's files as handed out
    base/copy/      the student copy and its build (build-grade/), made by the grader itself
A submission's only writable place is its scratch folder, /var/tmp/clothlab-grade/<hash of the
kit's path> (a sized tmpfs where root may mount one): base/copy is copied there before each
submission, and it is emptied after. The build is configured for that folder's copy/, so that
each submission's build there is incremental: only the student's files are compiled, and the
question tests relinked.
"""
import concurrent.futures
import fcntl
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ElementTree
from pathlib import Path

from . import manifest as lab_manifest
from . import regions, reports, sandbox as confinement, submissions
from .manifest import MARKER_FILE, ROOT
from .submissions import content_version, copy_files, marker_version

MAX_MESSAGES = 3  # failed checks shown per test (a loop over every vertex may fail hundreds)


SIGNAL_WORDS = {signal.SIGSEGV: "a segmentation fault (memory accessed out of bounds, or a null "
                                "pointer)", signal.SIGABRT: "an abort (a failed assertion, or an "
                                "exception not caught)", signal.SIGFPE: "a floating-point "
                                "exception (an integer divided by zero?)",
                signal.SIGBUS: "a bus error", signal.SIGILL: "an illegal instruction"}


class GradeError(Exception):
    """The grader itself cannot run (not a student's fault)."""


def say(message):
    print(message, file=sys.stderr, flush=True)


def sync(source, dest):
    """Makes dest's files those of source, writing only what changed (builds stay incremental);
    dest's build folders are left alone."""
    wanted = copy_files(source)
    for name, data in wanted.items():
        target = dest / name
        if not (target.is_file() and target.read_bytes() == data):
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
        os.chmod(target, (source / name).stat().st_mode & 0o777)
    for name in set(copy_files(dest)) - set(wanted):
        (dest / name).unlink()


def scratch_of(work):
    """A submission's scratch folder: fixed for a kit (its build is configured there), and
    apart from the kit and from everything else of the grader's, so that, where no namespace
    hides the rest, the folders above it lead nowhere (/var/tmp/clothlab-grade/<kit's hash>)."""
    top = Path("/var/tmp") if Path("/var/tmp").is_dir() else Path(tempfile.gettempdir())
    return top / "clothlab-grade" / hashlib.sha256(str(work).encode()).hexdigest()[:12]


def kit_copy(work):
    """The folder where the copy is built and each submission is graded."""
    return scratch_of(work) / "copy"


def build_dir(work):
    return kit_copy(work) / "build-grade"


def prepare_from_teacher(work, box, jobs):
    """The kit of this repository, generated and built; (lab, version)."""
    generate_kit(work)
    restore_base(work, box)
    build_base(work, read_kit(work)[0], jobs)
    return read_kit(work)


def generate_kit(work):
    """Generates the student copy of this repository into work/base/copy (only the files that
    changed: its build stays incremental), its stubs into work/stubs, and work/manifest.json."""
    try:
        lab = lab_manifest.load()
    except lab_manifest.ManifestError as error:
        raise GradeError(str(error))
    if not regions.scan_regions(ROOT):
        raise GradeError(f"{ROOT}: no solution region in src/ or shaders/: is this the teacher's "
                         "copy?")
    with tempfile.TemporaryDirectory(prefix="clothlab-grade-") as tmp:
        generated = Path(tmp) / "copy"
        made = subprocess.run([sys.executable, str(ROOT / "scripts/make-student-version"),
                               str(generated)], capture_output=True, text=True)
        if made.returncode != 0:
            raise GradeError("make-student-version failed:\n" + made.stderr)
        files = copy_files(generated)
        version = marker_version(files.get(MARKER_FILE)) or \
            content_version(files, lab.student_files)
        shutil.rmtree(work / "stubs", ignore_errors=True)
        for name in lab.student_files:
            (work / "stubs" / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(generated / name, work / "stubs" / name)
        (work / "manifest.json").write_text(json.dumps({"version": version, **lab.to_json()},
                                                       indent=1) + "\n")
        (work / "base" / "copy").mkdir(parents=True, exist_ok=True)
        os.chmod(work / "base", 0o700)
        sync(generated, work / "base" / "copy")


def restore_base(work, box):
    """The scratch folder emptied, then the kit's copy and build put back there."""
    base = work / "base"
    box.reset(base if (base / "copy").is_dir() else None)


def build_base(work, lab, jobs):
    """Builds the kit (the stubs: the teacher's code only, outside the sandbox, with ccache)
    and keeps it in work/base, from which each submission starts."""
    ok, output = build_outside(work, lab, jobs)
    if not ok:
        raise GradeError("the student copy (the stubs) does not build:\n" +
                         first_error(output, kit_copy(work)))
    base = work / "base"
    shutil.rmtree(base, ignore_errors=True)
    base.mkdir(mode=0o700)
    subprocess.run(["cp", "-a", str(kit_copy(work)), str(base / "copy")], check=True)
    subprocess.run(["chown", "-R", f"{os.geteuid()}:{os.getegid()}", str(base)], check=True)


def build_outside(work, lab, jobs):
    folder = build_dir(work)
    if not (folder / "CMakeCache.txt").exists():
        generator = ["-G", "Ninja"] if shutil.which("ninja") else []
        # PRE_TEST: the test programs are listed when ctest runs on the stubs, never after a
        # student's link (a student's program runs only in the sandbox).
        configured = subprocess.run(
            ["cmake", "-S", str(kit_copy(work)), "-B", str(folder), *generator,
             "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_GTEST_DISCOVER_TESTS_DISCOVERY_MODE=PRE_TEST"],
            capture_output=True, text=True)
        if configured.returncode != 0:
            raise GradeError("cmake could not configure the student copy:\n" +
                             configured.stdout[-3000:] + configured.stderr[-3000:])
    process = subprocess.run(build_command(work, lab, jobs), stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, text=True, errors="replace")
    return process.returncode == 0, process.stdout


def build_command(work, lab, jobs):
    folder = build_dir(work)
    keep_going = ["-k", "0"] if (folder / "build.ninja").exists() else ["-k"]
    return ["cmake", "--build", str(folder), "-j", str(jobs), "--target",
            *lab_targets(lab), "--", *keep_going]


def build_submission(work, lab, box, jobs):
    """Builds the student's files into the kit's copy, in the sandbox; (ok, output)."""
    log = scratch_of(work) / "build.log"
    home = scratch_of(work) / "home"
    home.mkdir(exist_ok=True)
    if box.root:
        os.chown(home, box.uid, box.uid)
    limit = box.limits.build_seconds
    with open(log, "wb") as out:
        code, timed_out = box.run(build_command(work, lab, jobs), limit,
                                  confinement.environment(home), out, cwd=kit_copy(work),
                                  cpu_seconds=limit)
    output = confinement.read_written(log, 4 * confinement.MiB).decode("utf-8", "replace")
    if timed_out:
        return False, f"the build did not finish within {limit:g} s; stopped\n{output[-3000:]}"
    if code in (-signal.SIGXCPU, 128 + signal.SIGXCPU, -signal.SIGKILL):
        return False, f"the build was stopped (a limit of processor time or memory)\n" \
                      f"{output[-3000:]}"
    return code == 0, output


def read_kit(work):
    """(lab, version) of a prepared kit: the manifest as it was when the kit was made."""
    try:
        data = json.loads((work / "manifest.json").read_text())
        return lab_manifest.parse(data, str(work / "manifest.json")), data["version"]
    except (OSError, ValueError, KeyError, lab_manifest.ManifestError) as error:
        raise GradeError(f"{work}: not a prepared kit ({error})")


def lab_targets(lab):
    return [q.target for q in lab.questions]


def list_tests(work, lab):
    """[(question, test name, [program, arguments...])] of the kit's build, from ctest."""
    listing = subprocess.run(["ctest", "--test-dir", str(build_dir(work)), "--show-only=json-v1"],
                             capture_output=True, text=True)
    if listing.returncode != 0:
        raise GradeError("ctest cannot list the question tests:\n" + listing.stderr[-2000:])
    tests = []
    for test in json.loads(listing.stdout).get("tests", []):
        labels = [v for p in test.get("properties", []) if p["name"] == "LABELS"
                  for v in p["value"]]
        for label in labels:
            if label.upper() in lab.ids:
                tests.append((label.upper(), test["name"], test["command"]))
    if not tests:
        raise GradeError("the build lists no question test (labels q5 ... q13)")
    return tests


def run_program(command, run_dir, number, box, output_limit, timeout):
    """Runs one test program as the submission; returns (kind, messages, cases): kind "ran"
    with cases {GoogleTest name: (passed | failed, messages)}, else timeout | output | crashed,
    with messages."""
    xml_path = run_dir / "results" / f"{number}.xml"
    log_path = run_dir / "results" / f"{number}.log"
    command = command + [f"--gtest_output=xml:{xml_path}"]
    # The shaders and assets the tests read: those of the submission's copy (its own shaders).
    env = confinement.environment(run_dir / "home", run_dir.parent / "copy")
    with open(log_path, "wb") as log:
        code, timed_out = box.run(command, timeout, env, log, cwd=run_dir / "cwd",
                                  file_size=output_limit, cpu_seconds=int(timeout) + 2)
    if timed_out:
        return "timeout", [f"did not finish within {timeout:g} s (an endless loop? a loop "
                           "whose end condition never holds?); stopped"], None
    log_bytes = confinement.read_written(log_path, output_limit + 1)
    output = log_bytes[-4000:].decode("utf-8", "replace")
    if code in (-signal.SIGXFSZ, 128 + signal.SIGXFSZ) or len(log_bytes) >= output_limit:
        return "output", [f"wrote more than {output_limit // 1024} KB of output (or of "
                          "files); stopped. Remove the prints from the code that runs every "
                          "step"], None
    if code in (-signal.SIGXCPU, 128 + signal.SIGXCPU):
        return "timeout", [f"used more than {timeout:g} s of processor time; stopped"], None
    try:
        root = ElementTree.fromstring(confinement.read_written(xml_path, output_limit))
    except ElementTree.ParseError:
        if code < 0 or code > 128:
            number_of_signal = -code if code < 0 else code - 128
            words = SIGNAL_WORDS.get(number_of_signal, f"signal {number_of_signal}")
            return "crashed", [f"crashed: {words}"], None
        return "crashed", [f"stopped with exit status {code} before the test could report (does "
                           f"the code call exit()?). Last output:\n{tail_lines(output, 6)}"], None
    cases = {}
    for case in root.iter("testcase"):
        messages = [clean_message(f.get("message") or f.text or "")
                    for f in list(case.iter("failure")) + list(case.iter("error"))]
        if len(messages) > MAX_MESSAGES:
            messages = messages[:MAX_MESSAGES] + [f"... and {len(messages) - MAX_MESSAGES} "
                                                  "more failed checks in this test"]
        cases[f"{case.get('classname')}.{case.get('name')}"] = (
            ("failed", messages) if messages else ("passed", []))
    if code != 0 and not any(status == "failed" for status, _ in cases.values()):
        return "crashed", [f"exit status {code} although no check failed. Last output:\n"
                           f"{tail_lines(output, 6)}"], None
    return "ran", [], cases


def run_tests(work, tests, box, jobs, budget):
    """{test name: (status, messages)} for every test, as the submission, in a fresh folder of
    its scratch. Each test program runs its tests at once; when it does not report (a loop, a
    crash, a flood), each of its tests runs alone, so that the report says which."""
    limits = box.limits
    run_dir = scratch_of(work) / "run"
    shutil.rmtree(run_dir, ignore_errors=True)
    for sub in ("cwd", "home", "results"):
        (run_dir / sub).mkdir(parents=True)
    if box.root:
        for path in (run_dir, *(run_dir / sub for sub in ("cwd", "home", "results"))):
            os.chown(path, box.uid, box.uid)
    programs = {}  # the build's program -> [(test name, GoogleTest name)]
    for _, name, command in tests:
        programs.setdefault(Path(command[0]), []).append((name, gtest_filter(command)))
    started = time.monotonic()
    results = {}
    numbers = iter(range(1_000_000))

    def spent():
        return time.monotonic() - started > budget

    def whole(program):
        members = programs[program]
        if spent():
            return program, ("budget", [], None)
        command = [str(program), "--gtest_filter=" + ":".join(f for _, f in members)]
        return program, run_program(command, run_dir, next(numbers), box, limits.test_output,
                                    2 * limits.test_seconds)

    def alone(program, name, test_filter):
        if spent():
            return name, ("timeout", [f"not run: this submission's {budget:g} s for its tests "
                                      "were spent (by tests that did not finish)"])
        kind, messages, cases = run_program(
            [str(program), f"--gtest_filter={test_filter}"], run_dir, next(numbers), box,
            limits.test_output, limits.test_seconds)
        if kind == "ran" and test_filter in cases:
            return name, cases[test_filter]
        return name, (kind if kind != "ran" else "crashed", messages or ["did not report"])

    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        again = []
        for program, (kind, _, cases) in pool.map(whole, list(programs)):
            members = programs[program]
            if kind == "ran" and all(f in cases for _, f in members):
                results.update({name: cases[f] for name, f in members})
            else:
                again += [(program, name, f) for name, f in members]
        for name, result in pool.map(lambda item: alone(*item), again):
            results[name] = result
    box.end_all()  # nothing of the submission outlives its tests
    # Paths as the student knows them: shaders/gpu_step.frag, not the scratch folder's.
    data = str(kit_copy(work)) + "/"
    return {name: (status, [m.replace(data, "") for m in messages])
            for name, (status, messages) in results.items()}


def tail_lines(text, count):
    return "\n".join(text.strip().splitlines()[-count:])


def clean_message(message):
    """A GoogleTest failure as the student reads it: the test's own words and the values, not
    the file and line or the 'Value of: ... Actual: false / Expected: true' of EXPECT_TRUE."""
    lines = message.strip().splitlines()
    if lines and re.match(r"^\S+:\d+$", lines[0]):
        lines = lines[1:]
    if len(lines) >= 3 and lines[0].startswith("Value of:") and lines[1].strip() == \
            "Actual: false" and lines[2].strip() == "Expected: true":
        lines = lines[3:]
    text = "\n".join(lines).strip()
    return text[:2000] + (" ..." if len(text) > 2000 else "")


def gtest_filter(command):
    return next((a.split("=", 1)[1] for a in command if a.startswith("--gtest_filter=")), "*")


DIAGNOSTIC = re.compile(r"^(?P<file>[^\s:][^:]*):(?P<line>\d+):(?:\d+:)? (?:fatal )?error: ")


NEXT_DIAGNOSTIC = re.compile(r"^[^\s:][^:]*:(\d+:)+ (warning|error): |^[^\s:][^:]*: In ")


def first_error(output, copy_folder, in_file=None):
    """The compiler's first error (in in_file, if given), as the student would read it (paths
    relative to the copy)."""
    text = output.replace(str(copy_folder) + "/", "")
    text = re.sub(r"(^|\s)(?:\.\./)+((?:src|shaders|tests)/)", r"\1\2", text, flags=re.MULTILINE)
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if in_file and not (DIAGNOSTIC.match(line) and
                            DIAGNOSTIC.match(line).group("file").endswith(in_file)):
            continue
        if DIAGNOSTIC.match(line) or "undefined reference" in line or \
                "multiple definition" in line or "did not finish within" in line:
            start = i - 1 if i > 0 and ": In " in lines[i - 1] else i
            block = [lines[start]] if start < i else []
            block.append(line)
            for following in lines[i + 1:i + 6]:
                if DIAGNOSTIC.match(following) or NEXT_DIAGNOSTIC.match(following) or re.match(
                        r"^(ninja|make|\[|FAILED)", following):
                    break
                block.append(following)
            return "\n".join(block)
    return tail_lines(text, 10)


def files_with_errors(output, student_files):
    failing = set()
    for line in output.splitlines():
        match = DIAGNOSTIC.match(line)
        if match:
            for name in student_files:
                if match.group("file").endswith(name):
                    failing.add(name)
    return failing


def write_student_files(work, lab, taken):
    """The student's files (taken, else the stubs) into the kit's copy."""
    for name in lab.student_files:
        data = taken.get(name)
        if data is None:
            data = (work / "stubs" / name).read_bytes()
        target = kit_copy(work) / name
        if not (target.is_file() and target.read_bytes() == data):
            target.write_bytes(data)


def score_question(question, tests, results, guards, points, partial):
    """(score, passed, total, failures [(test, messages, status)])."""
    names = [name for q, name, _ in tests if q == question]
    passed = [n for n in names if results[n][0] == "passed"]
    failures = [(n, results[n][1], results[n][0]) for n in names if results[n][0] != "passed"]
    if not partial or not names:
        score = points if names and len(passed) == len(names) else 0.0
    else:
        # Each test that fails on the stub is an equal share; a test that already passes on the
        # stub (a guard against breaking what worked) earns nothing, but failing costs a share.
        graded = len(names) - len([n for n in names if n in guards])
        if graded <= 0:
            score = points if len(passed) == len(names) else 0.0
        else:
            score = points * max(0, len(passed) - (len(names) - graded)) / graded
    return round(score, 2), len(passed), len(names), failures


def short_name(test):
    return test.split(".")[-1]


def read_submission(work, lab, version, reference, submission, box):
    """({student file: bytes}, [notes]) of a submission: copied into the scratch folder as it
    is (bounded), unpacked there by unpack.py in the sandbox, its student copy found."""
    scratch = scratch_of(work)
    unpacked = scratch / "unpacked"
    limits = box.limits
    source, notes = submissions.stage(submission, scratch / "submission", limits)
    shutil.copyfile(Path(submissions.__file__).with_name("unpack.py"), scratch / "unpack.py")
    if box.root:
        subprocess.run(["chown", "-R", f"{box.uid}:{box.uid}", str(scratch / "submission"),
                        str(scratch / "unpack.py")], check=True)
    log = scratch / "unpack.log"
    with open(log, "wb") as out:
        code, timed_out = box.run(
            ["python3", "-I", "-S", str(scratch / "unpack.py"), str(source), str(unpacked),
             str(limits.submission), str(limits.entries), str(limits.student_file)],
            120, confinement.environment(scratch), out, cwd=scratch,
            file_size=limits.student_file + 1)
    said = confinement.read_written(log, 1 << 20).decode("utf-8", "replace").strip()
    shutil.rmtree(scratch / "submission", ignore_errors=True)
    try:
        result = json.loads(said.splitlines()[-1])
    except (ValueError, IndexError):
        result = {"error": "the unpacking stopped (" + ("it took more than 120 s" if timed_out
                                                         else f"exit status {code}") + ")"}
    if "error" in result:
        raise ValueError(result["error"])
    notes += result.get("notes", [])
    root = submissions.find_root(unpacked, lab.student_files)
    taken, found = submissions.take_student_files(root, unpacked, lab.student_files, reference,
                                                  version, limits.student_file)
    shutil.rmtree(unpacked, ignore_errors=True)
    return taken, notes + found


def grade_one(work, lab, version, reference, tests, guards, submission, name, args, box):
    """A dict with everything known of one submission's grade."""
    started = time.monotonic()
    questions = lab.ids
    points = lab.points
    record = {"name": name, "submission": submissions.printable(str(submission)), "notes": [],
              "questions": {}, "build_error": None}
    restore_base(work, box)  # nothing of the previous submission is left
    try:
        taken, notes = read_submission(work, lab, version, reference, submission, box)
        record["notes"] += notes
    except (ValueError, OSError) as error:
        taken = {}
        record["notes"].append(f"cannot be read: {submissions.printable(str(error))}")
    if not taken:
        record["notes"].append("no student file found (" + ", ".join(lab.student_files)
                               + "): not a clothlab student copy? Every question gets 0")
        for q in questions:
            record["questions"][q] = {"score": 0.0, "passed": 0, "tests": 0, "status": "missing",
                                      "failures": [], "output": "no student file was handed in"}
        return finish(record, started, points)

    write_student_files(work, lab, taken)
    build_started = time.monotonic()
    ok, output = build_submission(work, lab, box, args.jobs)
    broken = {}  # question -> compiler's first error
    if not ok:
        failing = files_with_errors(output, lab.student_files)
        if failing:
            # Those files are graded as their stubs, and their questions as not compiling.
            for f in failing:
                taken.pop(f, None)
            for q in lab.questions:
                for f in sorted(set(q.files) & failing):
                    broken[q.id] = first_error(output, kit_copy(work), f)
            write_student_files(work, lab, taken)
            ok, output = build_submission(work, lab, box, args.jobs)
            record["notes"].append("does not compile: " + ", ".join(sorted(failing)) +
                                   " (graded as the stub; its questions get 0)")
        if not ok:
            record["build_error"] = first_error(output, kit_copy(work))
            record["notes"].append("the build fails: every question gets 0")
            for q in questions:
                record["questions"][q] = {"score": 0.0, "passed": 0, "tests": 0,
                                          "status": "build error", "failures": [],
                                          "output": "does not compile:\n" + record["build_error"]}
            return finish(record, started, points)
    tests_started = time.monotonic()
    record["build_seconds"] = round(tests_started - build_started, 1)
    results = run_tests(work, tests, box, args.jobs, box.limits.test_budget)
    record["test_seconds"] = round(time.monotonic() - tests_started, 1)
    for q in questions:
        score, passed, total, failures = score_question(q, tests, results, guards,
                                                        points[q], lab.partial_credit)
        if q in broken:
            record["questions"][q] = {"score": 0.0, "passed": 0, "tests": total,
                                      "status": "build error", "failures": [],
                                      "output": "does not compile:\n" + broken[q]}
            continue
        status = "done" if passed == total else "to do"
        lines = [f"{passed}/{total} tests passed: {score:g} of {points[q]:g} points"]
        for test, messages, kind in failures:
            lines.append(f"\nFAILED {short_name(test)}" + ("" if kind == "failed" else
                                                            f" ({kind})") + ":")
            lines += ["  " + m.replace("\n", "\n  ") for m in messages]
        record["questions"][q] = {"score": score, "passed": passed, "tests": total,
                                  "status": status, "output": "\n".join(lines),
                                  "failures": [(short_name(t), m[0] if m else "", kind)
                                               for t, m, kind in failures]}
        if any(kind != "failed" for _, _, kind in failures):
            kinds = sorted({kind for _, _, kind in failures if kind != "failed"})
            record["notes"].append(f"{q}: tests that " + " / ".join(
                {"timeout": "did not finish", "crashed": "crashed",
                 "output": "printed too much"}.get(k, k) for k in kinds))
    return finish(record, started, points)


def finish(record, started, points):
    record["score"] = round(sum(q["score"] for q in record["questions"].values()), 2)
    record["max_score"] = sum(points.values())
    record["seconds"] = round(time.monotonic() - started, 1)
    return record


def progress(k, n, name, started, durations):
    elapsed = time.monotonic() - started
    later = durations[1:] or durations
    left = (n - k) * (sum(later) / len(later)) if later else 0
    line = (f"[{k}/{n}] {name}: elapsed {int(elapsed // 60)} min {int(elapsed % 60):02d} s, "
            f"about {int(left // 60)} min {int(left % 60):02d} s left")
    if sys.stderr.isatty():
        print("\r" + line.ljust(100), end="" if k < n else "\n", file=sys.stderr, flush=True)
    else:
        say(line)


def grade_class(args):
    """Grades args.submissions into args.out (or only prepares the kit); the exit status.
    args: the command line of scripts/grade."""
    box = None
    # A grader stopped by SIGTERM (a time-out of ctest, kill) still ends its submissions'
    # processes, unmounts its scratch and removes its cgroup (the finally below).
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    try:
        work = (args.kit or args.work).resolve()
        work.mkdir(parents=True, exist_ok=True)
        lock = open(work / ".lock", "w")
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            raise GradeError(f"another grade runs in {work}: wait for it, or give --work")
        started = time.monotonic()
        limits = confinement.Limits(build_seconds=args.build_timeout, test_seconds=args.timeout,
                                    test_budget=args.test_budget,
                                    test_output=args.output_limit * 1024,
                                    **({"scratch": args.scratch_size * confinement.MiB}
                                       if args.scratch_size else {}))
        try:
            box = confinement.Sandbox(scratch_of(work), limits, enabled=not args.no_sandbox)
        except confinement.SandboxError as error:
            raise GradeError(str(error))
        if args.kit:
            lab, version = read_kit(work)
            restore_base(work, box)
            write_student_files(work, lab, {})
            build_base(work, lab, args.jobs)
        else:
            lab, version = prepare_from_teacher(work, box, args.jobs)
        if box.kind == "user" and not args.kit and \
                confinement.readable_by_submission(box, ROOT / "docs/answers.md"):
            raise GradeError(f"bubblewrap cannot run here, and the submissions' user could read "
                             f"the teacher's files ({ROOT / 'docs/answers.md'}): close the "
                             "repository to other users (chmod o-rwx), or grade with the "
                             "Gradescope bundle's kit (--kit), which holds no solution")
        if args.points:
            try:
                lab = lab_manifest.with_points(lab, args.points)
            except lab_manifest.ManifestError as error:
                raise GradeError(str(error))
        tests = list_tests(work, lab)
        say(f"grade: the student copy is built ({time.monotonic() - started:.0f} s), "
            f"{len(tests)} question tests; sandbox: {box.description}")
        # The tests that pass on the stubs (guards: they earn no points), found once for a kit:
        # --prepare keeps them in guards.json (the Gradescope image), each submission reads it.
        guards_file = work / "guards.json"
        if args.kit and guards_file.is_file() and not args.prepare:
            guards = set(json.loads(guards_file.read_text()))
        else:
            restore_base(work, box)
            stub_results = run_tests(work, tests, box, args.jobs, 600)
            guards = {name for name, (status, _) in stub_results.items() if status == "passed"}
            if args.kit:
                guards_file.write_text(json.dumps(sorted(guards), indent=1) + "\n")
        if args.prepare:
            if args.kit:
                say(f"grade: {len(guards)} tests pass on the stubs (guards), kept in "
                    f"{guards_file}")
            return 0
        reference = {n: d for n, d in copy_files(work / "base" / "copy").items()
                     if n not in lab.student_files}

        args.out.mkdir(parents=True, exist_ok=True)
        if box.kind == "user":
            os.chmod(args.out, 0o700)  # no submission reads the others' grades
        records, durations, used = [], [], set()
        for k, submission in enumerate(args.submissions, 1):
            name = submissions.unique_name(Path(args.name[k - 1]) if k <= len(args.name)
                                           else submission, used)
            began = time.monotonic()
            try:
                record = grade_one(work, lab, version, reference, tests, guards,
                                   submission.absolute(), name, args, box)
            except Exception as error:  # noqa: BLE001 (whatever a submission holds, the batch goes on)
                record = {"name": name, "submission": submissions.printable(str(submission)),
                          "build_error": None,
                          "notes": [f"could not be graded: {type(error).__name__}: "
                                    f"{submissions.printable(str(error))}"],
                          "questions": {q: {"score": 0.0, "passed": 0, "tests": 0,
                                            "status": "missing", "failures": [],
                                            "output": "could not be graded"}
                                        for q in lab.ids}}
                record = finish(record, began, lab.points)
            durations.append(time.monotonic() - began)
            records.append(record)
            write_results(args, record, lab, version, box.description)
            if not sys.stderr.isatty():
                say(f"grade: {name}: {record['score']:g}/{record['max_score']:g} "
                    f"({durations[-1]:.0f} s)")
            progress(k, len(args.submissions), name, started, durations)
        reports.write_csv(args.out / "grades.csv", records, lab)
        reports.write_report(args.out / "report.html", records, lab, version, box.description,
                             time.monotonic() - started)
        say(f"grade: {len(records)} submissions graded in {time.monotonic() - started:.0f} s: "
            f"{args.out / 'grades.csv'}, {args.out / 'report.html'}")
        return 0
    except GradeError as error:
        say(f"grade: {error}")
        return 1
    finally:
        if box is not None:
            box.release()


def write_results(args, record, lab, version, confinement):
    folder = args.out / record["name"]
    folder.mkdir(parents=True, exist_ok=True)
    results = reports.gradescope_results(record, lab, version, confinement)
    text = json.dumps(results, indent=1) + "\n"
    (folder / "results.json").write_text(text)
    (folder / "junit.xml").write_text(reports.junit_xml(record, lab), errors="replace")
    if args.gradescope_results:
        args.gradescope_results.parent.mkdir(parents=True, exist_ok=True)
        args.gradescope_results.write_text(text)
