"""Tearing on the GPU paths through the command line: a cloth pulled hard with --tear-strain
tears, its OBJ has fewer faces than the untorn cloth's 2 (N-1)^2, and as many as the cpu path's
(the torn springs are read back from the GPU with the state).
Usage: torn_obj_faces.py CLOTHLAB"""
import os, subprocess, sys, tempfile

B = sys.argv[1]
N = 20
ARGS = ['--headless', '--N', str(N), '--tear-strain', '0.3', '--drag', '19,19:2,2,2', '--steps', '600']
workdir = tempfile.mkdtemp(prefix='clothlab-torn-')
faces = {}
# BEGIN TEACHER
BACKENDS = ('cpu', 'gpu', 'gpu-compute')
# END TEACHER
# COPY| BACKENDS = ('cpu', 'gpu')  # the copy has no compute path
for backend in BACKENDS:
    path = os.path.join(workdir, backend + '.obj')
    run = subprocess.run([B] + ARGS + ['--backend', backend, '--obj', path],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if backend == 'gpu-compute' and run.returncode == 1 and 'needs OpenGL 4.3' in run.stderr:
        print("gpu-compute left out: " + run.stderr.strip())  # (macOS: OpenGL 4.1)
        continue
    run.check_returncode()
    with open(path) as f:
        faces[backend] = sum(1 for line in f if line.startswith('f '))
    os.remove(path)
os.rmdir(workdir)
whole = 2 * (N - 1) ** 2
print(f"faces of the OBJ after tearing: {faces} (untorn: {whole})")
ok = faces['cpu'] < whole and all(faces[b] == faces['cpu'] for b in faces)
sys.exit(0 if ok else 1)
