"""The lab's facts, written once in grading/lab.json: the questions that ask for code (title,
files, functions, test label, points), partial credit, and the teacher's files that the student
copy leaves out. Every script reads them from here."""
import json
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent  # the project (teacher's or student's copy)
MANIFEST = Path("grading/lab.json")
MARKER_FILE = ".student-copy"  # written into a student copy by scripts/make-student-version


class ManifestError(Exception):
    pass


@dataclass(frozen=True)
class Question:
    id: str  # "Q8": the handout's number
    title: str  # what it asks, in a few words
    points: float
    files: tuple  # the student's files that hold its solution regions
    functions: tuple  # where in those files (lab-report's "where")
    test: str  # tests/lab/<test>_test.cpp; its tests carry the label q8

    @property
    def label(self):
        return self.id.lower()

    @property
    def target(self):
        return f"lab_{self.label}_tests"


@dataclass(frozen=True)
class Lab:
    questions: tuple  # in the lab's order
    partial_credit: bool
    teacher_files: tuple
    teacher_folders: tuple

    @property
    def ids(self):
        return tuple(q.id for q in self.questions)

    def question(self, id_):
        return next(q for q in self.questions if q.id == id_.upper())

    @property
    def student_files(self):
        """Every file that holds a solution region, sorted."""
        return sorted({f for q in self.questions for f in q.files})

    @property
    def points(self):
        return {q.id: q.points for q in self.questions}

    def is_teacher_file(self, name):
        return name in self.teacher_files or name.startswith(self.teacher_folders)

    def to_json(self):
        return {"partial_credit": self.partial_credit,
                "questions": [{"id": q.id, "title": q.title, "points": q.points,
                               "files": list(q.files), "functions": list(q.functions),
                               "test": q.test} for q in self.questions],
                "teacher_files": list(self.teacher_files),
                "teacher_folders": list(self.teacher_folders)}


def parse(data, where="lab.json"):
    try:
        questions = tuple(Question(q["id"].upper(), q["title"], float(q["points"]),
                                   tuple(q["files"]), tuple(q.get("functions", ())), q["test"])
                          for q in data["questions"])
    except (KeyError, TypeError, ValueError, AttributeError) as error:
        raise ManifestError(f"{where}: a question lacks id, title, points, files or test "
                            f"({error!r})")
    if len({q.id for q in questions}) != len(questions) or not questions:
        raise ManifestError(f"{where}: no question, or one named twice")
    return Lab(questions, bool(data.get("partial_credit", True)),
               tuple(data.get("teacher_files", ())), tuple(data.get("teacher_folders", ())))


def load(path=None):
    """The manifest at path (default: this project's grading/lab.json)."""
    path = Path(path) if path else ROOT / MANIFEST
    try:
        return parse(json.loads(path.read_text()), str(path))
    except (OSError, ValueError) as error:
        raise ManifestError(f"{path}: cannot be read ({error})")


def with_points(lab, path):
    """The lab with the points and partial credit of a teacher's points file ({"questions":
    {"Q8": 20}, "partial_credit": true}), for a course that counts otherwise."""
    try:
        data = json.loads(Path(path).read_text())
    except (OSError, ValueError) as error:
        raise ManifestError(f"{path}: not a readable JSON points file ({error})")
    given = {k.upper(): float(v) for k, v in data.get("questions", {}).items()}
    unknown = sorted(set(given) - set(lab.ids))
    if unknown:
        raise ManifestError(f"{path}: no such question: {', '.join(unknown)}")
    questions = tuple(Question(q.id, q.title, given.get(q.id, q.points), q.files, q.functions,
                               q.test) for q in lab.questions)
    return Lab(questions, bool(data.get("partial_credit", lab.partial_credit)),
               lab.teacher_files, lab.teacher_folders)
