"""The Gradescope bundle: setup.sh, run_autograder and the grader's kit (the generated student
copy, the stubs, the lab's manifest and this package), never the solution. Made from what git
tracks and what the generator writes: no untracked file of the teacher's checkout (a compiler's
cache, an object file) ever reaches it."""
import re
import tempfile
import zipfile
from pathlib import Path

from . import grading, regions
from .manifest import ROOT

# The bundle's two scripts, teacher-only files of their own: setup.sh (its @PACKAGES@ filled
# in from scripts/setup.sh) and run_autograder.
TEMPLATES = ROOT / "grading" / "gradescope"


def debian_packages():
    text = (ROOT / "scripts/setup.sh").read_text()
    block = re.search(r"^packages=\((.*?)^\)", text, re.MULTILINE | re.DOTALL)
    return " ".join(word for line in block.group(1).splitlines()
                    for word in line.split("#")[0].split()) if block else ""


def make_bundle(path, language="en"):
    """The bundle, its kit the student copy in `language` (scripts/grade --lang)."""
    if language not in grading.languages_of_copies():
        raise SystemExit(f"grade: --lang {language}: no such language of the student copy "
                         f"(the languages: {', '.join(grading.languages_of_copies())})")
    with tempfile.TemporaryDirectory(prefix="clothlab-bundle-") as tmp:
        kit = Path(tmp) / "clothlab-grade"
        grading.generate_kit(kit, language)
        # The grader and its package: their tracked files only.
        package = Path(__file__).resolve().parent.relative_to(ROOT).as_posix() + "/"
        grader = {"scripts/grade": kit / "grade"}
        grader.update({name: kit / "clothlab_lab" / name[len(package):]
                       for name in regions.project_files(ROOT) if name.startswith(package)})
        for name, target in grader.items():
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes((ROOT / name).read_bytes())
            target.chmod((ROOT / name).stat().st_mode & 0o777)
        setup = (TEMPLATES / "setup.sh").read_text()
        files = {"setup.sh": setup.replace("@PACKAGES@", debian_packages()),
                 "run_autograder": (TEMPLATES / "run_autograder").read_text()}
        with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as bundle:
            for name, text in files.items():
                info = zipfile.ZipInfo(name)
                info.external_attr = 0o100755 << 16
                bundle.writestr(info, text)
            for file in sorted(kit.rglob("*")):
                if file.is_file():
                    info = zipfile.ZipInfo(file.relative_to(Path(tmp)).as_posix())
                    info.external_attr = (0o100000 | (file.stat().st_mode & 0o777)) << 16
                    info.compress_type = zipfile.ZIP_DEFLATED
                    bundle.writestr(info, file.read_bytes())
    print(f"Gradescope autograder written to {path}: upload it as the assignment's "
          "autograder (setup.sh, run_autograder, clothlab-grade/)")
