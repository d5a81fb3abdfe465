#!/usr/bin/env python3
"""scripts/grade against a hostile class. Usage: check_hostile.py PROJECT_ROOT

Each attack starts from the student copy as handed out (every question a stub) and puts its code
in question 5's region of src/core/coupled_springs.cpp as

    if (clothlab_attack()) { <question 5's answer> } else { <the stub> }

so that an attack that reaches what it wants earns question 5's points: "earns nothing" and
"reads nothing" are one check. Around the attacks, honest students (the solution) must get
their 80 points. The class:

  alice             the solution, a folder (honest, first)
  eve-reads         at run time: the teacher's answers and solution, another student's
                    submission, the grades, the kit, /etc/shadow, the grader's environment
  eve-has-include   at compile time: __has_include of the same files
  eve-incbin        at compile time: .incbin of the teacher's docs/answers.md
  eve-socket        a Unix socket of the host outside /tmp, and an abstract one
  eve-forks         400 processes forked, 6 GiB of memory asked and touched
  eve-filler        fills every writable place it finds, before an honest student
  carol             the solution, a .zip (honest, right after the filler)
  eve-smudge        the solution as a bare git repository whose config and .gitattributes set a
                    smudge filter (and a hook) that would break every file and touch a file
                    outside: graded on the bytes of its commit, and nothing runs
  troedel           the solution as a .tar.gz whose own name and one file name are not UTF-8
  eve-zipbomb       a .zip of 300 MB of zeros (about 300 KB): cut at 2 MB, nothing graded
  eve-entries       a .tar.gz of 30,000 empty files
  @SUM(1+1), -2+3   names that a spreadsheet would read as formulas
Then, graded alone with --build-timeout 20: a compile that never ends (constexpr loops), and
`#include "/dev/zero"`: both stopped, and no process of the submissions' users left. Then
eve-reads and an honest student again with bubblewrap refused (CLOTHLAB_GRADE_CONFINEMENT=user,
as in Docker): the fallback still reads nothing and says which confinement held.

The forged verdict (an atexit handler that rewrites GoogleTest's XML) and the in-memory patch of
GoogleTest are graded too: they earn nothing, the verdict being the checker's (tests/lab's
checker and runner). The attacks on the grader itself (a fake checker, the kit poisoned, a
daemon, names that collide or read as options, ...) are in check_hostile_kit.py.
Runs as root (the grader's unprivileged user and its cgroup); skipped otherwise.
"""
import csv
import json
import os
import shutil
import socket
import subprocess
import sys
import tarfile
import tempfile
import threading
import time
import zipfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from check_grade import Maker, check, problems, regions, run  # noqa: E402

COUPLED = "src/core/coupled_springs.cpp"


def attack_file(maker, folder, prelude, attack_body):
    """Question 5's region of folder's coupled_springs.cpp becomes `if (clothlab_attack())
    { answer } else { stub }`, clothlab_attack() written after the file's includes."""
    path = folder / COUPLED
    text = path.read_text()
    (_, solution, stub), = [r for r in regions(maker.root / COUPLED) if r[0] == "Q5"]
    if stub not in text:
        check(False, f"{folder.name}: the stub of Q5 is not in the copy")
        return
    text = text.replace(stub, f"if (clothlab_attack()) {{\n{solution}\n}} else {{\n{stub}\n}}")
    anchor = '#include "core/integrator.hpp"\n'
    function = (f"{prelude}\nstatic bool clothlab_attack() {{\n  static const bool won = [] {{\n"
                f"{attack_body}\n  }}();\n  return won;\n}}\n")
    path.write_text(text.replace(anchor, anchor + function, 1))


def c_string(text):
    return json.dumps(str(text))


class Listener:
    """A Unix socket of the host (a path outside /tmp, and an abstract name): counts who
    connects."""

    def __init__(self, folder):
        self.path = folder / "host.sock"
        self.abstract = f"clothlab-hostile-{os.getpid()}"
        self.connections = 0
        self.sockets = []
        for address in (str(self.path), "\0" + self.abstract):
            s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            s.bind(address)
            s.listen(8)
            self.sockets.append(s)
            threading.Thread(target=self.serve, args=(s,), daemon=True).start()
        os.chmod(folder, 0o777)
        os.chmod(self.path, 0o777)

    def serve(self, s):
        while True:
            try:
                connection, _ = s.accept()
            except OSError:
                return
            self.connections += 1
            connection.close()


UID = 65150  # the submissions' user of this test's graders (CLOTHLAB_GRADE_UID): no other's


def sandbox_processes():
    """The processes of this test's submissions' user, a few seconds after its grader ended
    (a process killed takes a moment to be gone)."""
    for _ in range(50):
        out = subprocess.run(["ps", "-eo", "uid=,pid=,stat=,comm="], capture_output=True,
                             text=True).stdout
        left = [line for line in out.splitlines() if int(line.split()[0]) == UID]
        if not left:
            return []
        time.sleep(0.1)
    return left


def main():
    root = Path(sys.argv[1]).resolve()
    if os.geteuid() != 0:
        print("check_hostile: not root: the grader cannot run the submissions as another user "
              "here; skipped")
        return 0
    work = Path(tempfile.mkdtemp(prefix="clothlab-hostile-"))
    outside = Path(tempfile.mkdtemp(prefix="clothlab-hostile-host-", dir="/var/tmp"))
    started = time.monotonic()
    try:
        maker = Maker(root, work)
        cls = work / "class"
        cls.mkdir()
        out = work / "out"
        kit = work / "kit"
        listener = Listener(outside)
        secret = "CLOTHLAB_HOSTILE_SECRET"
        subs = []

        subs.append(maker.copy("alice", cls))
        reads = [root / "docs/answers.md", root / COUPLED, cls / "alice" / COUPLED,
                 out / "students" / "alice" / "results.json", kit / "base/copy/CMakeLists.txt",
                 kit / "manifest.json", "/etc/shadow", outside / "host.sock"]
        opens = "\n".join(f"    if (std::FILE* f = std::fopen({c_string(p)}, \"r\")) {{\n"
                          "      std::fclose(f);\n      return true;\n    }" for p in reads)
        eve = maker.copy("eve-reads", cls, maker.stubs)
        attack_file(maker, eve, "#include <cstdio>\n#include <cstdlib>",
                    f"{opens}\n    return std::getenv(\"{secret}\") != nullptr;")
        subs.append(eve)
        eve = maker.copy("eve-has-include", cls, maker.stubs)
        seen = " || ".join(f"__has_include({c_string(p)})" for p in reads[:6])
        attack_file(maker, eve, f"#if {seen}\n#define CLOTHLAB_SEEN true\n#else\n"
                                "#define CLOTHLAB_SEEN false\n#endif", "    return CLOTHLAB_SEEN;")
        subs.append(eve)
        eve = maker.copy("eve-incbin", cls, maker.stubs)
        attack_file(maker, eve, 'asm(".section .rodata\\n.global clothlab_blob\\nclothlab_blob:\\n'
                    f'.incbin \\"{root / "docs/answers.md"}\\"\\n.byte 0\\n.previous");\n'
                    'extern "C" const char clothlab_blob[];',
                    "    return clothlab_blob[0] != 0;")
        subs.append(eve)
        eve = maker.copy("eve-socket", cls, maker.stubs)
        attack_file(maker, eve, "#include <cstddef>\n#include <cstring>\n#include <sys/socket.h>\n"
                    "#include <sys/un.h>\n#include <unistd.h>\n"
                    "static bool clothlab_connects(const char* name, bool abstract) {\n"
                    "  const int fd = socket(AF_UNIX, SOCK_STREAM, 0);\n"
                    "  if (fd < 0)\n    return false;\n  sockaddr_un a{};\n"
                    "  a.sun_family = AF_UNIX;\n"
                    "  std::strcpy(a.sun_path + (abstract ? 1 : 0), name);\n"
                    "  const socklen_t n = offsetof(sockaddr_un, sun_path) + std::strlen(name) + "
                    "(abstract ? 1 : 0);\n"
                    "  const bool ok = connect(fd, reinterpret_cast<sockaddr*>(&a), n) == 0;\n"
                    "  close(fd);\n  return ok;\n}",
                    f"    return clothlab_connects({c_string(listener.path)}, false) ||\n"
                    f"           clothlab_connects({c_string(listener.abstract)}, true);")
        subs.append(eve)
        eve = maker.copy("eve-forks", cls, maker.stubs)
        attack_file(maker, eve, "#include <cstdlib>\n#include <cstring>\n#include <unistd.h>",
                    "    int made = 0;\n    for (int i = 0; i < 400; ++i) {\n"
                    "      const pid_t pid = fork();\n      if (pid == 0) {\n        pause();\n"
                    "        _exit(0);\n      }\n      if (pid < 0)\n        break;\n      ++made;\n"
                    "    }\n    std::size_t touched = 0;\n    for (int i = 0; i < 24; ++i) {\n"
                    "      const std::size_t block = std::size_t(256) << 20;\n"
                    "      char* p = static_cast<char*>(std::malloc(block));\n"
                    "      if (p == nullptr)\n        break;\n      std::memset(p, 1, block);\n"
                    "      touched += block;\n    }\n"
                    "    return made >= 400 && touched >= (std::size_t(6) << 30);")
        subs.append(eve)
        eve = maker.copy("eve-filler", cls, maker.stubs)
        attack_file(maker, eve, "#include <cstdio>\n#include <cstdlib>\n#include <cstring>\n"
                    "#include <string>",
                    "    static char block[1000000];\n    std::memset(block, 'x', sizeof block);\n"
                    "    const char* home = std::getenv(\"HOME\");\n"
                    "    for (const std::string folder : {std::string(\".\"), std::string(home ? "
                    "home : \".\"), std::string(\"/tmp\")}) {\n"
                    "      for (int i = 0; i < 3000; ++i) {\n"
                    "        const std::string name = folder + \"/fill-\" + std::to_string(i);\n"
                    "        std::FILE* f = std::fopen(name.c_str(), \"wb\");\n"
                    "        if (f == nullptr)\n          break;\n"
                    "        const bool full = std::fwrite(block, 1, sizeof block, f) != "
                    "sizeof block;\n        std::fclose(f);\n        if (full)\n          break;\n"
                    "      }\n    }\n    return false;")
        subs.append(eve)
        carol = maker.copy("carol-clothlab", work)
        with zipfile.ZipFile(cls / "carol.zip", "w") as archive:
            for path in sorted(carol.rglob("*")):
                if path.is_file():
                    archive.write(path, path.relative_to(work).as_posix())
        subs.append(cls / "carol.zip")
        smudge = maker.copy("smudge-tree", work)
        (smudge / ".gitattributes").write_text("* filter=x\n")
        git = ["git", "-c", "user.name=Eve", "-c", "user.email=eve@example.org"]
        run(["git", "init", "-q", smudge])
        run(git + ["-C", smudge, "add", "-A"])
        run(git + ["-C", smudge, "commit", "-q", "-m", "lab"])
        run(["git", "clone", "-q", "--bare", smudge, cls / "eve-smudge.git"])
        bare = cls / "eve-smudge.git"
        run(["git", "--git-dir", bare, "config", "filter.x.smudge",
             f"sh -c 'touch {outside}/smudged; printf BROKEN; cat'"])
        run(["git", "--git-dir", bare, "config", "filter.x.required", "true"])
        for hook in ("post-checkout", "pre-auto-gc", "reference-transaction"):
            (bare / "hooks" / hook).write_text(f"#!/bin/sh\ntouch {outside}/hooked\n")
            os.chmod(bare / "hooks" / hook, 0o755)
        (bare / "info").mkdir(exist_ok=True)
        (bare / "info" / "attributes").write_text("* filter=x\n")
        subs.append(bare)
        troedel = os.fsencode(cls) + b"/tr\xf6del.tar.gz"
        solution = maker.copy("troedel-clothlab", work)
        (solution / "notes").mkdir()
        open(os.fsencode(solution / "notes") + b"/r\xe9sum\xe9-\xff.txt", "wb").write(b"mine\n")
        with tarfile.open(os.fsdecode(troedel), "w:gz") as archive:
            archive.add(solution, "troedel-clothlab")
        subs.append(Path(os.fsdecode(troedel)))
        with zipfile.ZipFile(cls / "eve-zipbomb.zip", "w", zipfile.ZIP_DEFLATED) as archive:
            with archive.open("clothlab/src/core/zeros.bin", "w", force_zip64=True) as member:
                block = bytes(1 << 20)
                for _ in range(300):
                    member.write(block)
        subs.append(cls / "eve-zipbomb.zip")
        with tarfile.open(cls / "eve-entries.tar.gz", "w:gz") as archive:
            for i in range(30000):
                archive.addfile(tarfile.TarInfo(f"clothlab/empty/{i}"))
        subs.append(cls / "eve-entries.tar.gz")
        subs.append(maker.copy("@SUM(1+1)", cls, maker.stubs))
        subs.append(maker.copy("-2+3", cls, maker.stubs))

        teacher_before = subprocess.run(["git", "-C", root, "status", "--porcelain"],
                                        capture_output=True, text=True).stdout
        env = dict(os.environ, **{secret: "the grader's secret", "CLOTHLAB_GRADE_UID": str(UID)})
        graded = run([root / "scripts/grade", "--out", out, "--work", kit, "--scratch-size",
                      "300", "--", *subs], env=env)
        print(graded.stdout + graded.stderr[-8000:])
        if not check(graded.returncode == 0, "scripts/grade failed on the hostile class"):
            return 1
        # Where bubblewrap cannot run (a chroot, Docker's seccomp), the grader falls back to an
        # unprivileged user without namespaces: a host socket that any user can reach, and the
        # paths of the scratch, are then within the submission's reach (docs/teaching.md, the
        # threat model). Those checks are reported, not required, there; every other one is.
        namespaces = "bubblewrap:" in graded.stderr
        if not namespaces:
            check("bubblewrap cannot run here" in graded.stderr,
                  "the grader did not use bubblewrap, and did not say why")
            print("KNOWN (fallback, no namespaces here): a host socket that any user can reach, "
                  "and the scratch's paths, are not hidden from a submission")

        def check_with_namespaces(condition, message):
            if namespaces:
                return check(condition, message)
            if not condition:
                print(f"KNOWN (fallback): {message}")
            return True

        students = out / "students"
        names = {p.name: json.loads((p / "results.json").read_text())
                 for p in students.iterdir() if (p / "results.json").is_file()}
        print("graded:", ", ".join(f"{n} {r['score']:g}" for n, r in sorted(names.items())))

        def score(name):
            return names.get(name, {}).get("score")

        def q5(name):
            tests = names.get(name, {}).get("tests", [])
            return next((t for t in tests if t["name"].startswith("Q5")), {})

        for honest in ("alice", "carol", "eve-smudge", "tr_del"):
            check(score(honest) == 80, f"{honest} (the solution) should get 80, got "
                                       f"{score(honest)}: {names.get(honest, {}).get('output')}")
        for eve in ("eve-reads", "eve-has-include", "eve-incbin", "eve-socket", "eve-forks",
                    "eve-filler", "eve-zipbomb", "eve-entries", "@SUM_1_1", "-2_3"):
            (check_with_namespaces if eve == "eve-socket" else check)(
                score(eve) == 0,
                f"{eve} should earn nothing, got {score(eve)}: {q5(eve).get('output', '')[:800]}")
        answers_line = next(line for line in (root / "docs/answers.md").read_text().splitlines()
                            if len(line.strip()) > 20)
        everything = "\n".join((p / "results.json").read_text() for p in students.iterdir()
                               if p.is_dir()) + (out / "grades.csv").read_text() + \
            (out / "report.html").read_text()
        check(answers_line not in everything and "root:" not in everything and
              "the grader's secret" not in everything,
              "a line of docs/answers.md, /etc/passwd or the grader's environment is in the "
              "outputs")
        others = "\n".join((p / "results.json").read_text() for p in students.iterdir()
                           if p.is_dir() and p.name != "eve-incbin")  # (its own line quotes it)
        check(str(root) not in others, "the teacher's tree's path is in the outputs")
        check_with_namespaces("/var/tmp/clothlab-grade" not in everything and
                              str(kit) not in everything, "the grader's paths are in the outputs")
        check_with_namespaces(listener.connections == 0, f"the host's socket was reached "
                                                         f"{listener.connections} times")
        check(not (outside / "smudged").exists() and not (outside / "hooked").exists(),
              "the bare repository's smudge filter or hook ran")
        check("BROKEN" not in json.dumps(names.get("eve-smudge", {})),
              "the smudge filter's output was graded")
        check("not UTF-8" in names.get("tr_del", {}).get("output", ""),
              f"the file name that is not UTF-8 is not reported: {names.get('tr_del')}")
        for bomb, words in (("eve-zipbomb", "larger than 2 MB: cut"), ("eve-entries", "refused")):
            check(words in names.get(bomb, {}).get("output", ""),
                  f"{bomb}: not refused: {names.get(bomb, {}).get('output')}")
        with open(out / "grades.csv", newline="") as f:
            rows = list(csv.reader(f))
        check(all(not row[0].startswith(("=", "+", "-", "@")) for row in rows[1:]) and
              any(row[0] == "'@SUM_1_1" for row in rows) and
              any(row[0] == "'-2_3" for row in rows),
              f"grades.csv: a name a spreadsheet reads as a formula: {[r[0] for r in rows]}")
        check(len(rows) == len(subs) + 1, f"grades.csv has {len(rows) - 1} rows for "
                                          f"{len(subs)} submissions")
        check(not sandbox_processes(), f"processes of the submissions' users are left: "
                                       f"{sandbox_processes()}")
        check(subprocess.run(["git", "-C", root, "status", "--porcelain"], capture_output=True,
                             text=True).stdout == teacher_before,
              "the teacher's repository changed during the grading")

        # Compiles that never end, alone.
        forever = maker.copy("eve-forever", cls, maker.stubs)
        attack_file(maker, forever, "constexpr long clothlab_spin() {\n  long s = 0;\n"
                    "  for (long i = 0; i < 200000; ++i)\n"
                    "    for (long j = 0; j < 200000; ++j)\n      s += i ^ j;\n  return s;\n}\n"
                    "static_assert(clothlab_spin() != 1);", "    return false;")
        zero = maker.copy("eve-dev-zero", cls, maker.stubs)
        attack_file(maker, zero, '#include "/dev/zero"', "    return false;")
        began = time.monotonic()
        graded = run([root / "scripts/grade", "--out", work / "out-forever", "--work", kit,
                      "--build-timeout", "20", "--", forever, zero], env=env)
        spent = time.monotonic() - began
        print(graded.stderr[-3000:])
        for name in ("eve-forever", "eve-dev-zero"):
            result = json.loads((work / "out-forever" / "students" / name / "results.json").read_text())
            check(result["score"] == 0, f"{name}: {result['score']}")
        check(spent < 200, f"two compiles stopped at 20 s took {spent:.0f} s to grade")
        check(not sandbox_processes(), f"a compiler outlived its build: {sandbox_processes()}")

        # Where bubblewrap is refused: the unprivileged user, the limits, the private scratch.
        # The teacher's tree closed to other users, as docs/teaching.md asks for this case.
        mode = root.stat().st_mode
        os.chmod(root, mode & ~0o007)
        try:
            fallback = run([root / "scripts/grade", "--out", work / "out-user", "--work", kit,
                            "--", cls / "eve-reads", cls / "alice"],
                           env=dict(env, CLOTHLAB_GRADE_CONFINEMENT="user"))
        finally:
            os.chmod(root, mode)
        print(fallback.stderr[-3000:])
        if "could read the teacher's files" in fallback.stderr:
            print("(the fallback refuses to grade from this teacher's tree, readable by every "
                  "user: as it must)")
        elif check(fallback.returncode == 0, "the fallback grading failed"):
            check("an unprivileged user and resource limits" in fallback.stderr,
                  "the fallback does not say which confinement held")
            results = {n: json.loads((work / "out-user" / "students" / n / "results.json").read_text())
                       for n in ("eve-reads", "alice")}
            check(results["alice"]["score"] == 80 and results["eve-reads"]["score"] == 0,
                  f"fallback: alice {results['alice']['score']}, eve-reads "
                  f"{results['eve-reads']['score']}")

        # The verdict out of the student's process: tests/lab's runner and checker.
        verdicts(maker, cls, work, kit, root)
    finally:
        print(f"check_hostile: {time.monotonic() - started:.0f} s")
        shutil.rmtree(outside, ignore_errors=True)
        if not problems:
            shutil.rmtree(work, ignore_errors=True)
        else:
            print(f"(the class and its grades are left in {work} to look at)")
    if problems:
        print(f"\n{len(problems)} problem(s) with scripts/grade under attack:")
        for p in problems:
            print("  - " + p.splitlines()[0])
        return 1
    print("scripts/grade holds against the hostile class; the honest students get their grade")
    return 0


FORGE_PRELUDE = r"""#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <unistd.h>
// At exit, after GoogleTest wrote its XML: every <failure> taken out, and a clean exit.
static void clothlab_forge() {
  std::ifstream cmdline("/proc/self/cmdline");
  std::string word;
  while (std::getline(cmdline, word, '\0')) {
    if (word.rfind("--gtest_output=xml:", 0) == 0) {
      const std::string path = word.substr(19);
      std::stringstream xml;
      {
        std::ifstream in(path);
        xml << in.rdbuf();
      }
      std::ofstream(path) << std::regex_replace(xml.str(), std::regex("<failure[\\s\\S]*?</failure>"), "");
    }
  }
  _exit(0);
}"""
FORGE_BODY = """    static const int registered = std::atexit(clothlab_forge);
    (void)registered;
    return false;"""
PATCH_PRELUDE = r"""#include <cstdint>
#include <sys/mman.h>
#include <unistd.h>
// GoogleTest's record of a failed check, found by its symbol in the program.
// (Weak: the library links before GoogleTest; the program that holds both resolves it.)
extern "C" void clothlab_add_result() __asm__(
    "_ZN7testing10TestResult17AddTestPartResultERKNS_14TestPartResultE") __attribute__((weak));"""
PATCH_BODY = """    if (&clothlab_add_result == nullptr)
      return false;
    auto* code = reinterpret_cast<unsigned char*>(&clothlab_add_result);
    const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
    auto* start = reinterpret_cast<void*>(reinterpret_cast<std::uintptr_t>(code) & ~(page - 1));
    if (mprotect(start, 2 * page, PROT_READ | PROT_WRITE | PROT_EXEC) == 0)
      code[0] = 0xc3;  // ret: no failure is ever recorded
    return false;"""


def verdicts(maker, cls, work, kit, root):
    """A forged XML and an in-memory patch of GoogleTest: 0, the verdict being out of the
    student's process."""
    forged = maker.copy("eve-forged-xml", cls, maker.stubs)
    attack_file(maker, forged, FORGE_PRELUDE, FORGE_BODY)
    patched = maker.copy("eve-patch", cls, maker.stubs)
    attack_file(maker, patched, PATCH_PRELUDE, PATCH_BODY)
    run([root / "scripts/grade", "--out", work / "out-verdicts", "--work", kit, "--", forged,
         patched], env=dict(os.environ, CLOTHLAB_GRADE_UID=str(UID)))
    for name in ("eve-forged-xml", "eve-patch"):
        path = work / "out-verdicts" / "students" / name / "results.json"
        got = json.loads(path.read_text())["score"] if path.exists() else None
        check(got == 0, f"{name}: a forged verdict earned {got}")

if __name__ == "__main__":
    sys.exit(main())
