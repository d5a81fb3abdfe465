"""Unpacks one submission into a folder, inside the sandbox (scripts/grade runs this file there,
as the submission's unprivileged user, with its limits): a .zip, a tar archive (.tar.gz ...),
a bare git repository or a folder, recognised by their bytes, not their names.

    python3 -I unpack.py SOURCE DEST MAX_BYTES MAX_ENTRIES MAX_FILE_BYTES

Every archive is streamed: the entry count and the bytes written are counted as they come and
the unpacking stops past a bound, before anything larger is expanded. Only regular files with
safe UTF-8 names are written (no link, no absolute path, no ..). A git repository is read
object by object from a copy of its objects and refs only: its config, hooks, attributes and
filters are never seen by git. Prints one JSON line: {"notes": [...]} or {"error": "..."}.
Standalone (the standard library only): it runs before any of the package is trusted there.
"""
import io
import json
import os
import shutil
import stat
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

SKIPPED_FOLDERS = ("build", "out", "Testing", ".git")  # a copy's build and version folders
CHUNK = 1 << 16
NAME_BYTES, PATH_BYTES = 255, 1024  # a file name's bytes (Linux's NAME_MAX), a path's


def printable_start(name):
    """The start of a name, for a note (at most 60 characters)."""
    return name[:60] + ("..." if len(name) > 60 else "")


class TooLarge(Exception):
    pass


class Writer:
    """Writes the submission's files under dest, counting entries and bytes against the bounds;
    notes what it skips."""

    def __init__(self, dest, max_bytes, max_entries, max_file_bytes):
        self.dest, self.max_bytes, self.max_entries = dest, max_bytes, max_entries
        self.max_file_bytes = max_file_bytes
        self.bytes = self.entries = 0
        self.notes = []

    def name(self, raw):
        """The safe relative name of an entry, or None (noted)."""
        if isinstance(raw, bytes):
            try:
                raw = raw.decode("utf-8")
            except UnicodeDecodeError:
                self.note("a file name that is not UTF-8: skipped")
                return None
        try:
            raw.encode("utf-8")
        except UnicodeEncodeError:  # a name Python decoded with surrogates
            self.note("a file name that is not UTF-8: skipped")
            return None
        parts = [p for p in raw.replace("\\", "/").split("/") if p not in ("", ".")]
        if raw.startswith("/") or ".." in parts or not parts or any("\0" in p for p in parts):
            self.note("a path outside the submission (absolute, or with ..): skipped")
            return None
        if any(len(p.encode("utf-8")) > NAME_BYTES for p in parts) or \
                len(raw.encode("utf-8")) > PATH_BYTES:
            self.note(f"a file name longer than {NAME_BYTES} bytes (or a path longer than "
                      f"{PATH_BYTES}): skipped")
            return None
        return "/".join(parts)

    def note(self, text):
        if text not in self.notes:
            self.notes.append(text)

    def count(self):
        self.entries += 1
        if self.entries > self.max_entries:
            raise TooLarge(f"more than {self.max_entries} entries")

    def write(self, name, source, declared=None):
        """Copies the stream source to name, at most max_file_bytes (a larger file is cut and
        noted); the total stays under max_bytes."""
        self.count()
        if declared is not None and self.bytes + min(declared, self.max_file_bytes + 1) > \
                self.max_bytes:
            raise TooLarge(f"more than {self.max_bytes // (1 << 20)} MB unpacked")
        target = self.dest / name
        try:
            target.parent.mkdir(parents=True, exist_ok=True)
            out = open(target, "wb")
        except OSError as error:
            # One entry that cannot be written (a name the file system refuses, a file where a
            # folder of the same name is): skipped, the rest unpacked.
            self.note(f"{printable_start(name)}: cannot be written ({error.strerror}): skipped")
            return
        written = 0
        with out:
            while True:
                block = source.read(CHUNK)
                if not block:
                    break
                written += len(block)
                self.bytes += len(block)
                if self.bytes > self.max_bytes:
                    raise TooLarge(f"more than {self.max_bytes // (1 << 20)} MB unpacked")
                if written > self.max_file_bytes:
                    self.note(f"{name}: larger than {self.max_file_bytes // (1 << 20)} MB: cut")
                    break
                out.write(block)


def from_zip(path, writer):
    with zipfile.ZipFile(path) as archive:
        for member in archive.infolist():
            writer.count()
            kind = (member.external_attr >> 16) & 0o170000  # 0: not said (a file)
            if member.is_dir() or kind not in (0, 0o100000):
                continue
            name = writer.name(member.filename)
            if name is None:
                continue
            writer.entries -= 1  # counted again by write
            with archive.open(member) as source:
                # The declared size may lie: the stream is counted as it is inflated.
                writer.write(name, source, member.file_size)


def from_tar(path, writer):
    with tarfile.open(path, "r|*") as archive:  # a stream: never the whole index in memory
        for member in archive:
            if not member.isfile():
                writer.count()
                continue
            name = writer.name(member.name)
            if name is None:
                writer.count()
                continue
            writer.write(name, archive.extractfile(member), member.size)


def from_folder(source, writer):
    for folder, dirs, files in os.walk(source):  # links to folders are not followed
        dirs[:] = [d for d in dirs if not d.startswith(SKIPPED_FOLDERS)]
        for file in files:
            path = Path(folder) / file
            try:
                info = path.lstat()
            except OSError:
                writer.count()
                writer.note("a file that cannot be read: skipped")
                continue
            relative = os.fsencode(path.relative_to(source))
            if not stat.S_ISREG(info.st_mode):
                writer.count()
                continue
            name = writer.name(relative)
            if name is None:
                writer.count()
                continue
            try:
                fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW)
            except OSError:
                writer.count()
                writer.note("a file that cannot be read: skipped")
                continue
            with os.fdopen(fd, "rb") as stream:
                writer.write(name, stream, info.st_size)


def git(git_dir, *arguments, **kwargs):
    """git on a repository made of objects and refs only: no configuration of the system, the
    user or the repository is read, no hook runs, no filter or attribute applies."""
    env = {"PATH": "/usr/bin:/bin", "HOME": str(git_dir), "GIT_CONFIG_NOSYSTEM": "1",
           "GIT_CONFIG_GLOBAL": "/dev/null", "GIT_ATTR_NOSYSTEM": "1",
           "GIT_NO_REPLACE_OBJECTS": "1", "GIT_DIR": str(git_dir), "LC_ALL": "C"}
    return subprocess.run(["git", "-c", "core.hooksPath=/dev/null", "-c", "core.fsmonitor=false",
                           *arguments], env=env, **kwargs)


def from_git(source, writer, scratch):
    """The files of HEAD's tree, read object by object from a clean copy of the repository."""
    clean = scratch / "repository.git"
    for part in ("objects", "refs"):
        for folder, dirs, files in os.walk(source / part):
            relative = Path(folder).relative_to(source)
            if relative.as_posix() == "objects/info":
                continue  # alternates: objects of another repository
            (clean / relative).mkdir(parents=True, exist_ok=True)
            for file in files:
                path = Path(folder) / file
                if not stat.S_ISREG(path.lstat().st_mode):
                    continue
                writer.bytes += path.lstat().st_size
                if writer.bytes > writer.max_bytes:
                    raise TooLarge(f"a repository of more than {writer.max_bytes // (1 << 20)} MB")
                shutil.copyfile(path, clean / relative / file, follow_symlinks=False)
    for file in ("HEAD", "packed-refs"):
        if (source / file).is_file() and not (source / file).is_symlink():
            shutil.copyfile(source / file, clean / file, follow_symlinks=False)
    (clean / "config").write_text("[core]\n\trepositoryformatversion = 0\n\tbare = true\n")
    writer.bytes = 0  # the repository's copy is not the submission's files
    listing = git(clean, "ls-tree", "-r", "-z", "-l", "--full-tree", "HEAD", capture_output=True)
    if listing.returncode != 0:
        raise ValueError("a git repository without a commit to grade: " +
                         listing.stderr.decode(errors="replace").strip()[:200])
    entries = []
    for record in listing.stdout.split(b"\0"):
        if not record:
            continue
        meta, _, raw_name = record.partition(b"\t")
        mode, kind, sha, size = meta.split()
        writer.count()
        if kind != b"blob" or mode not in (b"100644", b"100755"):
            continue
        name = writer.name(raw_name)
        if name is None:
            continue
        if int(size) > writer.max_file_bytes:
            writer.note(f"{name}: larger than {writer.max_file_bytes // (1 << 20)} MB: skipped")
            continue
        if writer.bytes + int(size) > writer.max_bytes:
            raise TooLarge(f"more than {writer.max_bytes // (1 << 20)} MB unpacked")
        writer.bytes += int(size)
        entries.append((name, sha.decode()))
    writer.bytes = 0
    for name, sha in entries:
        blob = git(clean, "cat-file", "blob", sha, stdout=subprocess.PIPE)
        # Each blob's size was checked above; write counts again.
        writer.entries -= 1
        writer.write(name, io.BytesIO(blob.stdout))
    shutil.rmtree(clean)


def main():
    source, dest = Path(sys.argv[1]), Path(sys.argv[2])
    max_bytes, max_entries, max_file_bytes = (int(a) for a in sys.argv[3:6])
    writer = Writer(dest, max_bytes, max_entries, max_file_bytes)
    dest.mkdir(parents=True, exist_ok=True)
    try:
        if source.is_dir():
            if (source / "HEAD").is_file() and (source / "objects").is_dir():
                from_git(source, writer, dest.parent)
            else:
                from_folder(source, writer)
        else:
            with open(source, "rb") as f:
                magic = f.read(262)
            if magic.startswith(b"PK"):
                from_zip(source, writer)
            elif magic[:2] == b"\x1f\x8b" or magic[:3] == b"BZh" or \
                    magic[:6] == b"\xfd7zXZ\x00" or magic[257:262] == b"ustar":
                from_tar(source, writer)
            else:
                raise ValueError("neither a folder nor a .zip or .tar.gz archive")
    except TooLarge as error:
        print(json.dumps({"error": f"refused: {error} (a copy of the lab is far smaller)"}))
        return 0
    except (ValueError, OSError, EOFError, zipfile.BadZipFile, tarfile.TarError,
            zipfile.LargeZipFile) as error:
        print(json.dumps({"error": f"cannot be read: {type(error).__name__}: {error}"}))
        return 0
    print(json.dumps({"notes": writer.notes, "entries": writer.entries}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
