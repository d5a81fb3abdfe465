"""A submission: copied into its scratch folder as it is (bounded, uninterpreted), unpacked there
in the sandbox (unpack.py), its student copy found, the student's own files taken, and what it
changed elsewhere said in words."""
import hashlib
import os
import re
import shutil
import stat
from pathlib import Path

from .manifest import MARKER_FILE
from .messages import _

NOT_PROJECT = ("build", "out", ".git", "Testing")  # a submission's folders that are not compared






def printable(text):
    """A name or message as every output can hold it: bytes that are not UTF-8 (a file name)
    replaced by \ufffd."""
    return text.encode("utf-8", "surrogateescape").decode("utf-8", "replace")


def stage(submission, dest, limits):
    """Copies the submission, as it is, to dest (a file: dest itself; a folder: its files,
    without links or build folders), refusing past the bounds before copying; (the copy's path,
    notes). Nothing of it is interpreted here: unpack.py does that in the sandbox."""
    info = os.stat(submission)  # the teacher's path: a link to an archive is fine
    if stat.S_ISREG(info.st_mode):
        if info.st_size > limits.submission:
            raise ValueError(f"refused: a file of {info.st_size // (1 << 20)} MB (at most "
                             f"{limits.submission // (1 << 20)} MB)")
        shutil.copyfile(submission, dest)
        return dest, []
    if not stat.S_ISDIR(info.st_mode):
        raise ValueError("no such file or folder")
    total = entries = 0
    notes = []
    bare = (Path(submission) / "HEAD").is_file() and (Path(submission) / "objects").is_dir()
    for folder, dirs, files in os.walk(submission):
        relative = Path(folder).relative_to(submission)
        if not bare:
            dirs[:] = [d for d in dirs if not d.startswith(NOT_PROJECT)]
        (dest / relative).mkdir(parents=True, exist_ok=True)
        for file in files:
            entries += 1
            if entries > limits.entries:
                raise ValueError(f"refused: more than {limits.entries} files")
            path = Path(folder) / file
            info = path.lstat()
            if not stat.S_ISREG(info.st_mode):
                note = _("holds links or special files: not taken")
                if note not in notes:
                    notes.append(note)
                continue
            total += info.st_size
            if total > limits.submission:
                raise ValueError(f"refused: more than {limits.submission // (1 << 20)} MB")
            fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW)
            with os.fdopen(fd, "rb") as source, open(dest / relative / file, "wb") as out:
                shutil.copyfileobj(source, out)
    return dest, notes


def copy_files(folder):
    """{relative name: bytes} of a student copy's files (not its build or output folders)."""
    files = {}
    for path in folder.rglob("*"):
        rel = path.relative_to(folder)
        if rel.parts[0].startswith(NOT_PROJECT) or not path.is_file() or path.is_symlink():
            continue
        files[rel.as_posix()] = path.read_bytes()
    return files


def marker_version(data):
    match = re.search(rb"^version: *(\S+)", data or b"", re.MULTILINE)
    return match.group(1).decode() if match else None


def content_version(files, student_files):
    """The version of a copy when its marker has none: a hash of every file but the student's."""
    digest = hashlib.sha256()
    for name in sorted(set(files) - set(student_files) - {MARKER_FILE}):
        digest.update(name.encode() + b"\0" + files[name] + b"\0")
    return digest.hexdigest()[:16]


def find_root(folder, student_files):
    """The folder of the copy inside a submission: the shallowest folder holding the marker or
    a student file at its place; None when there is none."""
    if (folder / MARKER_FILE).is_file() or any((folder / f).is_file() for f in student_files):
        return folder
    candidates = []
    for path in sorted(p for p in folder.rglob("*") if p.is_dir() and not p.is_symlink()):
        rel = path.relative_to(folder)
        if any(part.startswith(NOT_PROJECT) for part in rel.parts) or len(rel.parts) > 4:
            continue
        if (path / MARKER_FILE).is_file() or any((path / f).is_file() for f in student_files):
            candidates.append(path)
    return min(candidates, key=lambda p: len(p.parts)) if candidates else None


def take_student_files(submission_root, flat_folder, student_files, reference, kit_version,
                       max_file_bytes):
    """({student file: bytes}, [notes]): the student's own files, and what the submission
    changed elsewhere, in words."""
    notes = []
    taken = {}
    if submission_root is None:
        # Files handed in loose (a Gradescope upload of the files themselves): found by name.
        by_name = {}
        for path in flat_folder.rglob("*"):
            if path.is_file() and not path.is_symlink():
                by_name.setdefault(path.name, []).append(path)
        for name in student_files:
            found = by_name.get(Path(name).name, [])
            if len(found) == 1:
                taken[name] = found[0].read_bytes()
        if taken:
            notes.append(_("the student's files were handed in loose (not in a copy of the "
                           "project): found by their names"))
        return taken, notes
    for name in student_files:
        path = submission_root / name
        inside = submission_root.resolve() in path.resolve().parents
        if path.is_file() and (path.is_symlink() or not inside):
            notes.append(_("{file} is a link: not taken (the stub is graded)").format(file=name))
        elif path.is_file():
            if path.stat().st_size > max_file_bytes:
                notes.append(_("{file} is larger than {size} MB: not taken (the stub is "
                               "graded)").format(file=name, size=max_file_bytes // (1 << 20)))
                continue
            taken[name] = path.read_bytes()
    missing = [n for n in student_files if n not in taken]
    if missing and taken:
        notes.append(_("missing, graded as the stub: {files}").format(files=", ".join(missing)))
    submitted = copy_files(submission_root)
    their_version = marker_version(submitted.get(MARKER_FILE))
    edited = sorted(n for n in set(submitted) & set(reference)
                    if n not in student_files and n != MARKER_FILE and submitted[n] != reference[n])
    absent = sorted(n for n in set(reference) - set(submitted)
                    if n not in student_files and n != MARKER_FILE)
    added = sorted(set(submitted) - set(reference) - set(student_files) - {MARKER_FILE})

    def listed(names):
        return ", ".join(names[:8]) + (_(" and {count} more").format(count=len(names) - 8)
                                       if len(names) > 8 else "")

    if MARKER_FILE not in submitted:
        notes.append(_("no {file} file: the version of the copy cannot be told").format(
            file=MARKER_FILE))
    elif their_version and their_version != kit_version:
        notes.append(_("made from another version of the student copy (version {theirs}; this "
                       "one is {ours}): graded with this version's tests and build files").format(
                           theirs=their_version, ours=kit_version))
    elif not their_version:
        notes.append(_("its {file} carries no version (an older copy?)").format(file=MARKER_FILE))
    if edited and their_version and their_version != kit_version:
        notes.append(_("{count} file(s) that are not the student's own differ from this "
                       "version's (the teacher's are used): {files}").format(
                           count=len(edited), files=listed(edited)))
    elif edited:
        notes.append(_("changed {count} file(s) that are not the student's own, ignored (the "
                       "teacher's are used): {files}").format(count=len(edited),
                                                             files=listed(edited)))
    if absent:
        notes.append(_("lacks {count} file(s) of the copy (the teacher's are used): {files}")
                     .format(count=len(absent), files=listed(absent)))
    if added:
        notes.append(_("adds {count} file(s), ignored: {files}").format(count=len(added),
                                                                         files=listed(added)))
    return taken, notes


def unique_name(submission, used):
    base = submission.name
    for suffix in (".tar.gz", ".tgz", ".tar.xz", ".tar.bz2", ".tar", ".zip", ".git"):
        if base.lower().endswith(suffix):
            base = base[:-len(suffix)]
    base = re.sub(r"[^A-Za-z0-9._@-]+", "_", base).strip("._") or "submission"
    name, n = base, 2
    while name in used:
        name, n = f"{base}-{n}", n + 1
    used.add(name)
    return name
