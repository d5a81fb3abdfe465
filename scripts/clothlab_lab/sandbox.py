"""Where a submission's bytes are handled: unpacked, compiled, linked and run.

Everything runs in the submission's scratch folder, as an unprivileged user with no capability,
within the limits of LIMITS. The scratch's top folder is root's: each step gets only the
subfolders it needs, writable or read-only (the build writes copy/, the tests only run/, to
which copy/ is read-only). Where bubblewrap works each step also runs in its own namespaces: no
network, no other process, and a file system of /usr, the few /etc files the compiler and Mesa
read, those subfolders and a small /tmp: no teacher tree, no other submission, no grades, no
host socket, not even the rest of the scratch. Where it does not (Docker's default seccomp
profile: Gradescope, many CI containers), the unprivileged user, the limits, the file modes and
the private scratch still hold, and the grader's own folders are closed to that user (say()
reports which confinement held). Every process of that user ends after each step.
"""
import fcntl
import os
import resource
import shutil
import signal
import stat
import subprocess
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

MiB = 1 << 20


@dataclass(frozen=True)
class Limits:
    """Every bound on a submission, in one place. An honest submission uses far less (measured
    on the lab's solution, docs/teaching.md "The threat model and the limits")."""
    build_seconds: float = 600  # wall time of one build (compiler and linker included)
    test_seconds: float = 10  # wall time of one test; twice that for a program's whole run
    test_budget: float = 120  # wall time of all of one submission's tests
    memory: int = 2048 * MiB  # address space of each process (RLIMIT_AS)
    memory_total: int = 3072 * MiB  # memory of all its processes together (a cgroup, where any)
    processes: int = 256  # processes and threads: of its user (RLIMIT_NPROC), of its cgroup
    file_size: int = 256 * MiB  # one file written by the build (RLIMIT_FSIZE)
    test_output: int = 1 * MiB  # a test's output, and each file it writes
    open_files: int = 512  # (RLIMIT_NOFILE)
    scratch: int = 1024 * MiB  # every byte written, where the scratch is a sized tmpfs
    tmp: int = 64 * MiB  # the sandbox's own /tmp (bubblewrap)
    submission: int = 200 * MiB  # a submission's files, unpacked
    entries: int = 20000  # a submission's files and folders
    student_file: int = 2 * MiB  # one file of a submission


LIMITS = Limits()
SANDBOX_UID = 64990  # the submission's user where the grader runs as root (no login, no files)
# The /etc files that the compiler, the linker and Mesa read; nothing else of /etc is visible.
ETC = ("ld.so.cache", "ld.so.conf", "ld.so.conf.d", "alternatives", "glvnd", "localtime")
SIGNAL_NAMES = {signal.SIGXCPU: "processor time", signal.SIGXFSZ: "file size"}


class SandboxError(Exception):
    pass


class Cgroup:
    """A control group for the submission's processes, where root may make one (cgroup v1's
    memory and pids hierarchies, or v2's unified one): a bound on their memory and number
    together, and the list of them, so that every one ends. Empty where none can be made."""

    def __init__(self, name, memory, processes):
        self.folders = []
        top = Path("/sys/fs/cgroup")
        settings = {"memory.limit_in_bytes": memory, "memory.max": memory,
                    "pids.max": processes}
        if (top / "cgroup.controllers").exists():
            try:
                (top / "cgroup.subtree_control").write_text("+memory +pids")
            except OSError:
                pass
            candidates = [top / name]
        else:
            candidates = [top / "memory" / name, top / "pids" / name]
        for folder in candidates:
            try:
                folder.mkdir(exist_ok=True)
                for file, value in settings.items():
                    if (folder / file).exists():
                        (folder / file).write_text(str(value))
                self.folders.append(folder)
            except OSError:
                continue
        self.bounds = sorted({f for folder in self.folders for f in ("memory", "pids")
                              if any(p.name.startswith(f) for p in folder.iterdir())})

    def enter(self):
        """Puts the calling process (a child about to become the submission) in the group."""
        for folder in self.folders:
            try:
                (folder / "cgroup.procs").write_text(str(os.getpid()))
            except OSError:
                pass

    def end_all(self):
        for _ in range(20):
            alive = [int(p) for folder in self.folders for p in
                     (folder / "cgroup.procs").read_text().split()]
            if not alive:
                return
            for pid in alive:
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
            time.sleep(0.05)

    def remove(self):
        self.end_all()
        for folder in self.folders:
            try:
                folder.rmdir()
            except OSError:
                pass


def sandbox_uid():
    """(uid, lock): a user of its own for this grader's submissions: the first of SANDBOX_UID,
    SANDBOX_UID + 1, ... that no other grader on this machine holds (two graders never end or
    count each other's processes), or CLOTHLAB_GRADE_UID."""
    if "CLOTHLAB_GRADE_UID" in os.environ:
        uid = int(os.environ["CLOTHLAB_GRADE_UID"])
        if uid == 0:
            raise SandboxError("CLOTHLAB_GRADE_UID=0: the submission's code never runs as root")
        return uid, None
    locks = Path(tempfile.gettempdir()) / "clothlab-grade-users"
    locks.mkdir(mode=0o700, exist_ok=True)
    for uid in range(SANDBOX_UID, SANDBOX_UID + 100):
        lock = open(locks / str(uid), "w")
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return uid, lock
        except OSError:
            lock.close()
    raise SandboxError(f"100 graders hold the users {SANDBOX_UID} and after: none is free")


class Sandbox:
    """Runs commands as the submission: `run(argv, ...)`. kind is "bubblewrap", "user" (an
    unprivileged user and the limits, no namespaces) or "none" (--no-sandbox)."""

    def __init__(self, scratch, limits=LIMITS, enabled=True):
        self.scratch = Path(scratch)
        self.limits = limits
        self.root = os.geteuid() == 0
        self.uid, self.uid_lock = sandbox_uid() if self.root else (os.geteuid(), None)
        self.sized = False  # the scratch is a tmpfs of limits.scratch bytes
        self.shared_folders = None  # where every user may write (the fallback's leftovers)
        self.cgroup = None
        self.kind, self.description = "none", "none (--no-sandbox): the tests run as the grader"
        self.prepare_scratch()
        if not enabled:
            return
        bwrap_says = self.try_bubblewrap()
        if bwrap_says is None:
            self.kind = "bubblewrap"
            self.description = ("bubblewrap: namespaces (no network, no other process, only /usr,"
                                " a few /etc files and the scratch folder visible)")
        elif self.root:
            self.kind = "user"
            self.description = (f"an unprivileged user and resource limits, no namespaces "
                                f"(bubblewrap cannot run here: {bwrap_says})")
        else:
            raise SandboxError("bubblewrap cannot run here and the grader is not root, so it "
                               f"cannot run the submissions as another user: {bwrap_says}. Run "
                               "it as root (in a container), install bubblewrap, or give "
                               "--no-sandbox on a machine that holds nothing else")
        if self.root:
            self.cgroup = Cgroup(f"clothlab-grade-{os.getpid()}", limits.memory_total,
                                 limits.processes)
        who = f"uid {self.uid}, no capability" if self.root else "the grader's own user"
        if self.cgroup and self.cgroup.bounds:
            who += (f"; a cgroup of {limits.memory_total // MiB} MB and {limits.processes} "
                    "processes for the whole submission")
        total = (f"at most {self.limits.scratch // MiB} MB written in all" if self.sized else
                 "no bound on the total written (no tmpfs could be mounted; each file is "
                 "bounded)")
        self.description += f"; {who}; {total}"

    # -- the scratch folder --------------------------------------------------------------

    def prepare_scratch(self):
        """Makes the scratch folder, as a tmpfs of limits.scratch bytes where root may mount
        one. Its top folder is root's (the submission's user may pass through it, never list,
        rename or replace what is there): reset() makes the subfolders a step needs."""
        self.scratch.parent.mkdir(mode=0o711, parents=True, exist_ok=True)
        self.scratch.mkdir(mode=0o711, exist_ok=True)
        if self.root:
            os.chown(self.scratch.parent, 0, 0)
            os.chmod(self.scratch.parent, 0o711)
            if not os.path.ismount(self.scratch):
                mounted = subprocess.run(["mount", "-t", "tmpfs", "-o",
                                          f"size={self.limits.scratch},mode=0711,nosuid,nodev",
                                          "clothlab-scratch", str(self.scratch)],
                                         capture_output=True)
                self.sized = mounted.returncode == 0
            else:
                self.sized = True
            os.chown(self.scratch, 0, 0)
            os.chmod(self.scratch, 0o711)

    def release(self):
        self.reset(None)
        if self.cgroup:
            self.cgroup.remove()
        if self.sized and os.path.ismount(self.scratch):
            subprocess.run(["umount", "--lazy", str(self.scratch)], capture_output=True)

    def reset(self, base, own=()):
        """Ends every process of the submission's user, removes what it left in the machine's
        shared places (the fallback), empties the scratch folder and, if base is given, copies
        it there (the kit's copy and its build, root's: read-only to the submission's user).
        Then makes each folder of `own` (names under the scratch) empty and the submission's."""
        self.end_all()
        self.remove_leftovers()
        for child in self.scratch.iterdir() if self.scratch.exists() else ():
            if child.is_dir() and not child.is_symlink():
                shutil.rmtree(child, ignore_errors=True)
            else:
                child.unlink(missing_ok=True)
        if base is not None:
            # cp keeps the times: the build stays incremental.
            subprocess.run(["cp", "-a", f"{base}/.", str(self.scratch)], check=True)
        if self.root:  # (cp gave it base's owner and mode)
            os.chown(self.scratch, 0, 0)
            os.chmod(self.scratch, 0o711)
        for name in own:
            folder = self.scratch / name
            folder.mkdir(mode=0o700)
            self.grant(folder)

    def grant(self, folder):
        """folder and all it holds become the submission's user's (to write)."""
        if self.root:
            subprocess.run(["chown", "-R", f"{self.uid}:{self.uid}", str(folder)], check=True)

    def revoke(self, folder):
        """folder and all it holds become root's again, and read-only to every other user
        (after the build: the tests read the copy, they never change it). Every process of the
        submission's user has ended first, so that nothing it holds open writes on."""
        self.end_all()
        if self.root:
            subprocess.run(["chown", "-R", "0:0", str(folder)], check=True)
            subprocess.run(["chmod", "-R", "go-w", str(folder)], check=True)

    def end_all(self):
        """Every process of the submission's user ends (a compiler that outlived its build, a
        daemon that forked twice and left its session and its cgroup): kill(-1) as that user
        signals exactly its processes, again until none is left. SandboxError when some are
        still there after 10 s (a grader that cannot end them must not go on)."""
        if self.cgroup:
            self.cgroup.end_all()
        if not self.root or self.kind == "none":
            return
        deadline = time.monotonic() + 10
        while True:
            left = processes_of(self.uid)
            if not left:
                return
            if time.monotonic() > deadline:
                raise SandboxError(f"processes of the submissions' user {self.uid} are still "
                                   f"there after 10 s of SIGKILL: {left[:10]}")
            # The shell's own kill: procps may be missing (a minimal container).
            subprocess.run(["setpriv", f"--reuid={self.uid}", f"--regid={self.uid}",
                            "--clear-groups", "--", "/bin/sh", "-c", "kill -9 -1"],
                           capture_output=True)
            time.sleep(0.02)

    def remove_leftovers(self):
        """In the fallback, the submissions share their user and the machine's /tmp, /var/tmp,
        /dev/shm, /run/lock, every other folder that every user may write, and System V IPC:
        what one left there (a file, a shared memory segment) is
        removed before the next one runs, so that nothing of one reaches another. (Bubblewrap
        gives each its own /tmp, /dev and IPC namespace.)"""
        if self.kind != "user" or not self.root:
            return
        if self.shared_folders is None:
            self.shared_folders = world_writable_folders()
        for top in self.shared_folders:
            remove_owned(Path(top), self.uid, depth=2)
        for kind, flag, column in (("shm", "-m", 7), ("sem", "-s", 4), ("msg", "-q", 7)):
            try:
                rows = Path(f"/proc/sysvipc/{kind}").read_text().splitlines()[1:]
            except OSError:
                continue
            for row in rows:
                fields = row.split()
                if len(fields) > column and fields[column] == str(self.uid):
                    subprocess.run(["ipcrm", flag, fields[1]], capture_output=True)

    # -- running a command as the submission ---------------------------------------------

    def prefix(self, writable=(), readable=(), chdir=None, env=None, tmp=True):
        """The words that run a command as the submission, confined: it may write the folders
        of `writable` and read those of `readable` (where bubblewrap holds, nothing else of the
        scratch exists for it; in the fallback, the folders' owners and modes say). With chdir
        and env, the command starts there with exactly that environment (/usr/bin/env), so
        that whoever runs these words needs neither."""
        words = []
        if self.root and self.kind != "none":
            words += ["setpriv", f"--reuid={self.uid}", f"--regid={self.uid}", "--clear-groups",
                      "--no-new-privs", "--inh-caps=-all", "--bounding-set=-all", "--"]
        if self.kind == "bubblewrap":
            words += bubblewrap_words(writable, readable, chdir, self.limits.tmp if tmp
                                      else None)
        if chdir or env is not None:
            # (after NAME=VALUE words, env takes the next word as the command: no "--" there)
            words += ["/usr/bin/env"] + (["-i"] if env is not None else []) + \
                ([f"--chdir={chdir}"] if chdir else []) + \
                ([f"{k}={v}" for k, v in env.items()] if env else ["--"])
        return words

    def try_bubblewrap(self):
        """None when bubblewrap runs here as the submission's user, else why not."""
        if os.environ.get("CLOTHLAB_GRADE_CONFINEMENT") == "user":
            return "CLOTHLAB_GRADE_CONFINEMENT=user (as in a container that refuses namespaces)"
        if not shutil.which("bwrap"):
            return "bubblewrap is not installed (apt-get install bubblewrap)"
        self.kind = "bubblewrap"
        try:
            tried = subprocess.run(self.prefix() + ["/usr/bin/true"], capture_output=True,
                                   text=True, timeout=30)
        except subprocess.TimeoutExpired:
            return "bubblewrap did not start within 30 s"
        finally:
            self.kind = "none"
        if tried.returncode != 0:
            # Its first sentence: bwrap goes on with a link to its README, which has no place
            # in a report that links nowhere.
            said = tried.stderr.strip().split(". ")[0][:200]
            return said or f"exit status {tried.returncode}"
        return None

    def limit(self, cpu_seconds, file_size):
        """The resource limits of a command, set in the child before it becomes the submission
        (the limits are inherited through setpriv and bubblewrap)."""
        limits = self.limits

        def apply():
            os.setsid()  # its own session: the grader ends the group at a time-out
            if self.cgroup:
                self.cgroup.enter()
            for kind, value in ((resource.RLIMIT_AS, limits.memory),
                                (resource.RLIMIT_FSIZE, file_size),
                                (resource.RLIMIT_CPU, int(cpu_seconds)),
                                (resource.RLIMIT_NOFILE, limits.open_files),
                                (resource.RLIMIT_CORE, 0)):
                resource.setrlimit(kind, (value, value))
            if self.kind != "none":
                resource.setrlimit(resource.RLIMIT_NPROC, (limits.processes, limits.processes))
        return apply

    def run(self, argv, seconds, env, stdout, cwd=None, writable=(), readable=(), file_size=None,
            cpu_seconds=None):
        """Runs argv as the submission, in cwd, writing only the folders of `writable`;
        (exit status, timed out). The whole process tree ends when it returns, every process of
        the submission's user with it: at the time-out, or when the command ends first."""
        command = self.prefix(writable, readable, cwd, env) + [str(a) for a in argv]
        process = subprocess.Popen(
            command, cwd="/", env=env, stdout=stdout, stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            preexec_fn=self.limit(cpu_seconds or seconds + 2, file_size or
                                  self.limits.file_size))
        try:
            return wait_then_end(process, seconds)
        finally:
            self.end_all()

    def run_outside(self, argv, seconds, env, stdout, cwd, file_size=None):
        """Runs a program of the teacher's (a checker, verified against the kit) as the grader,
        out of the sandbox, in cwd (a folder of the grader's), within the limits and in the
        submission's cgroup; (exit status, timed out). Its process group ends when it returns:
        the bubblewrap of the runner it started, and so the runner (--die-with-parent)."""
        process = subprocess.Popen(
            [str(a) for a in argv], cwd=cwd, env=env, stdout=stdout, stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            preexec_fn=self.limit(seconds + 2, file_size or self.limits.file_size))
        return wait_then_end(process, seconds)


def world_writable_folders(depth=4):
    """The folders every user may write, /tmp, /var/tmp, /dev/shm and /run/lock first, then
    those found `depth` levels down from / (not in /proc and /sys; not inside one already
    found, which remove_owned goes through): a few tenths of a second, once per grader run."""
    found = [top for top in ("/tmp", "/var/tmp", "/dev/shm", "/run/lock") if os.path.isdir(top)
             and not os.path.islink(top)]
    folders = [("/", 0)]
    while folders:
        folder, level = folders.pop()
        try:
            entries = list(os.scandir(folder))
        except OSError:
            continue
        for entry in entries:
            if entry.path in ("/proc", "/sys"):
                continue
            try:
                if not entry.is_dir(follow_symlinks=False):
                    continue
                mode = entry.stat(follow_symlinks=False).st_mode
            except OSError:
                continue
            if mode & 0o002:
                if entry.path not in found:
                    found.append(entry.path)
            elif level + 1 < depth:
                folders.append((entry.path, level + 1))
    return found


def remove_owned(folder, uid, depth):
    """Removes what uid owns in folder, and, `depth` levels down, in the folders there that
    every user may write (sticky, like /tmp/.X11-unix); never through a link."""
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return
    for entry in entries:
        try:
            info = entry.stat(follow_symlinks=False)
        except OSError:
            continue
        if info.st_uid == uid:
            if stat.S_ISDIR(info.st_mode):
                shutil.rmtree(entry.path, ignore_errors=True)
            else:
                try:
                    os.unlink(entry.path)
                except OSError:
                    pass
        elif depth > 1 and stat.S_ISDIR(info.st_mode) and info.st_mode & 0o002:
            remove_owned(Path(entry.path), uid, depth - 1)


def processes_of(uid):
    """The processes of a user that still live (zombies, already dead, left out): /proc read
    directly, where pgrep or ps may be missing (a minimal container)."""
    found = []
    for entry in os.scandir("/proc"):
        if not entry.name.isdigit():
            continue
        try:
            with open(f"/proc/{entry.name}/status") as status:
                fields = dict(line.split(":", 1) for line in status if ":" in line)
        except OSError:
            continue  # gone meanwhile
        uids = fields.get("Uid", "").split()[:3]
        if str(uid) in uids and not fields.get("State", "").strip().startswith(("Z", "X")):
            found.append(int(entry.name))
    return found


def wait_then_end(process, seconds):
    """(exit status, timed out) of a process started in a session of its own, waited for at most
    `seconds`; its whole process group is killed either way."""
    try:
        code, timed_out = process.wait(timeout=seconds), False
    except subprocess.TimeoutExpired:
        code, timed_out = None, True
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    if code is None:
        code = process.wait()
    return code, timed_out


def bubblewrap_words(writable, readable, chdir, tmp_bytes):
    words = ["bwrap", "--unshare-all", "--die-with-parent", "--new-session",
             "--ro-bind", "/usr", "/usr", "--proc", "/proc", "--dev", "/dev"]
    for top in ("bin", "sbin", "lib", "lib32", "lib64", "libx32"):
        path = Path("/") / top
        if path.is_symlink():
            words += ["--symlink", os.readlink(path), str(path)]
        elif path.is_dir():
            words += ["--ro-bind", str(path), str(path)]
    for name in ETC:
        words += ["--ro-bind-try", f"/etc/{name}", f"/etc/{name}"]
    if tmp_bytes:
        words += ["--size", str(tmp_bytes), "--tmpfs", "/tmp"]
    for path in readable:
        words += ["--ro-bind", str(path), str(path)]
    for path in writable:
        words += ["--bind", str(path), str(path)]
    # The sandbox's own root (the folders made to hold the binds) read-only: it writes only
    # the folders given, its /tmp and /dev/shm (its own, gone with it).
    words += ["--remount-ro", "/"]
    if chdir:
        words += ["--chdir", str(chdir)]
    return words + ["--"]


def environment(home, data_dir=None):
    """The environment of a submission's process: nothing of the grader's."""
    env = {"PATH": "/usr/local/bin:/usr/bin:/bin", "HOME": str(home), "TMPDIR": str(home),
           "LC_ALL": "C.UTF-8", "LANG": "C.UTF-8", "GTEST_COLOR": "no", "CCACHE_DISABLE": "1",
           # Mesa's shader cache in the home (Mesa would take the passwd entry's home)
           "XDG_CACHE_HOME": str(Path(home) / ".cache"),
           "USER": "student", "LOGNAME": "student"}
    if data_dir:
        env["CLOTHLAB_DATA_DIR"] = str(data_dir)
    return env


def read_written(path, limit):
    """The bytes of a file the submission may have written (or replaced by a link): at most
    limit bytes, never through a link, b"" when it is not a plain file."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError:
        return b""
    with os.fdopen(fd, "rb") as f:
        if not os.path.stat.S_ISREG(os.fstat(f.fileno()).st_mode):
            return b""
        return f.read(limit)


def readable_by_submission(sandbox, path):
    """Whether the submission's user could read path, or reach into it (a folder it may pass
    through: the names of a student copy are known), in the fallback."""
    if sandbox.kind != "user":
        return False
    test = "test -r \"$1\" || { test -d \"$1\" && test -x \"$1\"; }"
    tried = subprocess.run(sandbox.prefix() + ["/bin/sh", "-c", test, "sh", str(path)],
                           capture_output=True)
    return tried.returncode == 0


def measure(command, env, cwd):  # pragma: no cover (for docs/teaching.md's numbers)
    """(seconds, peak resident KiB) of a command, via GNU time where installed."""
    with tempfile.NamedTemporaryFile() as out:
        started = time.monotonic()
        subprocess.run(["/usr/bin/time", "-f", "%M", "-o", out.name, *command], env=env,
                       cwd=cwd, capture_output=True)
        return time.monotonic() - started, int(Path(out.name).read_text().split()[-1] or 0)
