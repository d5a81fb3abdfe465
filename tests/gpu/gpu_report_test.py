"""scripts/gpu-report on this build's programs, small (--quick), so that the report a teacher runs
on a GPU machine keeps working where there is none (CI, llvmpipe).

    gpu_report_test.py GPU_REPORT BUILD_DIR

With --allow-software it prints its table (the renderer's name, the GPU tests, both paths against
the CPU, the benchmark's rows) and exits 0. Without it, on a software renderer, it refuses with
exit 3 and says why and what to do; on a GPU it reports (exit 0)."""
import subprocess
import sys

report, build = sys.argv[1], sys.argv[2]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def run(*options):
    return subprocess.run([report, "--programs", build, "--quick", *options],
                          capture_output=True, text=True, timeout=600)


tried = run("--allow-software")
print(tried.stdout)
print(tried.stderr[-2000:], file=sys.stderr)
check(tried.returncode == 0, f"--allow-software: exit {tried.returncode}, not 0")
lines = tried.stdout.splitlines()
title = [line for line in lines if line.startswith("clothlab GPU report: ")]
check(len(title) == 1 and "OpenGL" in title[0], "the table names the OpenGL renderer")
check(any(line.startswith("GPU tests: ") and " passed" in line for line in lines),
      "the table says how many GPU tests passed")
agreement = [line for line in lines if "agreement with the CPU" in line]
check(len(agreement) == 1 and agreement[0].count("of tolerance") >= 1,
      "the table has the agreement of the paths with the CPU")
headless = [line for line in lines if line.startswith("headless N=16, 300 steps")]
check(len(headless) == 1 and "(bound" in headless[0], "the table compares headless runs")
speed = [line for line in lines if line.startswith("us per step, N=64")]
check(len(speed) == 2, "the table has the benchmark's two rows at N = 64")
for line in speed:
    first = line[50:].split()[0]  # the fragment path's column
    check(first.replace(".", "", 1).isdigit(), f"a number of microseconds in: {line}")
software = any("SOFTWARE RENDERER" in line for line in lines)

refused = run()
if software:
    check(refused.returncode == 3, f"a software renderer without --allow-software: exit "
          f"{refused.returncode}, not 3")
    check("software" in refused.stderr and "--allow-software" in refused.stderr,
          f"the refusal says it is a software renderer and what to do: {refused.stderr}")
    check("clothlab GPU report" not in refused.stdout, "no table after a refusal")
else:
    check(refused.returncode == 0, f"on a GPU: exit {refused.returncode}")

print(f"{len(failures)} failed" if failures else "ok")
sys.exit(1 if failures else 0)
