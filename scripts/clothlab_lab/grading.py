"""Grading a class: the kit (the student copy, built once, and its checkers), then for each
submission, in its scratch folder and in the sandbox: its files unpacked, the student's own
taken, built into a copy of the kit, its question tests run; the scores and the outputs,
whatever a submission holds.

The kit (kits.py) is made once in --work (or --kit), root's and closed to every other user;
beside it the grader keeps verdicts/ (what the checkers write), logs/ (the sandboxed steps'
output) and, in the fallback, staged/ (the submissions, copied before the first one runs).
A submission's scratch folder, /var/tmp/clothlab-grade/<hash of the kit's path> (a sized tmpfs
where root may mount one), is root's too: base/copy is copied there before each submission as
copy/, the submission's to write only while it builds its runner there, read-only to its tests,
which write only run/. The build is configured for that copy/, so that each submission's build
is incremental: the student's files compiled, the runner (lab_runner) relinked. The checkers run
as the grader, from checkers/, and start that runner in the sandbox; nothing that a
submission can write is ever run, trusted or read by the grader outside it.
"""
import concurrent.futures
import fcntl
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
from . import reports, sandbox as confinement, submissions
from . import messages
from .kits import (KIT_FORMAT, RUNNER, GradeError, Kit, build_dir, generate_kit, kit_copy,
                   kit_language, lab_targets, languages_of_copies, make_checkers,
                   private_folder, read_kit, record_kit, runner_path, scratch_of)
from .manifest import ROOT
from .messages import N_, _
from .submissions import copy_files

MAX_MESSAGES = 3  # failed checks shown per test (a loop over every vertex may fail hundreds)


SIGNAL_WORDS = {signal.SIGSEGV: N_("a segmentation fault (memory accessed out of bounds, or a "
                                   "null pointer)"),
                signal.SIGABRT: N_("an abort (a failed assertion, or an exception not caught)"),
                signal.SIGFPE: N_("a floating-point exception (an integer divided by zero?)"),
                signal.SIGBUS: N_("a bus error"), signal.SIGILL: N_("an illegal instruction")}


def say(message):
    print(message, file=sys.stderr, flush=True)


def prepare_kit(work, box, args):
    """The kit, made (from this repository, or --kit --prepare: the bundle's) or, for --kit,
    checked; (lab, version, Kit)."""
    jobs = args.jobs
    if args.kit and not args.prepare:
        lab, version = read_kit(work)
        kit = Kit(work, lab)
        if kit.guards is None:
            raise GradeError(f"{work}: the kit has no guards.json: make it with --prepare")
        # The copy's build, brought up to date here (where it was made, nothing to do).
        restore_base(work, box)
        write_student_files(work, lab, {})
        build_base(work, lab, jobs)
        kit.verify()
        return lab, version, kit
    if not args.kit:
        if args.lang not in languages_of_copies():
            raise GradeError(f"--lang {args.lang}: no such language of the student copy "
                             f"(the languages: {', '.join(languages_of_copies())})")
        generate_kit(work, args.lang)
    lab, version = read_kit(work)
    try:
        record = json.loads((work / "kit.json").read_text())
    except (OSError, ValueError):
        record = {}
    if record.get("format") != KIT_FORMAT:
        # A kit of an older grader: its build is not trusted (its checkers ran next to the
        # submissions' code). Built again from nothing (ccache keeps it short).
        shutil.rmtree(work / "base" / "copy" / "build-grade", ignore_errors=True)
        for name in ("checkers", "guards.json", "kit.json", "mesa-cache"):
            path = work / name
            shutil.rmtree(path, ignore_errors=True) if path.is_dir() else \
                path.unlink(missing_ok=True)
    restore_base(work, box)
    write_student_files(work, lab, {})
    build_base(work, lab, jobs)
    tests = make_checkers(work, lab)
    warm_mesa_cache(work, tests)
    # The tests that pass on the stubs (guards: they earn no points), run through the
    # checkers just recorded.
    (work / "guards.json").unlink(missing_ok=True)
    record_kit(work, tests)
    kit = Kit(work, lab)
    restore_base(work, box)
    stub_results = run_tests(work, kit, box, jobs, 600)
    unstarted = [m for _, messages in stub_results.values() for m in messages
                 if "could not be started" in m]
    if unstarted:
        raise GradeError("the stubs' runner cannot be started in the sandbox: " + unstarted[0])
    guards = sorted(name for name, (status, _) in stub_results.items() if status == "passed")
    (work / "guards.json").write_text(json.dumps(guards, indent=1) + "\n")
    record_kit(work, tests)
    made = Kit(work, lab)
    made.seconds = kit.seconds  # (the stubs' run: the checkers' order for the first student)
    return lab, version, made


def restore_base(work, box):
    """The scratch folder emptied, then the kit's copy and build put back there (root's), with
    the folders a submission writes (its build's home, its unpacking's folder) and the
    unpacking's program (root's, read-only)."""
    base = work / "base"
    box.reset(base if (base / "copy").is_dir() else None, own=("home", "unpack"))
    tools = scratch_of(work) / "tools"
    tools.mkdir(mode=0o755)
    shutil.copyfile(Path(submissions.__file__).with_name("unpack.py"), tools / "unpack.py")
    os.chmod(tools / "unpack.py", 0o644)


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
    subprocess.run(["chmod", "-R", "go-w", str(base)], check=True)


# The grader's additions to the kit's build, for speed only (the build is the copy's own
# otherwise): the headers that the student's files include, precompiled once for the library
# that holds those files, so that a submission's build compiles only its own code (a few
# seconds less per submission on two cores). CMake runs it after the copy's CMakeLists.txt.
SPEED_CMAKE = """# Written by scripts/grade (clothlab_lab/grading.py): the kit's build only.
include_guard(GLOBAL)
cmake_language(DEFER DIRECTORY "${{CMAKE_SOURCE_DIR}}" CALL _clothlab_grade_headers)
function(_clothlab_grade_headers)
  if(TARGET {target})
    target_precompile_headers({target} PRIVATE {headers})
  endif()
endfunction()
"""
STUDENT_LIBRARY = "clothlab_core"  # src/core's library: where the student's C++ files are


def speed_options(work, lab, folder):
    """The configure options of the kit's build that make a submission's build shorter: the
    precompiled headers above, and the gold linker where it works (it links the runner in a
    tenth of the default linker's time here)."""
    headers = []
    for name in lab.student_files:
        if name.endswith(".cpp") and (work / "stubs" / name).is_file():
            for line in (work / "stubs" / name).read_text(errors="replace").splitlines():
                match = re.match(r"\s*#\s*include\s*([<\"][^>\"]+[>\"])", line)
                if match and match.group(1) not in headers:
                    headers.append(match.group(1))
    script = folder / "grade-speed.cmake"
    script.write_text(SPEED_CMAKE.format(target=STUDENT_LIBRARY, headers=" ".join(
        h if h.startswith("<") else f"[[{h}]]" for h in headers)))
    options = [f"-DCMAKE_PROJECT_INCLUDE={script}"]
    with tempfile.TemporaryDirectory(prefix="clothlab-grade-ld-") as tmp:
        tried = subprocess.run(["c++", "-fuse-ld=gold", "-x", "c++", "-", "-o", f"{tmp}/a"],
                               input="int main() { return 0; }\n", capture_output=True,
                               text=True)
    if tried.returncode == 0:
        options.append("-DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=gold")
    return options


def build_outside(work, lab, jobs):
    folder = build_dir(work)
    if not (folder / "CMakeCache.txt").exists():
        folder.mkdir(parents=True, exist_ok=True)
        generator = ["-G", "Ninja"] if shutil.which("ninja") else []
        # PRE_TEST: the test programs are listed when ctest runs, on the kit's build.
        configured = subprocess.run(
            ["cmake", "-S", str(kit_copy(work)), "-B", str(folder), *generator,
             "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_GTEST_DISCOVER_TESTS_DISCOVERY_MODE=PRE_TEST",
             *speed_options(work, lab, folder)],
            capture_output=True, text=True)
        if configured.returncode != 0:
            raise GradeError("cmake could not configure the student copy:\n" +
                             configured.stdout[-3000:] + configured.stderr[-3000:])
    # The catalogues too: the checkers' hints and this grader's words in the kit's language.
    targets = lab_targets(lab) + ["clothlab_catalogues"]
    process = subprocess.run(build_command(work, lab, jobs, targets), stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, text=True, errors="replace")
    return process.returncode == 0, process.stdout


def build_command(work, lab, jobs, targets=None):
    folder = build_dir(work)
    keep_going = ["-k", "0"] if (folder / "build.ninja").exists() else ["-k"]
    return ["cmake", "--build", str(folder), "-j", str(jobs), "--target",
            *(targets or lab_targets(lab)), "--", *keep_going]


def build_submission(work, lab, box, jobs):
    """Builds the student's files into the kit's copy, in the sandbox: only the runner, the
    one program that links the student's code; (ok, output). The copy is the submission's to
    write during its build only."""
    copy, home = kit_copy(work), scratch_of(work) / "home"
    log = work / "logs" / "build.log"
    limit = box.limits.build_seconds
    box.grant(copy)
    try:
        with open(log, "wb") as out:
            code, timed_out = box.run(build_command(work, lab, jobs, [RUNNER]), limit,
                                      confinement.environment(home), out, cwd=copy,
                                      writable=[copy, home], cpu_seconds=limit)
    finally:
        box.revoke(copy)
    output = confinement.read_written(log, 4 * confinement.MiB).decode("utf-8", "replace")
    if timed_out:
        return False, _("the build did not finish within {seconds:g} s; stopped").format(
            seconds=limit) + "\n" + output[-3000:]
    if code in (-signal.SIGXCPU, 128 + signal.SIGXCPU, -signal.SIGKILL):
        return False, _("the build was stopped (a limit of processor time or memory)") + \
            "\n" + output[-3000:]
    return code == 0, output


def checker_environment(home, runner, prefix, language="en"):
    """The environment of a checker (the grader's program): no path of the scratch but the
    runner's, which it starts only through the sandbox's words (prefix). Its hints in
    `language` (LC_MESSAGES: the programs choose their language from it, src/core/i18n.cpp),
    its numbers in the C locale's form."""
    environment = {"PATH": "/usr/local/bin:/usr/bin:/bin", "HOME": str(home), "LC_ALL": "C.UTF-8",
                   "LANG": "C.UTF-8", "GTEST_COLOR": "no", "CLOTHLAB_LAB_RUNNER": str(runner),
                   "CLOTHLAB_LAB_SANDBOX": json.dumps(prefix)}
    if language != "en":
        del environment["LC_ALL"]
        environment["LC_MESSAGES"] = language
    return environment


def warm_mesa_cache(work, tests):
    """Mesa's shader cache of the kit (work/mesa-cache), made once by running the kit's checkers
    with the stubs' runner (the teacher's code, before any submission) outside the sandbox:
    each submission's tests start from a copy of it, so that they compile only the student's
    shaders, and Mesa never creates its 1.3 MB index under the tests' limit on file size."""
    cache = work / "mesa-cache"
    if (cache / "mesa_shader_cache" / "index").is_file():
        return
    cache = private_folder(work, "mesa-cache")
    with tempfile.TemporaryDirectory(prefix="clothlab-grade-warm-") as tmp:
        env = confinement.environment(Path(tmp), kit_copy(work))
        env["XDG_CACHE_HOME"] = str(cache)
        for program in sorted({Path(command[0]).name for _, _, command in tests}):
            try:
                subprocess.run([work / "checkers" / program, "--gtest_brief=1"], env=dict(
                    env, CLOTHLAB_LAB_RUNNER=str(runner_path(work))), cwd=tmp, timeout=300,
                    capture_output=True)
            except subprocess.TimeoutExpired:
                pass


def run_program(kit, program, filters, number, run, output_limit, timeout):
    """Runs one checker (verified against the kit) on some of its tests; returns (kind,
    messages, cases): kind "ran" with cases {GoogleTest name: (passed | failed, messages)}, else
    timeout | output | crashed, with messages. The checker runs as the grader, out of the
    sandbox, in a folder of the grader's; it starts the submission's runner in the sandbox (the
    words of CLOTHLAB_LAB_SANDBOX) and reads back only numbers: the verdict is never in the
    student's process, and is read only from what the checker wrote."""
    verdicts, box = run["verdicts"], run["box"]
    xml_path = verdicts / f"{number}.xml"
    log_path = verdicts / f"{number}.log"
    command = [kit.checker(program), "--gtest_filter=" + ":".join(filters),
               f"--gtest_output=xml:{xml_path}"]
    with open(log_path, "wb") as log:
        code, timed_out = box.run_outside(command, timeout, run["env"], log, cwd=verdicts,
                                          file_size=output_limit)
    if timed_out:
        return "timeout", [_("did not finish within {seconds:g} s (an endless loop? a loop "
                             "whose end condition never holds?); stopped").format(
                                 seconds=timeout)], None
    log_bytes = confinement.read_written(log_path, output_limit + 1)
    output = log_bytes[-4000:].decode("utf-8", "replace")
    if code in (-signal.SIGXFSZ, 128 + signal.SIGXFSZ) or len(log_bytes) >= output_limit:
        return "output", [_("wrote more than {size} KB of output (or of files); stopped. "
                            "Remove the prints from the code that runs every step").format(
                                size=output_limit // 1024)], None
    if code in (-signal.SIGXCPU, 128 + signal.SIGXCPU):
        return "timeout", [_("used more than {seconds:g} s of processor time; stopped").format(
            seconds=timeout)], None
    try:
        root = ElementTree.fromstring(confinement.read_written(xml_path, 64 << 20))
    except ElementTree.ParseError:
        if code < 0 or code > 128:
            number_of_signal = -code if code < 0 else code - 128
            words = _(SIGNAL_WORDS[number_of_signal]) if number_of_signal in SIGNAL_WORDS else \
                _("signal {number}").format(number=number_of_signal)
            return "crashed", [_("crashed: {what}").format(what=words)], None
        return "crashed", [_("stopped with exit status {code} before the test could report "
                             "(does the code call exit()?). Last output:").format(code=code) +
                           "\n" + tail_lines(output, 6)], None
    cases = {}
    for case in root.iter("testcase"):
        messages = [clean_message(f.get("message") or f.text or "")
                    for f in list(case.iter("failure")) + list(case.iter("error"))]
        if len(messages) > MAX_MESSAGES:
            messages = messages[:MAX_MESSAGES] + [
                _("... and {count} more failed checks in this test").format(
                    count=len(messages) - MAX_MESSAGES)]
        cases[f"{case.get('classname')}.{case.get('name')}"] = (
            ("failed", messages) if messages else ("passed", []))
    if code != 0 and not any(status == "failed" for status, _ in cases.values()):
        return "crashed", [_("exit status {code} although no check failed. Last output:").format(
            code=code) + "\n" + tail_lines(output, 6)], None
    return "ran", [], cases


def run_tests(work, kit, box, jobs, budget):
    """{test name: (status, messages)} for every test of the kit: each checker runs its tests at
    once (two checkers at a time with --jobs 2), each starting the submission's runner in the
    sandbox, to which the copy is read-only and a fresh run/ folder (its working folder and
    home) the one place to write. When a checker does not report (a loop, a crash, a flood),
    each of its tests runs alone, so that the report says which."""
    limits = box.limits
    run_dir = scratch_of(work) / "run"
    shutil.rmtree(run_dir, ignore_errors=True)
    for sub in ("cwd", "home"):
        (run_dir / sub).mkdir(parents=True, mode=0o700)
    if (work / "mesa-cache").is_dir():
        shutil.copytree(work / "mesa-cache", run_dir / "home" / ".cache", symlinks=False)
    box.grant(run_dir)
    verdicts = private_folder(work, "verdicts")
    prefix = box.prefix(writable=[run_dir], readable=[kit_copy(work)], chdir=run_dir / "cwd",
                        env=confinement.environment(run_dir / "home", kit_copy(work)))
    run = {"box": box, "verdicts": verdicts,
           "env": checker_environment(verdicts, runner_path(work), prefix, kit_language(work))}
    programs = {}  # checker -> [(test name, GoogleTest filter)]
    for _, name, program, test_filter in kit.tests:
        programs.setdefault(program, []).append((name, test_filter))
    started = time.monotonic()
    results = {}
    numbers = iter(range(1_000_000))

    def spent():
        return time.monotonic() - started > budget

    def whole(program):
        if spent():
            return program, ("budget", [], None)
        began = time.monotonic()
        result = run_program(kit, program, [f for _, f in programs[program]], next(numbers),
                             run, limits.test_output, 2 * limits.test_seconds)
        kit.seconds[program] = time.monotonic() - began
        return program, result

    def alone(program, name, test_filter):
        if spent():
            return name, ("timeout", [_("not run: this submission's {seconds:g} s for its tests "
                                        "were spent (by tests that did not finish)").format(
                                            seconds=budget)])
        kind, messages, cases = run_program(kit, program, [test_filter], next(numbers), run,
                                            limits.test_output, limits.test_seconds)
        if kind == "ran" and test_filter in cases:
            return name, cases[test_filter]
        return name, (kind if kind != "ran" else "crashed", messages or [_("did not report")])

    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            again = []
            # The longest checkers first (as last measured): two at a time end together.
            order = sorted(programs, key=lambda p: -kit.seconds.get(p, 0))
            for program, (kind, _, cases) in pool.map(whole, order):
                members = programs[program]
                if kind == "ran" and all(f in cases for _, f in members):
                    results.update({name: cases[f] for name, f in members})
                else:
                    again += [(program, name, f) for name, f in members]
            for name, result in pool.map(lambda item: alone(*item), again):
                results[name] = result
    finally:
        box.end_all()  # nothing of the submission outlives its tests
    missing = [name for _, name, _, _ in kit.tests if name not in results]
    if missing:
        raise GradeError(f"the tests {', '.join(missing[:5])} have no result: a grader's error")
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


DIAGNOSTIC = re.compile(r"^(?P<file>[^\s:][^:]*):(?P<line>\d+):(?:\d+:)? (?:fatal )?error: ")


NEXT_DIAGNOSTIC = re.compile(r"^[^\s:][^:]*:(\d+:)+ (warning|error): |^[^\s:][^:]*: In ")


def first_error(output, copy_folder, in_file=None):
    """The compiler's first error (in in_file, if given), as the student would read it (paths
    relative to the copy)."""
    text = output.replace(str(copy_folder) + "/", "").replace(str(copy_folder.parent) + "/", "")
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
    """The student's files whose compile failed: named by the compiler's diagnostics, or by
    the build tool's FAILED line of their object (an assembler's error names neither)."""
    failing = set()
    for line in output.splitlines():
        match = DIAGNOSTIC.match(line)
        for name in student_files:
            if match and match.group("file").endswith(name) or \
                    line.startswith("FAILED: ") and line.rstrip().endswith(f"/{Path(name).name}.o"):
                failing.add(name)
    return failing


def write_student_files(work, lab, taken):
    """The student's files (taken, else the stubs) into the kit's copy (root's now: no
    process of the submission's user lives, and no folder on the way may be a link)."""
    for name in lab.student_files:
        data = taken.get(name)
        if data is None:
            data = (work / "stubs" / name).read_bytes()
        write_without_links(kit_copy(work), name, data)


def write_without_links(folder, name, data):
    """Writes folder/name, refusing a link anywhere on the way (each folder opened with
    O_NOFOLLOW), and only when its bytes change (the build stays incremental)."""
    fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW)
    try:
        parts = name.split("/")
        for part in parts[:-1]:
            inner = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW, dir_fd=fd)
            os.close(fd)
            fd = inner
        try:
            current = os.open(parts[-1], os.O_RDONLY | os.O_NOFOLLOW, dir_fd=fd)
            with os.fdopen(current, "rb") as f:
                if f.read() == data:
                    return
        except FileNotFoundError:
            pass
        out = os.open(parts[-1], os.O_WRONLY | os.O_CREAT | os.O_TRUNC | os.O_NOFOLLOW, 0o644,
                      dir_fd=fd)
        with os.fdopen(out, "wb") as f:
            f.write(data)
    finally:
        os.close(fd)


def score_question(question, tests, results, guards, points, partial):
    """(score, passed, total, failures [(test, messages, status)])."""
    names = [name for q, name, *_ in tests if q == question]
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
    is (bounded), unpacked there by unpack.py in the sandbox (which sees only that folder and
    the program), its student copy found."""
    scratch = scratch_of(work)
    folder = scratch / "unpack"
    unpacked = folder / "files"
    limits = box.limits
    source, notes = submissions.stage(submission, folder / "submission", limits)
    box.grant(folder)
    tool = scratch / "tools" / "unpack.py"
    log = work / "logs" / "unpack.log"
    with open(log, "wb") as out:
        code, timed_out = box.run(
            ["python3", "-I", "-S", str(tool), str(source), str(unpacked),
             str(limits.submission), str(limits.entries), str(limits.student_file)],
            120, confinement.environment(folder), out, cwd=folder, writable=[folder],
            readable=[tool], file_size=limits.submission)  # (a pack may be large; each file is cut)
    said = confinement.read_written(log, 1 << 20).decode("utf-8", "replace").strip()
    shutil.rmtree(folder / "submission", ignore_errors=True)
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


def question_record(status, tests, output, score=0.0, passed=0, failures=()):
    return {"score": score, "passed": passed, "tests": tests, "status": status,
            "failures": list(failures), "output": output}


def grade_one(work, lab, version, reference, kit, submission, name, args, box, notes=()):
    """A dict with everything known of one submission's grade."""
    started = time.monotonic()
    questions = lab.ids
    points = lab.points
    record = {"name": name, "submission": submissions.printable(str(submission["original"])),
              "notes": list(notes), "questions": {}, "build_error": None}
    kit.verify()  # the kit is the one made; else GradeError: the grader stops
    restore_base(work, box)  # nothing of the previous submission is left
    try:
        if submission.get("error"):
            raise ValueError(submission["error"])
        taken, found = read_submission(work, lab, version, reference, submission["source"], box)
        record["notes"] += found
    except (ValueError, OSError) as error:
        taken = {}
        record["notes"].append(_("cannot be read: {why}").format(
            why=submissions.printable(str(error))))
    if not taken:
        record["notes"].append(_("no student file found ({files}): not a clothlab student copy? "
                                 "Every question gets 0").format(
                                     files=", ".join(lab.student_files)))
        for q in questions:
            record["questions"][q] = question_record("missing", kit.count(q),
                                                     _("no student file was handed in"))
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
            record["notes"].append(_("does not compile: {files} (graded as the stub; its "
                                     "questions get 0)").format(files=", ".join(sorted(failing))))
        if not ok:
            record["build_error"] = first_error(output, kit_copy(work))
            record["notes"].append(_("the build fails: every question gets 0"))
            for q in questions:
                record["questions"][q] = question_record(
                    "build error", kit.count(q),
                    _("does not compile:") + "\n" + record["build_error"])
            return finish(record, started, points)
    tests_started = time.monotonic()
    record["build_seconds"] = round(tests_started - build_started, 1)
    results = run_tests(work, kit, box, args.jobs, box.limits.test_budget)
    record["test_seconds"] = round(time.monotonic() - tests_started, 1)
    for q in questions:
        score, passed, total, failures = score_question(q, kit.tests, results, kit.guards,
                                                        points[q], lab.partial_credit)
        if total != kit.count(q):
            raise GradeError(f"{q}: {total} tests graded, the kit has {kit.count(q)}")
        if q in broken:
            record["questions"][q] = question_record("build error", total,
                                                     _("does not compile:") + "\n" + broken[q])
            continue
        status = "done" if passed == total else "to do"
        lines = [_("{passed}/{total} tests passed: {score:g} of {points:g} points").format(
            passed=passed, total=total, score=score, points=points[q])]
        kind_words = {"timeout": _("did not finish"), "crashed": _("crashed"),
                      "output": _("printed too much"), "budget": _("not run")}
        for test, messages, kind in failures:
            lines.append("\n" + (_("FAILED {test}:") if kind == "failed" else
                                 _("FAILED {test} ({why}):")).format(
                test=short_name(test), why=kind_words.get(kind, kind)))
            lines += ["  " + m.replace("\n", "\n  ") for m in messages]
        record["questions"][q] = question_record(
            status, total, "\n".join(lines), score, passed,
            [(short_name(t), m[0] if m else "", kind) for t, m, kind in failures])
        if any(kind != "failed" for _, _, kind in failures):
            kinds = sorted({kind for _, _, kind in failures if kind != "failed"})
            record["notes"].append(_("{question}: tests that {what}").format(
                question=q, what=" / ".join(kind_words.get(k, k) for k in kinds)))
    return finish(record, started, points)


def finish(record, started, points):
    """The record's total and time; every text in it made valid in every output (junit.xml,
    results.json, the report): control characters written out, never passed on."""
    reports.clean_record(record)
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


def stage_privately(work, entries, box):
    """In the fallback (no namespace hides the file system), before the first submission runs:
    each submission copied into work/staged (root's, 0700; bounded as in the scratch), graded
    from there; and a class whose submissions the submissions' user could read where they are
    (another student's code, its path on the grader's command line, /proc/PID/cmdline) is
    refused."""
    if len(entries) > 1:
        open_ = [e["original"] for e in entries
                 if confinement.readable_by_submission(box, e["original"])]
        if open_:
            raise GradeError(
                "bubblewrap cannot run here, and the submissions' user could read the "
                f"submissions where they are ({submissions.printable(str(open_[0]))}"
                + (f" and {len(open_) - 1} more" if len(open_) > 1 else "") + "): every "
                "student's code could read the others'. Close their folder to other users "
                "(chmod o-rwx), or grade where bubblewrap runs")
    staged = private_folder(work, "staged")
    for k, entry in enumerate(entries):
        try:
            entry["source"], notes = submissions.stage(entry["original"], staged / f"{k:05d}",
                                                       box.limits)
            entry["notes"] = notes
        except (ValueError, OSError) as error:
            entry["error"] = str(error)


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
        os.chmod(work, 0o700)  # the kit, the staged submissions, the verdicts: the grader's
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
        for name in ("logs", "verdicts"):
            private_folder(work, name)
        if args.kit and not args.prepare and args.lang not in ("en", kit_language(args.kit)):
            raise GradeError(f"--lang {args.lang}: the kit {args.kit} is the copy in "
                             f"{kit_language(args.kit)}; prepare one in {args.lang} (--prepare)")
        lab, version, kit = prepare_kit(work, box, args)
        # What the students read (results.json, junit.xml) and the class's report: in the
        # language of the copy they were handed (--lang), from the kit's catalogues (beside its
        # checkers: make_checkers).
        messages.start(work / "checkers", kit_language(work))
        # (with --kit too: this script's own path, on the grader's command line, names the tree)
        if box.kind == "user" and (ROOT / "docs/answers.md").exists() and \
                confinement.readable_by_submission(box, ROOT / "docs/answers.md"):
            raise GradeError(f"bubblewrap cannot run here, and the submissions' user could read "
                             f"the teacher's files ({ROOT / 'docs/answers.md'}): close the "
                             "repository to other users (chmod o-rwx), or grade with the "
                             "Gradescope bundle's own grader (clothlab-grade/grade --kit), "
                             "which holds no solution")
        if args.points:
            try:
                lab = lab_manifest.with_points(lab, args.points)
            except lab_manifest.ManifestError as error:
                raise GradeError(str(error))
        say(f"grade: the student copy is built ({time.monotonic() - started:.0f} s), "
            f"{len(kit.tests)} question tests; sandbox: {box.description}")
        if args.prepare:
            say(f"grade: {len(kit.guards)} tests pass on the stubs (guards), kept in "
                f"{work / 'guards.json'}; the kit's files recorded in {work / 'kit.json'}")
            return 0
        reference = {n: d for n, d in copy_files(work / "base" / "copy").items()
                     if n not in lab.student_files}
        used = set()
        entries = [{"name": submissions.unique_name(Path(args.name[k]) if k < len(args.name)
                                                     else submission, used),
                    "original": submission.absolute(), "source": submission.absolute(),
                    "notes": []} for k, submission in enumerate(args.submissions)]
        try:
            if box.kind == "user":
                stage_privately(work, entries, box)
            return grade_entries(args, work, lab, version, kit, box, entries, reference, started)
        finally:
            shutil.rmtree(work / "staged", ignore_errors=True)
    except GradeError as error:
        say(f"grade: {error}")
        return 1
    finally:
        if box is not None:
            try:
                box.release()
            except confinement.SandboxError as error:
                say(f"grade: {error}")


def grade_entries(args, work, lab, version, kit, box, entries, reference, started):
    """Grades each submission in turn, writing its results as it goes, then the class's; the
    exit status. The class's outputs are written whatever happens to one student's, and also
    when the grader stops (a GradeError), saying so in each."""
    args.out.mkdir(parents=True, exist_ok=True)
    if box.kind == "user":
        os.chmod(args.out, 0o700)  # no submission reads the others' grades
    (args.out / "students").mkdir(exist_ok=True)
    records, durations, stopped, unwritten = [], [], None, 0
    try:
        for k, entry in enumerate(entries, 1):
            name = entry["name"]
            began = time.monotonic()
            try:
                record = grade_one(work, lab, version, reference, kit, entry, name, args, box,
                                   entry["notes"])
            except GradeError:
                raise
            except confinement.SandboxError as error:
                raise GradeError(str(error))
            except Exception as error:  # noqa: BLE001 (whatever a submission holds, go on)
                record = {"name": name, "build_error": None,
                          "submission": submissions.printable(str(entry["original"])),
                          "notes": [_("could not be graded: {what}").format(
                              what=f"{type(error).__name__}: "
                                   f"{submissions.printable(str(error))}")],
                          "questions": {q: question_record("missing", kit.count(q),
                                                           _("could not be graded"))
                                        for q in lab.ids}}
                record = finish(record, began, lab.points)
            durations.append(time.monotonic() - began)
            records.append(record)
            try:
                write_results(args, record, lab, version, box.description)
            except OSError as error:
                unwritten += 1
                record["notes"].append(_("its results.json and junit.xml could not be written: "
                                         "{why}").format(why=submissions.printable(str(error))))
                say(f"grade: {name}: the results could not be written: {error}")
            if not sys.stderr.isatty():
                say(f"grade: {name}: {record['score']:g}/{record['max_score']:g} "
                    f"({durations[-1]:.0f} s)")
            progress(k, len(entries), name, started, durations)
    except GradeError as error:
        stopped = _("the grader stopped after {graded} of {count} submissions: {why}").format(
            graded=len(records), count=len(entries), why=error)
        for entry in entries[len(records):]:
            records.append(not_graded(entry, lab, stopped))
        raise
    finally:
        written = write_class_outputs(args, records, lab, version, box.description,
                                      time.monotonic() - started, stopped)
    say(f"grade: {len(records)} submissions graded in {time.monotonic() - started:.0f} s: "
        f"{args.out / 'grades.csv'}, {args.out / 'report.html'}; each student's in "
        f"{args.out / 'students'}")
    return 0 if written and not unwritten else 1


def not_graded(entry, lab, why):
    record = {"name": entry["name"], "submission": submissions.printable(str(entry["original"])),
              "build_error": None, "graded": False, "notes": [f"NOT GRADED: {why}"],
              "questions": {q: question_record("not graded", 0, "not graded") for q in lab.ids}}
    return finish(record, time.monotonic(), lab.points)


def write_class_outputs(args, records, lab, version, description, elapsed, stopped):
    """grades.csv and report.html, each on its own: one that cannot be written costs not the
    other; True when both were."""
    written = True
    for name, write in (("grades.csv", lambda p: reports.write_csv(p, records, lab, stopped)),
                        ("report.html", lambda p: reports.write_report(
                            p, records, lab, version, description, elapsed, stopped))):
        try:
            write(args.out / name)
        except OSError as error:
            written = False
            say(f"grade: {args.out / name} could not be written: {error}")
    return written


def write_results(args, record, lab, version, confinement):
    """The student's results.json and junit.xml, in --out/students/NAME/ (a name a student
    chooses can never be that of a class output), and --gradescope-results if given."""
    folder = args.out / "students" / record["name"]
    folder.mkdir(parents=True, exist_ok=True)
    results = reports.gradescope_results(record, lab, version, confinement)
    text = json.dumps(results, indent=1) + "\n"
    (folder / "results.json").write_text(text)
    (folder / "junit.xml").write_text(reports.junit_xml(record, lab))
    if args.gradescope_results:
        args.gradescope_results.parent.mkdir(parents=True, exist_ok=True)
        args.gradescope_results.write_text(text)
