"""clothlab's headless CSV against the independent reference_model.py, for the three stages, both
integrators, pins, wind, ground and non-default parameters.
Usage: test_against_reference.py CLOTHLAB [spring|solution]
  spring: the single spring only (no code of the lab's questions; passes in the student copy);
  solution: the chain and the cloth, which need the solution of questions 5 to 9 and 13.

The two implementations add the same terms in a different order, so they may differ in the last
bits: the test allows a relative difference of 1e-12 (measured: at most 7e-14 after 400 steps),
far below any physical effect and far above rounding."""
import csv, os, subprocess, sys, tempfile
from reference_model import run
B = sys.argv[1]
TOLERANCE = 1e-12
failures = 0
cases=[
 (['--stage','spring','--steps','300'], dict(stage='spring',steps=300)),
 (['--stage','spring','--steps','300','--integrator','explicit','--K','35','--mu','0.1','--mass','1.5','--gravity','3'], dict(stage='spring',steps=300,integ='explicit',K=35,mu=0.1,m=1.5,g0=3)),
 (['--stage','coupled','--chain','4','--steps','300','--K','50'], dict(stage='coupled',steps=300,chain=4,K=50)),
 (['--stage','cloth','--N','7','--steps','400','--wind-strength','15','--wind-dir','1,2,0.5','--ground-z','-0.4','--ground-friction','3'], dict(stage='cloth',steps=400,N=7,Kw=15,wdir=(1,2,0.5),ground=-0.4,mug=3)),
 (['--stage','cloth','--N','6','--steps','300','--integrator','explicit','--dt','0.0005','--pins','none','--ground-z','-0.05','--K-struct','800','--K-shear','300','--K-bend','50','--size','2'], dict(stage='cloth',steps=300,N=6,integ='explicit',dt=0.0005,pins=False,ground=-0.05,Ks=800,Ksh=300,Kb=50,S=2.0)),
]
if len(sys.argv) > 2:
    wanted = sys.argv[2]
    cases = [c for c in cases if (c[1]['stage'] == 'spring') == (wanted == 'spring')]
workdir = tempfile.mkdtemp(prefix='clothlab-model-')
path = os.path.join(workdir, 'c.csv')
for args,kw in cases:
    subprocess.run([B,'--headless','--csv',path]+args,check=True)
    with open(path) as f:
        rows=list(csv.reader(f))[1:]
    ref=run(**kw)
    assert len(rows)==len(ref),(len(rows),len(ref))
    worst=0.0; exact=0; total=0
    for r,e in zip(rows,ref):
        assert int(r[0])==e[0] and int(r[2])==e[2]
        for a,b in zip(r[3:],e[3:]):
            a=float(a); total+=1; exact+= (a==b)
            worst=max(worst,abs(a-b)/max(1.0,abs(b)))
    ok = worst <= TOLERANCE
    failures += not ok
    print('ok  ' if ok else 'FAIL', ' '.join(args), f"max rel diff {worst:.3g}, bitwise equal {exact}/{total}")
os.remove(path)
os.rmdir(workdir)
print(f"{len(cases) - failures} passed, {failures} failed")
sys.exit(1 if failures else 0)
