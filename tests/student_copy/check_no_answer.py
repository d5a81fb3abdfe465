#!/usr/bin/env python3
"""The student copy holds no answer outside the student's places (issue 17), at either hint
level, and the check that says so can fail. Usage: check_no_answer.py PROJECT_ROOT

1. scripts/make-student-version writes the copy at each hint level (handout, guided): it refuses
   a copy whose code (src/, shaders/, scripts/, bench/) holds one of a question's answers
   (ANSWERS, normalised code, C++ and GLSL) outside the student's places, or whose handout-level
   TODOs write an answer; both copies are written.
2. Planted leaks are refused: each question's answer, written into a file of a copy of the
   project outside the student's places (C++ and GLSL), makes the generator fail naming the file
   and the question.
3. Each question's handout-level TODO holds none of its answers, while the guided TODOs of the
   questions whose steps they spell out do (so that the check is seen to find them).
4. The copy offers nothing to call instead of answering: none of the helpers that answered a
   question in one call is declared in its headers, and the parallel CPU path is a stub that
   names the teacher's copy.
5. Only what git tracks is shipped: in a teacher's checkout that holds a compiler's cache
   (.ccache/, as the Classroom workflow leaves it, and a ccache folder) with the solution's
   objects, and a stray object file beside the sources, the student copy and the Gradescope
   bundle (scripts/grade --gradescope-bundle) hold no object file, no cache folder and no line
   of any solution region; the bundle holds the grader's tracked files and the copy, nothing
   else.
Exit 0 when all of this holds; otherwise every failed check is listed.
"""
import importlib.machinery
import importlib.util
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

problems = []


def check(condition, message):
    if not condition:
        problems.append(message)
        print("FAILED: " + message, flush=True)
    return condition


def load_generator(root):
    loader = importlib.machinery.SourceFileLoader("make_student_version",
                                                  str(root / "scripts/make-student-version"))
    spec = importlib.util.spec_from_loader(loader.name, loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


# One planted answer per question: (question, file of the copy, the line added to it).
PLANTED = [
    ("Q5", "src/core/single_spring.cpp", "void leak(std::size_t i) { add(i - 1, -F); }"),
    ("Q6", "src/core/energy.cpp",
     "void leak(double dt, double mu) { speed[k] = (1 - dt * mu) * speed[k]; }"),
    ("Q7", "src/window/scene.cpp", "particles_.is_fixed[index(n - 1, 0, n)] = 1;"),
    ("Q8", "src/core/contacts.cpp", "const double shear_rest = std::sqrt(2.0) * h;"),
    ("Q8", "shaders/draw_flat.vert", "float L0 = length(x0(ku, kv) - x0(ku2, kv2));"),
    ("Q9", "src/core/contacts.cpp", "v.z = std::max(v.z, 0.0);"),
    ("Q9", "shaders/gpu_normal.frag", "v_new.z = max(v_new.z, 0.0);"),
    ("Q12", "shaders/gpu_tear.frag", "force += spring_force(p, p_j, 1.0, 1.0);"),
    ("Q13", "src/core/export.cpp", "f += K_w * glm::dot(n_here, u_w) * n_here;"),
    ("Q13", "shaders/gpu_normal.frag", "force += K * dot(n, wind_direction) * n;"),
]
# What answered a question in one call before issue 17: none may be declared in the copy.
REMOVED_CALLS = [r"\bintegrate\s*\(", r"\bcompute_spring_forces\s*\(",
                 r"\baccumulate_spring_forces\s*\(", r"\brest_length\s*\(\s*(std::size_t|"
                 r"spring_family)", r"\bjoined\s*\(", r"\bL0\s*\("]


def tracked_tree(root, generator, dest):
    """A checkout of the project's tracked files (as they are in root's work tree) at dest: a
    git repository whose index holds them."""
    for name in generator.project_files():
        target = dest / name
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(root / name, target)
    subprocess.run(["git", "init", "-q", str(dest)], check=True)
    subprocess.run(["git", "-C", str(dest), "add", "-A"], check=True)
    return dest


# Where a compiler's cache and stray objects sit in a teacher's checkout: the Classroom
# workflow's .ccache/, a ccache folder, an object beside the sources, a build folder.
UNTRACKED = (".ccache/0/a/spring_mesh.cpp.o", ".ccache/ccache.conf", "ccache/b/coupled.o",
             "src/core/spring_mesh.cpp.o",
             "build-old/src/core/coupled_springs.cpp.o")


def untracked_stay_home(root, generator, work):
    tree = tracked_tree(root, generator, work / "teacher")
    solutions = {}
    for name in generator.project_files():
        if Path(name).suffix in (".cpp", ".frag", ".glsl", ".comp") and \
                "BEGIN SOLUTION" in (root / name).read_text(errors="replace"):
            regions = []
            generator.transform(name, (root / name).read_text(), set(), regions)
            for question, _, _, _, solution, stub in regions:
                stubs = {line.strip() for line in stub}
                solutions.update({line.strip(): f"{question} ({name})" for line in solution
                                  if _regions_significant(generator, line) and
                                  line.strip() not in stubs})
    leak = "\n".join(solutions).encode()
    for name in UNTRACKED:
        (tree / name).parent.mkdir(parents=True, exist_ok=True)
        (tree / name).write_bytes(b"\x7fELF objects of the solution\n" + leak)
    copy = work / "copy-untracked"
    made = generate(tree, copy)
    bundle = work / "autograder.zip"
    bundled = subprocess.run([sys.executable, str(tree / "scripts/grade"), "--gradescope-bundle",
                              str(bundle)], capture_output=True, text=True)
    if not check(made.returncode == 0 and bundled.returncode == 0,
                 f"the copy or the bundle of a checkout with a cache was not made:\n"
                 f"{made.stderr[-1500:]}{bundled.stderr[-1500:]}"):
        return
    shipped = {f"copy/{p.relative_to(copy).as_posix()}": p.read_bytes()
               for p in copy.rglob("*") if p.is_file()}
    with zipfile.ZipFile(bundle) as archive:
        shipped.update({f"bundle/{n}": archive.read(n) for n in archive.namelist()
                        if not n.endswith("/")})
    for name, data in sorted(shipped.items()):
        parts = name.split("/")
        check(not name.endswith((".o", ".obj", ".a")) and
              not any("ccache" in part.lower() for part in parts),
              f"{name}: an object file or a compiler's cache reached the student copy or the "
              "bundle")
        text = data.decode("utf-8", "replace")
        found = [line for line in text.splitlines() if line.strip() in solutions]
        # A region's first line (the grader's package only describes one, in its comments).
        marker = "/clothlab_lab/" not in name and any(
            generator._regions.BEGIN.match(line) for line in text.splitlines())
        check(b"objects of the solution" not in data and not found and not marker,
              f"{name}: holds a solution region or line ({found[:1]} of "
              f"{solutions.get(found[0].strip()) if found else 'a region'})")
    # The bundle: setup.sh, run_autograder, the grader's tracked files, the kit generated.
    package = [n for n in generator.project_files() if n.startswith("scripts/clothlab_lab/")]
    expected = {"setup.sh", "run_autograder", "clothlab-grade/grade",
                "clothlab-grade/manifest.json"}
    expected |= {"clothlab-grade/clothlab_lab/" + n[len("scripts/clothlab_lab/"):]
                 for n in package}
    # (the kit's copy leaves out what no build reads: .git*, build*, out*, Testing)
    expected |= {f"clothlab-grade/base/copy/{n[len('copy/'):]}" for n in shipped
                 if n.startswith("copy/") and not n[len("copy/"):].startswith(
                     (".git", "build", "out", "Testing"))}
    expected |= {f"clothlab-grade/stubs/{n}" for n in generator.LAB.student_files}
    got = {n[len("bundle/"):] for n in shipped if n.startswith("bundle/")}
    check(got == expected, f"the bundle holds {sorted(got - expected)[:8]} beyond the grader's "
                           f"tracked files and the copy, and lacks {sorted(expected - got)[:8]}")


def _regions_significant(generator, line):
    return generator._regions.significant(line)


def generate(root, dest, *options):
    return subprocess.run([sys.executable, str(root / "scripts/make-student-version"), str(dest),
                           *options], capture_output=True, text=True)


def main():
    root = Path(sys.argv[1]).resolve()
    generator = load_generator(root)
    work = Path(tempfile.mkdtemp(prefix="clothlab-no-answer-"))
    try:
        # 1. Both hint levels: written, and the copy's headers and stubs are what they say.
        for level in generator.HINT_LEVELS:
            dest = work / f"copy-{level}"
            made = generate(root, dest, "--hints", level)
            check(made.returncode == 0, f"--hints {level}: make-student-version refused the "
                                        f"copy:\n{made.stderr}")
            if made.returncode != 0:
                continue
            marker = (dest / ".student-copy").read_text()
            check(f"hints: {level}" in marker, f"--hints {level}: the marker says '{marker}'")
            # 4. Nothing to call instead of answering.
            for header in sorted((dest / "src").rglob("*.hpp")):
                text = header.read_text()
                code = re.sub(r"//[^\n]*", "", text)
                for pattern in REMOVED_CALLS:
                    check(not re.search(pattern, code),
                          f"{header.relative_to(dest)} declares {pattern!r}: a student could "
                          "call it instead of answering")
            # The copy has no cloth_parallel.cpp: its build compiles the stand-in,
            # cloth_parallel_absent.cpp, which says the path is in the teacher's copy.
            absent = (dest / "src/core/cloth_parallel_absent.cpp").read_text()
            cmake = (dest / "src/core/CMakeLists.txt").read_text()
            check(not (dest / "src/core/cloth_parallel.cpp").exists()
                  and "cloth_parallel.cpp" not in re.sub(r"#[^\n]*", "", cmake)
                  and "in the teacher's copy" in absent
                  and "return false;" in absent and "#pragma omp" not in absent,
                  "the copy builds a parallel path, not the stand-in that names the teacher's "
                  "copy")
            check(not (dest / "tests/model").exists() and
                  not (dest / "shaders/gpu_compute_step.comp").exists(),
                  "the copy has the Python reference model or the compute shader")

        # 2. Planted leaks are refused, naming the file and the question.
        tree = tracked_tree(root, generator, work / "planted")
        for question, name, line in PLANTED:
            path = tree / name
            original = path.read_text()
            path.write_text(original + "\n" + line + "\n")
            refused = generate(tree, work / "copy-planted")
            path.write_text(original)
            check(refused.returncode == 1 and name in refused.stderr and
                  re.search(rf"\b{question}\b", refused.stderr),
                  f"a planted answer of {question} in {name} ('{line}') was not refused:\n"
                  f"{refused.stderr[-1500:]}")
            shutil.rmtree(work / "copy-planted", ignore_errors=True)

        # 3. The TODOs, question by question.
        for level in generator.HINT_LEVELS:
            regions = []
            for name in generator.project_files():
                if Path(name).suffix in (".cpp", ".frag", ".glsl", ".comp") and \
                        not generator.is_teacher_file(name):
                    text = (root / name).read_text()
                    if "BEGIN SOLUTION" in text:
                        generator.transform(name, text, set(), regions, level)
            for question in generator.QUESTIONS:
                todo = generator.todo_texts(regions, question)
                check(f"TODO {question}" in todo, f"{level}: no TODO {question}")
                found = generator.answers_in(todo, {question}, keep_comments=True)
                if level == "handout":
                    check(not found, f"the handout-level TODO of {question} writes its answer: "
                                     f"{found}")
                elif question != "Q13":  # the handout itself gives question 13's formula
                    check(found, f"the guided TODO of {question} spells out its steps, yet the "
                                 "answer check finds nothing in it: the check cannot fail")
        # 5. Untracked files of the teacher's checkout ship nowhere.
        untracked_stay_home(root, generator, work)
    finally:
        if not problems:
            shutil.rmtree(work, ignore_errors=True)
        else:
            print(f"(left in {work} to look at)")
    if problems:
        print(f"\n{len(problems)} problem(s):")
        for p in problems:
            print("  - " + p.splitlines()[0])
        return 1
    print(f"no answer outside the student's places at either hint level; {len(PLANTED)} planted "
          "answers refused; the handout-level TODOs write no answer")
    return 0


if __name__ == "__main__":
    sys.exit(main())
