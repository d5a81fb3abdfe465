"""The grader's kit: the student copy generated from this repository, built once, and the
question tests' checkers copied out of that build into a folder of the grader's, with the
sha256 of every file the verdict depends on recorded when the kit is made (kit.json) and checked
before each use. A file that differs, a question whose number of tests differs from the kit's,
a question test that is not a checker starting the runner: an error of the grader
(GradeError), said, never a grade.

The kit's folder (--work, or --kit), root's and closed to every other user:
    manifest.json   the lab (grading/lab.json) and the copy's version, as when the kit was made
    stubs/          the student's files as handed out
    base/copy/      the student copy and its build (build-grade/), made by the grader itself
    checkers/       the checkers (lab_q5_tests ...: GoogleTest and the assertions, no student
                    code), copied out of that build, and tests.json, the list of their tests
    guards.json     the tests that already pass on the stubs (they earn nothing)
    kit.json        the sha256 of each file above and the number of tests of each question
"""
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from collections import Counter
from pathlib import Path

from . import manifest as lab_manifest
from . import regions
from .manifest import MARKER_FILE, ROOT
from .submissions import content_version, copy_files, marker_version

KIT_FORMAT = 2  # kit.json's layout: a kit of another (an older grader's) is rebuilt from nothing
RUNNER = "lab_runner"  # tests/lab's program that links the student's code
CHECKER = re.compile(r"lab_q\d+_tests")  # tests/lab's checkers: the assertions, no student code


class GradeError(Exception):
    """The grader itself cannot run (not a student's fault)."""


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


def runner_path(work):
    return build_dir(work) / "tests" / "lab" / RUNNER


def private_folder(work, name):
    """A folder of the grader's in the kit (root's, 0700), emptied."""
    folder = work / name
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(mode=0o700)
    return folder


def sha256(path):
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def kit_files(work):
    """The kit's files that the verdict depends on (relative names): the manifest, the guards,
    the checkers and their list of tests, the stubs. A link or a special file there is an
    error: nothing but the grader writes the kit."""
    names = [n for n in ("manifest.json", "guards.json") if (work / n).is_file()]
    for folder in ("checkers", "stubs"):
        for path in sorted((work / folder).rglob("*")):
            if path.is_symlink() or not (path.is_file() or path.is_dir()):
                raise GradeError(f"the kit holds a link or a special file: {path}")
            if path.is_file():
                names.append(path.relative_to(work).as_posix())
    return names


class Kit:
    """The checkers of a made kit and the list of their tests, with the sha256 of every file the
    verdict depends on, as recorded when the kit was made (kit.json). verify() before each
    submission and verify_checker() before each checker's run: a file that differs is an error
    of the grader (GradeError), said, never a grade."""

    def __init__(self, work, lab):
        self.work = work
        try:
            record = json.loads((work / "kit.json").read_text())
            self.hashes = dict(record["files"])
            self.counts = {q: int(n) for q, n in record["tests"].items()}
            if record.get("format") != KIT_FORMAT:
                raise ValueError(f"format {record.get('format')}, not {KIT_FORMAT}")
        except (OSError, ValueError, KeyError, TypeError, AttributeError) as error:
            raise GradeError(f"{work}: not a kit made by this grader (kit.json: {error}); make "
                             "it again (scripts/grade --prepare)")
        self.record_text = (work / "kit.json").read_text()
        self.verify()
        self.tests = []  # [(question, test name, checker, GoogleTest filter)]
        for entry in json.loads((work / "checkers" / "tests.json").read_text()):
            self.tests.append((entry["question"], entry["name"], entry["program"],
                               entry["filter"]))
        listed = Counter(q for q, _, _, _ in self.tests)
        if dict(listed) != self.counts or set(self.counts) != set(lab.ids) or \
                any(n < 1 for n in self.counts.values()):
            raise GradeError(f"the kit's tests per question ({dict(listed)}) differ from those "
                             f"recorded when it was made ({self.counts}), or a question of the "
                             f"lab ({', '.join(lab.ids)}) has none: make the kit again")
        self.guards = set(json.loads((work / "guards.json").read_text())) \
            if (work / "guards.json").is_file() else None
        self.seconds = {}  # checker -> seconds of its last whole run (the longest start first)

    def verify(self):
        """GradeError unless every file of the kit is the one recorded when it was made."""
        if (self.work / "kit.json").read_text() != self.record_text:
            raise GradeError(f"{self.work / 'kit.json'} changed while grading: the grader stops")
        names = kit_files(self.work)
        differ = sorted(set(names) ^ set(self.hashes))
        differ += [n for n in names if n in self.hashes and sha256(self.work / n) !=
                   self.hashes[n]]
        if differ:
            raise GradeError("the kit's files are not those recorded when it was made ("
                             + ", ".join(differ[:8]) + "): the grader stops. Make the kit again "
                             "(delete --work, or scripts/grade --prepare) and look for who wrote "
                             "there")

    def checker(self, name):
        """The path of a checker, verified against the kit's record just before it runs."""
        path = self.work / "checkers" / name
        recorded = self.hashes.get(f"checkers/{name}")
        if not CHECKER.fullmatch(name) or recorded is None or sha256(path) != recorded:
            raise GradeError(f"the checker {name} is not the one recorded when the kit was made:"
                             " the grader stops")
        return path

    def count(self, question):
        return self.counts[question]


def record_kit(work, tests):
    """Writes kit.json: the sha256 of the kit's files and the tests of each question, now that
    the kit is made."""
    record = {"format": KIT_FORMAT,
              "files": {n: sha256(work / n) for n in kit_files(work)},
              "tests": dict(Counter(q for q, _, _ in tests))}
    (work / "kit.json.new").write_text(json.dumps(record, indent=1) + "\n")
    os.replace(work / "kit.json.new", work / "kit.json")


def make_checkers(work, lab):
    """Copies the checkers out of the kit's build into work/checkers (root's, 0700; never bound
    into a sandbox) and lists their tests there (tests.json); [(question, name, command)].
    Every question test must be a checker that starts the runner: one that is not is refused
    (a program that linked the student's code would run as the grader)."""
    if not os.access(runner_path(work), os.X_OK):
        raise GradeError(f"tests/lab has no {RUNNER}: this grader runs question tests split "
                         f"into a checker (lab_qN_tests: the assertions) and {RUNNER} (the "
                         "student's code), and nothing else")
    tests = list_tests(work, lab)
    new = private_folder(work, "checkers.new")
    entries = []
    for question, name, command in tests:
        program = Path(command[0])
        if program.parent != runner_path(work).parent or not CHECKER.fullmatch(program.name):
            raise GradeError(f"the question test {name} runs {program}, not a checker of "
                             "tests/lab (lab_qN_tests, which starts lab_runner): refused")
        if not (new / program.name).exists():
            data = program.read_bytes()
            if b"CLOTHLAB_LAB_RUNNER" not in data:
                raise GradeError(f"{program.name} does not start {RUNNER} "
                                 "(CLOTHLAB_LAB_RUNNER): every question test must be a checker "
                                 "that runs the student's code through the runner; refused")
            (new / program.name).write_bytes(data)
            os.chmod(new / program.name, 0o700)
        entries.append({"question": question, "name": name, "program": program.name,
                        "filter": gtest_filter(command)})
    (new / "tests.json").write_text(json.dumps(entries, indent=1) + "\n")
    # The catalogues beside the checkers, where they and this grader read them (the checkers'
    # hints in the kit's language): the grader's own copy, hashed with the kit, never the
    # scratch copy's build, which a submission's build may write.
    if (build_dir(work) / "locale").is_dir():
        shutil.copytree(build_dir(work) / "locale", new / "locale", symlinks=False)
    shutil.rmtree(work / "checkers", ignore_errors=True)
    new.rename(work / "checkers")
    return tests


def languages_of_copies():
    """The languages a student copy can be written in: English, then those of po/."""
    return ["en"] + sorted(p.stem for p in (ROOT / "po").glob("*.po"))


def generate_kit(work, language="en"):
    """Generates the student copy of this repository into work/base/copy (only the files that
    changed: its build stays incremental), in `language` (make-student-version --lang: the
    copy the class was handed), its stubs into work/stubs, and work/manifest.json."""
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
                               str(generated), "--lang", language], capture_output=True,
                              text=True)
        if made.returncode != 0:
            raise GradeError("make-student-version failed:\n" + made.stderr)
        files = copy_files(generated)
        version = marker_version(files.get(MARKER_FILE)) or \
            content_version(files, lab.student_files)
        shutil.rmtree(work / "stubs", ignore_errors=True)
        for name in lab.student_files:
            (work / "stubs" / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(generated / name, work / "stubs" / name)
        (work / "manifest.json").write_text(json.dumps(
            {"version": version, "language": language, **lab.to_json()}, indent=1) + "\n")
        (work / "base" / "copy").mkdir(parents=True, exist_ok=True)
        os.chmod(work / "base", 0o700)
        sync(generated, work / "base" / "copy")


def kit_language(work):
    """The language of a prepared kit's copy (English for a kit made before it was recorded)."""
    try:
        return str(json.loads((work / "manifest.json").read_text()).get("language", "en"))
    except (OSError, ValueError, AttributeError):
        return "en"


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
    """[(question, test name, [program, arguments...])] of the kit's build, from ctest (which
    runs the checkers to list their tests: the kit's, before any submission)."""
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


def gtest_filter(command):
    return next((a.split("=", 1)[1] for a in command if a.startswith("--gtest_filter=")), "*")
