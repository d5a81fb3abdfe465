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
    subprocess.run([B] + ARGS + ['--backend', backend, '--obj', path], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(path) as f:
        faces[backend] = sum(1 for line in f if line.startswith('f '))
    os.remove(path)
os.rmdir(workdir)
whole = 2 * (N - 1) ** 2
print(f"faces of the OBJ after tearing: {faces} (untorn: {whole})")
ok = faces['cpu'] < whole and all(faces[backend] == faces['cpu'] for backend in BACKENDS)
sys.exit(0 if ok else 1)
