#!/usr/bin/env python3
"""scripts/grade against submissions that attack the grader itself: nothing a submission's code
can write is ever run, trusted or read by the grader outside that submission's sandbox, and
nothing of one submission is visible to another. Usage: check_hostile_kit.py PROJECT_ROOT

Each attack starts from the student copy as handed out (every question a stub) and puts its code
in question 5's region (check_hostile.py's `if (clothlab_attack()) { answer } else { stub }`:
an attack that works earns question 5's points), run when the runner starts (a static
constructor) and again in the tests. The class, graded as root with bubblewrap:

  alice           the solution (honest, first)
  eve-checker     renames a fake checker (a script that would write its mark outside, as root)
                  over every checker it can reach: the scratch's build, the kit's checkers/ and
                  its base/, and writes into them
  bob             the stubs, right after: 0 (the kit was not poisoned for the next student)
  eve-poison      writes into everything under the kit (--work) and the scratch that the grader
                  reuses: the base, the manifest, the guards, Mesa's cache, the unpacking's
                  program, the copy's sources and build files
  carol           the solution, a .zip (honest)
  eve-daemon      forks twice, leaves its session (and tries its cgroup), and rewrites every
                  results file it can name for 40 s after the grader ends
  grades.csv, students, report.html, grades.csv.zip   names of the class's outputs (the
                  solution, the stubs, the solution, a .zip of the solution)
  longname.zip    the solution beside a file whose name is 300 bytes long: 80, with a note
  eve-control     a control byte (and a terminal's colour) in the compiler's first error: every
                  output stays valid (junit.xml parses)
  eve-cmdline     reads every process's /proc/PID/cmdline and looks for another student's
                  solution (and the teacher's) under each path it names, and for the files
                  that eve-poison left in /tmp, /dev/shm and /run/lock
  dave            the solution (honest, last)
Then a second grader run over the same --work: the honest student 80, the stubs 0, the kit's
checkers and record unchanged. Then the same attacks with bubblewrap refused
(CLOTHLAB_GRADE_CONFINEMENT=user, as in Docker): a class readable by other users is refused
(every runner could read the others), a closed one is graded with nothing read, and with
  eve-walker      walks the whole file system and tries to write in every folder and every
                  file it sees outside its run folder and the shared places (/tmp, /var/tmp,
                  /dev, /run/lock, which the grader empties of what it left)
earning nothing. Then the
daemon through the Gradescope bundle's run_autograder (AUTOGRADER_ROOT in a folder here), in
the fallback: results.json is the grader's, and stays so. Then `scripts/grade *` in a class
folder that holds a submission named --no-sandbox: refused, and graded in the sandbox with `--`.
After each: no process of the submissions' user is left, and the honest students get 80.
Runs as root (the grader's unprivileged user); skipped otherwise.
"""
import csv
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ElementTree
import zipfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from check_grade import Maker, check, problems, regions, run  # noqa: E402
from check_hostile import COUPLED, attack_file, c_string  # noqa: E402

UID = 65151  # the submissions' user of this test's graders (check_hostile.py has 65150)


WALKER_PRELUDE = r"""#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>
static bool clothlab_own(const std::string& p) {
  char cwd[4096];
  if (!::getcwd(cwd, sizeof cwd)) return false;
  std::string c(cwd);
  // its own run folder (the cwd's parent: run/), its /tmp, /dev, /proc
  std::string run = c.substr(0, c.rfind('/'));
  for (const std::string& own : {run, std::string("/tmp"), std::string("/dev"), std::string("/proc"), std::string("/sys"), std::string("/var/tmp"), std::string("/run/lock")})
    if (p == own || p.rfind(own + "/", 0) == 0) return true;
  return false;
}
static int clothlab_hits = 0;
static void clothlab_walk(const std::string& dir, int depth, int& budget) {
  if (depth > 12 || budget-- <= 0) return;
  DIR* d = ::opendir(dir.c_str());
  if (!d) return;
  std::vector<std::string> subdirs;
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    if (name == "." || name == "..") continue;
    const std::string p = (dir == "/" ? "" : dir) + "/" + name;
    struct stat s;
    if (::lstat(p.c_str(), &s) != 0) continue;
    if (S_ISDIR(s.st_mode)) {
      if (!clothlab_own(p)) {
        const std::string probe = p + "/.eve-walker-probe";
        const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
        if (fd >= 0) { ::close(fd); ::unlink(probe.c_str()); ++clothlab_hits;
          std::fprintf(stderr, "EVE-WALKER wrote in %s\n", p.c_str()); }
      }
      subdirs.push_back(p);
    } else if (S_ISREG(s.st_mode) && !clothlab_own(p)) {
      const int fd = ::open(p.c_str(), O_WRONLY | O_APPEND);
      if (fd >= 0) { ::close(fd); ++clothlab_hits;
        std::fprintf(stderr, "EVE-WALKER could write %s\n", p.c_str()); }
    }
  }
  ::closedir(d);
  for (const std::string& s : subdirs) clothlab_walk(s, depth + 1, budget);
}"""
WALKER_BODY = r"""    int budget = 200000;
    clothlab_walk("/", 0, budget);
    return clothlab_hits > 0;"""


def attack_at_start(maker, folder, prelude, body):
    """attack_file, the attack also run by a static constructor (when the runner starts)."""
    attack_file(maker, folder, prelude, body)
    path = folder / COUPLED
    text = path.read_text()
    end = "  return won;\n}\n"
    path.write_text(text.replace(end, end + "static const bool clothlab_at_start = "
                                            "clothlab_attack();\n", 1))


def writes_any(paths):
    """C++: true when one of paths could be written (created, or opened for writing)."""
    lines = [f"    for (const char* path : {{{', '.join(c_string(p) for p in paths)}}}) {{",
             "      const int fd = ::open(path, O_WRONLY | O_CREAT | O_APPEND, 0755);",
             "      if (fd >= 0) {", "        ::close(fd);", "        hit = true;", "      }",
             "    }"]
    return "\n".join(lines)


def sandbox_processes():
    for _ in range(50):
        out = subprocess.run(["ps", "-eo", "uid=,pid=,stat=,comm="], capture_output=True,
                             text=True).stdout
        left = [line for line in out.splitlines() if int(line.split()[0]) == UID and
                line.split()[2][:1] != "Z"]
        if not left:
            return []
        time.sleep(0.1)
    return left


def snapshot(paths):
    """{path: sha256} of every file under paths."""
    found = {}
    for top in paths:
        for path in sorted(Path(top).rglob("*")) if Path(top).is_dir() else [Path(top)]:
            if path.is_file() and not path.is_symlink():
                found[str(path)] = hashlib.sha256(path.read_bytes()).hexdigest()
    return found


class Class:
    def __init__(self, root, work):
        self.root, self.work = root, work
        self.maker = Maker(root, work)
        self.kit = work / "kit"
        sys.path.insert(0, str(root / "scripts"))
        from clothlab_lab import grading  # the scratch's path, as the grader computes it
        self.scratch = grading.scratch_of(self.kit.resolve())
        self.outside = work / "outside"  # root's alone: a mark there is root's doing
        self.outside.mkdir(mode=0o700)
        self.autograder = work / "autograder"
        # A line of question 5's answer that the stub lacks: the mark of a solution's file.
        (_, solution, stub), = [r for r in regions(root / COUPLED) if r[0] == "Q5"]
        code = [line.strip() for line in solution.splitlines() if line.strip() and
                not line.strip().startswith("//") and line.strip() not in stub]
        self.marker = max(code, key=len)

    def grade(self, out, *subs, env=None, options=(), cwd=None):
        graded = run([self.root / "scripts/grade", "--out", out, "--work", self.kit, *options,
                      "--", *subs], env=dict(os.environ, CLOTHLAB_GRADE_UID=str(UID),
                                             **(env or {})), cwd=cwd)
        print(graded.stderr[-4000:])
        return graded

    def results(self, out):
        return {p.name: json.loads((p / "results.json").read_text())
                for p in (out / "students").iterdir() if (p / "results.json").is_file()}

    def zipped(self, name, tree, extra=()):
        path = self.work / "class" / name
        with zipfile.ZipFile(path, "w") as archive:
            for file in sorted(tree.rglob("*")):
                if file.is_file():
                    archive.write(file, file.relative_to(tree.parent).as_posix())
            for entry, data in extra:
                archive.writestr(entry, data)
        return path

    def attacks(self):
        """{name: folder} of the attacks (made once, graded in every confinement)."""
        m, cls, kit, scratch = self.maker, self.work / "class", self.kit, self.scratch
        made = {}
        fake = self.work / "fake-checker"
        fake.write_text(f"#!/bin/sh\necho ran > {self.outside}/fake-checker-ran\n"
                        "for a; do case $a in --gtest_output=xml:*) printf '<testsuites/>' > "
                        "\"${a#--gtest_output=xml:}\";; esac; done\n")
        checkers = [f"{folder}/lab_{q.lower()}_tests" for q in
                    ("q5", "q6", "q7", "q8", "q9", "q12", "q13")
                    for folder in (scratch / "copy/build-grade/tests/lab", kit / "checkers",
                                   kit / "base/copy/build-grade/tests/lab")]
        eve = m.copy("eve-checker", cls, m.stubs)
        attack_at_start(m, eve, "#include <cstdio>\n#include <fcntl.h>\n#include <sys/stat.h>\n"
                        "#include <unistd.h>\n#include <string>",
                        f"    static const char fake[] = {c_string(fake.read_text())};\n"
                        "    bool hit = false;\n"
                        "    for (const char* path : {"
                        f"{', '.join(map(c_string, checkers))}}}) {{\n"
                        "      const std::string next = std::string(path) + \".new\";\n"
                        "      if (std::FILE* f = std::fopen(next.c_str(), \"w\")) {\n"
                        "        std::fputs(fake, f);\n        std::fclose(f);\n"
                        "        ::chmod(next.c_str(), 0755);\n"
                        "        hit = std::rename(next.c_str(), path) == 0 || hit;\n      }\n"
                        "      const int fd = ::open(path, O_WRONLY | O_TRUNC);\n"
                        "      if (fd >= 0) {\n"
                        "        hit = ::write(fd, fake, sizeof fake - 1) > 0 || hit;\n"
                        "        ::close(fd);\n      }\n    }\n    return hit;")
        made["eve-checker"] = eve
        reused = [kit / "manifest.json", kit / "guards.json", kit / "kit.json", kit / "poison",
                  kit / "checkers/poison", kit / "base/poison", kit / "base/copy/poison",
                  kit / "base/copy/build-grade/build.ninja", kit / "mesa-cache/poison",
                  kit / "stubs" / COUPLED, kit / "logs/poison", kit / "verdicts/poison",
                  scratch / "poison", scratch / "tools/unpack.py", scratch / "tools/poison",
                  scratch / "copy/poison", scratch / "copy" / COUPLED,
                  scratch / "copy/build-grade/build.ninja",
                  scratch / "copy/build-grade/.ninja_log",
                  scratch / "copy/build-grade/tests/lab/lab_runner",
                  scratch / "copy/build-grade/tests/lab/poison",
                  scratch / "copy/shaders/gpu_step.frag", scratch.parent / "poison"]
        # Left in the machine's shared places (the fallback's /tmp, /dev/shm, /run/lock), for the
        # next student's code: eve-cmdline looks for them.
        leftovers = [f"/tmp/{self.work.name}-leftover", f"/dev/shm/{self.work.name}-leftover"]
        leftovers += [f"/run/lock/{self.work.name}-leftover"] if os.path.isdir("/run/lock") else []
        self.leftovers = leftovers
        eve = m.copy("eve-poison", cls, m.stubs)
        attack_at_start(m, eve, "#include <fcntl.h>\n#include <unistd.h>",
                        "    bool hit = false;\n" + writes_any(reused) + "\n"
                        f"    for (const char* path : {{{', '.join(map(c_string, leftovers))}}})"
                        "\n      ::close(::open(path, O_WRONLY | O_CREAT, 0644));\n"
                        "    return hit;")
        made["eve-poison"] = eve
        targets = [self.autograder / "results/results.json"] + [
            self.work / out / "students" / name / "results.json"
            for out in ("out", "out-again", "out-user", "out-options")
            for name in ("alice", "carol", "dave", "eve-daemon", "submission")] + [
            self.work / out / file for out in ("out", "out-user")
            for file in ("grades.csv", "report.html")]
        eve = m.copy("eve-daemon", cls, m.stubs)
        attack_at_start(m, eve, "#include <cstdio>\n#include <fcntl.h>\n#include <unistd.h>",
                        "    if (::fork() == 0) {\n      ::setsid();\n"
                        "      if (::fork() != 0)\n        ::_exit(0);\n"
                        "      const int null = ::open(\"/dev/null\", O_RDWR);\n"
                        "      for (int fd = 0; fd < 3; ++fd)\n        ::dup2(null, fd);\n"
                        "      for (int fd = 3; fd < 1024; ++fd)\n        ::close(fd);\n"
                        "      char pid[32];\n"
                        "      std::snprintf(pid, sizeof pid, \"%d\", int(::getpid()));\n"
                        "      for (const char* procs : {\"/sys/fs/cgroup/memory/cgroup.procs\", "
                        "\"/sys/fs/cgroup/pids/cgroup.procs\", \"/sys/fs/cgroup/cgroup.procs\"})"
                        " {\n        if (std::FILE* f = std::fopen(procs, \"w\")) {\n"
                        "          std::fputs(pid, f);\n          std::fclose(f);\n        }\n"
                        "      }\n"
                        "      for (int i = 0; i < 400; ++i) {\n"
                        f"        for (const char* path : {{{', '.join(map(c_string, targets))}"
                        "}) {\n"
                        "          if (std::FILE* f = std::fopen(path, \"w\")) {\n"
                        "            std::fputs(\"{\\\"score\\\": 1000}\\n\", f);\n"
                        "            std::fclose(f);\n          }\n        }\n"
                        "        ::usleep(100000);\n      }\n      ::_exit(0);\n    }\n"
                        "    return false;")
        made["eve-daemon"] = eve
        eve = m.copy("eve-control", cls, m.stubs)
        path = eve / COUPLED
        path.write_bytes(path.read_bytes() + b"\n#error clothlab \x07\x01\x1b[31m red \x0c\n")
        made["eve-control"] = eve
        eve = m.copy("eve-cmdline", cls, m.stubs)
        attack_at_start(
            m, eve, "#include <dirent.h>\n#include <fstream>\n#include <sstream>\n"
                    "#include <string>\n#include <vector>",
            "    bool hit = false;\n"
            "    std::vector<std::string> places;\n"
            "    if (DIR* proc = ::opendir(\"/proc\")) {\n"
            "      while (const dirent* entry = ::readdir(proc)) {\n"
            "        std::ifstream cmdline(std::string(\"/proc/\") + entry->d_name + "
            "\"/cmdline\");\n"
            "        std::string word;\n"
            "        while (std::getline(cmdline, word, '\\0'))\n"
            # (the grader's paths: this test's folder and the teacher's tree, not those of
            # other work on this machine, which the fallback does not hide: docs/teaching.md)
            f"          if ((word.rfind({c_string(self.work)}, 0) == 0 || "
            f"word.rfind({c_string(self.root)}, 0) == 0) &&\n"
            "              word.find(\"eve-cmdline\") == std::string::npos)\n"
            "            for (std::string up = word; up.size() > 1; "
            "up = up.substr(0, up.rfind('/')))\n"
            "              places.push_back(up);\n"
            "      }\n      ::closedir(proc);\n    }\n"
            f"    places.push_back({c_string(kit / 'staged/00000')});\n"
            f"    places.push_back({c_string(kit / 'staged/00001')});\n"
            f"    for (const char* left : {{{', '.join(map(c_string, leftovers))}}})\n"
            "      if (std::ifstream(left))\n        hit = true;  // another student's\n"
            "    for (const std::string& place : places)\n"
            "      for (const char* below : {\"/" + COUPLED + "\", \"/clothlab/" + COUPLED +
            "\"}) {\n"
            "        std::ifstream file(place + below);\n"
            "        std::stringstream text;\n        text << file.rdbuf();\n"
            # Another's solution (or the teacher's): the answer, without this attack's code.
            f"        if (text.str().find({c_string(self.marker)}) != std::string::npos &&\n"
            "            text.str().find(\"clothlab_attack\") == std::string::npos)\n"
            "          hit = true;\n      }\n    return hit;")
        made["eve-cmdline"] = eve
        # Tries to write every folder and file it can see outside its own run folder and the
        # places every user may write (which the grader empties after it).
        eve = m.copy("eve-walker", cls, m.stubs)
        attack_at_start(m, eve, WALKER_PRELUDE, WALKER_BODY)
        made["eve-walker"] = eve
        return made


def main():
    root = Path(sys.argv[1]).resolve()
    if os.geteuid() != 0:
        print("check_hostile_kit: not root: the grader cannot run the submissions as another "
              "user here; skipped")
        return 0
    work = Path(tempfile.mkdtemp(prefix="clothlab-hostile-kit-"))
    started = time.monotonic()
    mode = root.stat().st_mode
    try:
        c = Class(root, work)
        m, cls = c.maker, work / "class"
        cls.mkdir()
        eves = c.attacks()
        alice = m.copy("alice", cls)
        bob = m.copy("bob", cls, m.stubs)
        carol = c.zipped("carol.zip", m.copy("carol-clothlab", work))
        dave = m.copy("dave", cls)
        named = {"grades.csv": m.copy("grades.csv", cls), "students": m.copy("students", cls),
                 "report.html": m.copy("report.html", cls, m.stubs)}
        collision = c.zipped("grades.csv.zip", m.copy("clothlab", work / "zipped"))
        longname = c.zipped("longname.zip", m.copy("clothlab", work / "long"),
                            [("clothlab/notes/" + "n" * 300 + ".txt", "a very long name\n")])
        honest = {"alice", "carol", "dave", "grades.csv", "students", "grades.csv-2",
                  "longname"}

        # The kit, made before the class: what the class must leave as it is.
        made = run([root / "scripts/grade", "--work", c.kit, "--prepare"],
                   env=dict(os.environ, CLOTHLAB_GRADE_UID=str(UID)))
        if not check(made.returncode == 0, f"--prepare failed: {made.stderr[-3000:]}"):
            return 1
        kept = [c.kit / "checkers", c.kit / "stubs", c.kit / "manifest.json",
                c.kit / "guards.json", c.kit / "kit.json"]
        before = snapshot(kept)

        # 1. Bubblewrap.
        out = work / "out"
        subs = [alice, eves["eve-checker"], bob, eves["eve-poison"], carol, eves["eve-daemon"],
                named["grades.csv"], named["students"], named["report.html"], collision,
                longname, eves["eve-control"], eves["eve-cmdline"], dave]
        graded = c.grade(out, *subs)
        if not check(graded.returncode == 0, "scripts/grade failed on the class"):
            return 1
        check("bubblewrap:" in graded.stderr, "bubblewrap did not hold here")
        left = sandbox_processes()
        check(not left, f"processes of the submissions' user are left: {left}")
        results = c.results(out)
        expect_class(c, out, results, honest, "bubblewrap")
        time.sleep(3)  # (a daemon would write by now)
        check(c.results(out) == results, "a results.json changed after the grader ended")
        check(snapshot(kept) == before, "the kit's checkers, stubs, manifest, guards or record "
                                        "changed while grading the class")
        junit = out / "students" / "eve-control" / "junit.xml"
        try:
            tree = ElementTree.parse(junit)
            text = ElementTree.tostring(tree.getroot(), encoding="unicode")
            check("\\x07" in text and "\x1b" not in text,
                  f"eve-control's junit.xml does not write the control byte out: {text[-800:]}")
        except ElementTree.ParseError as error:
            check(False, f"eve-control's junit.xml is not XML: {error}")
        check("\\\\x07" in json.dumps(results.get("eve-control", {})),
              "eve-control's results.json does not show the compiler's error, control byte "
              "written out")

        # 2. The grader's next run over the same --work: unaffected.
        again = c.grade(work / "out-again", alice, bob)
        second = c.results(work / "out-again")
        check(again.returncode == 0 and second.get("alice", {}).get("score") == 80 and
              second.get("bob", {}).get("score") == 0,
              f"the next run: alice {second.get('alice', {}).get('score')}, bob "
              f"{second.get('bob', {}).get('score')}")
        check(snapshot(kept) == before, "the kit changed for the grader's next run")

        # 3. The fallback (no namespaces): a class that other users can read is refused; a
        # closed one is graded, nothing read, nothing left.
        fallback = {"CLOTHLAB_GRADE_CONFINEMENT": "user"}
        os.chmod(root, mode & ~0o007)
        try:
            open_class = work / "open-class"
            open_class.mkdir(mode=0o755)
            os.chmod(open_class, 0o755)
            os.chmod(work, 0o755)
            shutil.copytree(alice, open_class / "alice")
            shutil.copytree(bob, open_class / "bob")
            refused = c.grade(work / "out-open", open_class / "alice", open_class / "bob",
                              env=fallback)
            check(refused.returncode == 1 and "could read the submissions" in refused.stderr,
                  "the fallback graded a class that every submission's user can read")
            os.chmod(work, 0o700)
            user = c.grade(work / "out-user", alice, eves["eve-checker"], eves["eve-poison"],
                           eves["eve-daemon"], eves["eve-cmdline"], eves["eve-walker"], carol,
                           env=fallback)
        finally:
            os.chmod(root, mode)
        if check(user.returncode == 0 and "an unprivileged user and resource limits" in
                 user.stderr, "the fallback did not grade the closed class"):
            left = sandbox_processes()
            check(not left, f"fallback: processes of the submissions' user are left: {left}")
            got = c.results(work / "out-user")
            for name in ("alice", "carol"):
                check(got.get(name, {}).get("score") == 80, f"fallback: {name} got "
                                                            f"{got.get(name, {}).get('score')}")
            for name in ("eve-checker", "eve-poison", "eve-daemon", "eve-cmdline", "eve-walker"):
                check(got.get(name, {}).get("score") == 0, f"fallback: {name} earned "
                      f"{got.get(name, {}).get('score')}: {q5(got.get(name, {}))}")
            time.sleep(3)
            check(c.results(work / "out-user") == got,
                  "fallback: a results.json changed after the grader ended")
        check(not (c.outside / "fake-checker-ran").exists(), "the fake checker ran as root")
        check(snapshot(kept) == before, "the kit changed in the fallback")
        check(not any(Path(p).exists() for p in c.leftovers),
              f"fallback: what a submission left in a shared folder is still there: "
              f"{[p for p in c.leftovers if Path(p).exists()]}")

        # 4. Gradescope: the daemon through the bundle's run_autograder, in the fallback.
        autograder(c, root, eves["eve-daemon"], fallback)

        # 5. A submission named --no-sandbox, in the class folder, from `scripts/grade *`.
        options_class = work / "options"
        options_class.mkdir()
        shutil.copytree(alice, options_class / "alice")
        shutil.copytree(m.stubs, options_class / "--no-sandbox")
        attack_file(m, options_class / "--no-sandbox", "#include <cstdio>\n#include <unistd.h>",
                    f"    std::FILE* answers = std::fopen({c_string(root / 'docs/answers.md')}, "
                    "\"r\");\n    return ::getuid() == 0 || answers != nullptr;")
        grade = f"{root / 'scripts/grade'} --out {work / 'out-options'} --work {c.kit}"
        for line in (f"{grade} *", f"{grade.split(' --out')[0]} * --out {work / 'out-options'}"
                     f" --work {c.kit}"):
            tried = run(["bash", "-c", line], cwd=options_class,
                        env=dict(os.environ, LC_ALL="C", CLOTHLAB_GRADE_UID=str(UID)))
            check(tried.returncode == 2 and "--" in tried.stderr and "./" in tried.stderr and
                  not (work / "out-options" / "students").exists(),
                  f"`{line}` was not refused: {tried.returncode} {tried.stderr[-800:]}")
        safe = run(["bash", "-c", f"{grade} -- *"], cwd=options_class,
                   env=dict(os.environ, LC_ALL="C", CLOTHLAB_GRADE_UID=str(UID)))
        got = c.results(work / "out-options") if (work / "out-options").is_dir() else {}
        check(safe.returncode == 0 and "bubblewrap:" in safe.stderr and
              got.get("--no-sandbox", {}).get("score") == 0 and
              got.get("alice", {}).get("score") == 80,
              f"`scripts/grade ... -- *`: {safe.stderr[-1500:]} {sorted(got)}")
        check(not sandbox_processes(), "processes of the submissions' user are left")
    finally:
        os.chmod(root, mode)
        print(f"check_hostile_kit: {time.monotonic() - started:.0f} s")
        if not problems:
            shutil.rmtree(work, ignore_errors=True)
        else:
            print(f"(the class and its grades are left in {work} to look at)")
    if problems:
        print(f"\n{len(problems)} problem(s) with scripts/grade under attack:")
        for p in problems:
            print("  - " + p.splitlines()[0])
        return 1
    print("nothing a submission wrote was run, trusted or read outside its sandbox; the honest "
          "students get their grade")
    return 0


def q5(result):
    return next((t.get("output", "")[:600] for t in result.get("tests", [])
                 if t["name"].startswith("Q5")), "")


def expect_class(c, out, results, honest, where):
    for name in sorted(honest):
        check(results.get(name, {}).get("score") == 80,
              f"{where}: {name} (the solution) should get 80, got "
              f"{results.get(name, {}).get('score')}: {results.get(name, {}).get('output')}")
    for name in ("bob", "eve-checker", "eve-poison", "eve-daemon", "report.html",
                 "eve-control", "eve-cmdline"):
        check(results.get(name, {}).get("score") == 0,
              f"{where}: {name} should earn nothing, got {results.get(name, {}).get('score')}: "
              f"{q5(results.get(name, {}))}")
    check(not (c.outside / "fake-checker-ran").exists(), f"{where}: the fake checker ran as root")
    check("longer than 255 bytes" in results.get("longname", {}).get("output", ""),
          f"{where}: the 300-byte name is not noted: {results.get('longname', {}).get('output')}")
    check("does not compile" in results.get("eve-control", {}).get("output", ""),
          f"{where}: eve-control's compile error is not reported")
    # The class's outputs: files, whatever the students are named.
    if check((out / "grades.csv").is_file() and (out / "report.html").is_file(),
             f"{where}: grades.csv or report.html is not a file"):
        with open(out / "grades.csv", newline="") as f:
            rows = {row[0]: row for row in list(csv.reader(f))[1:]}
        check(len(rows) == len(results) == 14, f"{where}: grades.csv has {len(rows)} rows, "
                                               f"{len(results)} results.json for 14 submissions")
        check(rows.get("grades.csv", [""] * 9)[8] == "80", f"{where}: grades.csv's own row: "
                                                          f"{rows.get('grades.csv')}")


def autograder(c, root, daemon, fallback):
    """The bundle's run_autograder on the daemon's files, Gradescope's folders here."""
    bundle = c.work / "autograder.zip"
    made = run([root / "scripts/grade", "--gradescope-bundle", bundle])
    if not check(made.returncode == 0, f"--gradescope-bundle failed: {made.stderr}"):
        return
    source = c.autograder / "source"
    with zipfile.ZipFile(bundle) as archive:
        archive.extractall(source)
    (c.autograder / "submission").mkdir()
    shutil.copytree(daemon, c.autograder / "submission" / "clothlab")
    shutil.copy2(source / "run_autograder", c.autograder / "run_autograder")
    os.chmod(c.autograder / "run_autograder", 0o755)
    ran = run([c.autograder / "run_autograder"], env=dict(
        os.environ, AUTOGRADER_ROOT=str(c.autograder), CLOTHLAB_GRADE_KIT=str(c.kit),
        CLOTHLAB_GRADE_UID=str(UID), **fallback))
    produced = c.autograder / "results" / "results.json"
    if not check(ran.returncode == 0 and produced.is_file(),
                 f"run_autograder wrote no results.json: {ran.stdout[-2000:]}"):
        return
    first = produced.read_bytes()
    result = json.loads(first)
    check(result.get("score") == 0 and len(result.get("tests", [])) == 7 and
          "an unprivileged user" in ran.stdout,
          f"run_autograder: the daemon's submission got {result.get('score')}: "
          f"{ran.stdout[-1500:]}")
    check(sorted(os.listdir(c.autograder / "results")) == ["results.json"],
          f"/autograder/results holds more than results.json: "
          f"{os.listdir(c.autograder / 'results')}")
    check((c.autograder / "results").stat().st_mode & 0o777 == 0o700,
          "/autograder/results is open to other users")
    check(not sandbox_processes(), "run_autograder: processes of the submissions' user are left")
    time.sleep(3)
    check(produced.read_bytes() == first, "run_autograder: results.json changed after the end")


if __name__ == "__main__":
    sys.exit(main())
