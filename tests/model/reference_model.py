"""An independent implementation of docs/model.md: pure Python, doubles, written from the
contract's text alone and sharing no code with clothlab (test_against_reference.py compares the
two, step by step, particle by particle)."""
import math
def sub(a,b): return [a[0]-b[0],a[1]-b[1],a[2]-b[2]]
def cross(a,b): return [a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0]]
def norm(a): return math.sqrt(a[0]*a[0]+a[1]*a[1]+a[2]*a[2])
def run(stage, steps, dt=None, K=20.0, Ks=5000., Ksh=2000., Kb=500., mu=None, m=1.0, g0=9.8, integ='semi-implicit',
        chain=2, N=20, S=1.0, pins=True, Kw=0.0, wdir=(0,1,0), ground=-1.0, mug=2.0,
        drag=None, Kd=1000.0, sphere=None, mus=5.0, self_d=0.0, tear=0.0,
        substeps=10, iterations=1, beta=0.0):
    # drag: (ku, kv, (x, y, z)); sphere: (cx, cy, cz, r); self_d: thickness; tear: strain
    # integ 'xpbd': substeps, iterations, beta (model.md, XPBD)
    if dt is None: dt = 0.002 if stage=='cloth' else 0.01
    if mu is None: mu = 0.5 if stage=='cloth' else 0.2
    P=[];V=[];fixed=[];springs=[]
    if stage in ('spring','coupled'):
        n = 1 if stage=='spring' else chain
        p0=[0.1,0.0,1.0]
        for i in range(n+1):
            P.append([p0[0],p0[1],p0[2]+i*-0.5]); V.append([0.,0.,0.]); fixed.append(i==0)
        V[n]=[1.,-1.,0.]
        for i in range(1,n+1): springs.append((i-1,i,norm(sub(P[i],P[i-1])),K))
    else:
        h=S/(N-1)
        for kv in range(N):
            for ku in range(N):
                P.append([-S/2+ku*h,-S/2+kv*h,0.0]); V.append([0.,0.,0.]); fixed.append(False)
        if pins: fixed[0]=True; fixed[N-1]=True
        idx=lambda u,v:u+N*v
        for kv in range(N):
            for ku in range(N):
                for (du,dv,k) in ((1,0,Ks),(0,1,Ks),(1,1,Ksh),(2,0,Kb),(0,2,Kb)):
                    u2,v2=ku+du,kv+dv
                    if u2<N and v2<N: a,b=idx(ku,kv),idx(u2,v2); springs.append((a,b,norm(sub(P[a],P[b])),k))
                # the other diagonal (ku+1,kv)-(ku,kv+1)
                if ku+1<N and kv+1<N: a,b=idx(ku+1,kv),idx(ku,kv+1); springs.append((a,b,norm(sub(P[a],P[b])),Ksh))
    out=[]
    def record(s):
        for k in range(len(P)): out.append((s, s*dt, k, *P[k], *V[k]))
    record(0)
    wl=norm(wdir); uw=[wdir[0]/wl,wdir[1]/wl,wdir[2]/wl]
    def colour(a,b):
        # the cloth's 12 colours (model.md's table), from the spring's lower end (ku, kv)
        if stage!='cloth': return 0  # the chain: from the fixed end down, the list's order
        lo,hi=min(a,b),max(a,b); ku,kv=lo%N,lo//N; du,dv=hi%N-ku,hi//N-kv
        return {(1,0):0+ku%2,(0,1):2+kv%2,(1,1):4+ku%2,(-1,1):6+ku%2,(2,0):8+(ku//2)%2,(0,2):10+(kv//2)%2}[(du,dv)]
    def external():
        # F_ext: the wind (normals of the current positions) and the drag, without the springs
        E=[[0.,0.,0.] for _ in P]
        if stage=='cloth' and Kw!=0:
            for kv in range(N):
                for ku in range(N):
                    du=sub(P[min(ku+1,N-1)+N*kv],P[max(ku-1,0)+N*kv]); dv=sub(P[ku+N*min(kv+1,N-1)],P[ku+N*max(kv-1,0)])
                    c=cross(du,dv); l=norm(c); n=[c[0]/l,c[1]/l,c[2]/l]; dd=n[0]*uw[0]+n[1]*uw[1]+n[2]*uw[2]
                    for i in range(3): E[ku+N*kv][i]+=Kw*dd*n[i]
        if stage=='cloth' and drag is not None:
            dk=drag[0]+N*drag[1]
            if not fixed[dk]:
                for i in range(3): E[dk][i]+=Kd*(drag[2][i]-P[dk][i])
        return E
    def contact(k,tau):
        # the sphere, then the ground, on particle k over tau (dt; xpbd: its substep h)
        if stage=='cloth' and sphere is not None:
            c=sphere[:3]; r=sphere[3]; d=sub(P[k],c); L=norm(d)
            if L<r:
                n=[d[0]/L,d[1]/L,d[2]/L] if L>0 else [0.,0.,1.]
                vn=V[k][0]*n[0]+V[k][1]*n[1]+V[k][2]*n[2]
                if vn<0:
                    for i in range(3): V[k][i]-=vn*n[i]
                vn=V[k][0]*n[0]+V[k][1]*n[1]+V[k][2]*n[2]
                for i in range(3):
                    V[k][i]=vn*n[i]+(1-mus*tau)*(V[k][i]-vn*n[i])
                    P[k][i]=c[i]+r*n[i]
        if stage=='cloth' and ground is not None and P[k][2]<ground:
            P[k][2]=ground; V[k][2]=max(V[k][2],0.0); V[k][0]*=(1-mug*tau); V[k][1]*=(1-mug*tau)
    def xpbd_step():
        h=dt/substeps; E=external()
        order=sorted(range(len(springs)),key=lambda j:colour(springs[j][0],springs[j][1]))
        for _ in range(substeps):
            X=[p[:] for p in P]
            for k in range(len(P)):
                if fixed[k]: continue
                a=[E[k][0]/m, E[k][1]/m, E[k][2]/m-g0]
                for i in range(3): V[k][i]=(1-mu*h)*V[k][i]+h*a[i]; P[k][i]+=h*V[k][i]
            lam=[0.0]*len(springs)
            for _ in range(iterations):
                for j in order:
                    a,b,L0,k=springs[j]
                    if k<=0: continue
                    wa=0. if fixed[a] else 1/m; wb=0. if fixed[b] else 1/m
                    d=sub(P[a],P[b]); L=norm(d)
                    if wa+wb==0 or L==0: continue
                    n=[d[0]/L,d[1]/L,d[2]/L]; C=L-L0
                    at=1/(k*h*h); gam=beta/(k*h)
                    closing=sum(n[i]*((P[a][i]-X[a][i])-(P[b][i]-X[b][i])) for i in range(3))
                    dl=(-C-at*lam[j]-gam*closing)/((1+gam)*(wa+wb)+at)
                    lam[j]+=dl
                    for i in range(3): P[a][i]+=wa*dl*n[i]; P[b][i]-=wb*dl*n[i]
            for k in range(len(P)):
                if not fixed[k]:
                    for i in range(3): V[k][i]=(P[k][i]-X[k][i])/h
            for k in range(len(P)):
                if not fixed[k]: contact(k,h)
    for s in range(1,steps+1):
        if integ=='xpbd':
            xpbd_step()
        F=[[0.,0.,0.] for _ in P]
        for (a,b,L0,k) in ([] if integ=='xpbd' else springs):
            d=sub(P[a],P[b]); L=norm(d); c=k*(L0-L)/L
            for i in range(3): F[a][i]+=c*d[i]; F[b][i]-=c*d[i]
        if stage=='cloth' and Kw!=0 and integ!='xpbd':
            for kv in range(N):
                for ku in range(N):
                    du=sub(P[min(ku+1,N-1)+N*kv],P[max(ku-1,0)+N*kv]); dv=sub(P[ku+N*min(kv+1,N-1)],P[ku+N*max(kv-1,0)])
                    c=cross(du,dv); l=norm(c); n=[c[0]/l,c[1]/l,c[2]/l]; dd=n[0]*uw[0]+n[1]*uw[1]+n[2]*uw[2]
                    for i in range(3): F[ku+N*kv][i]+=Kw*dd*n[i]
        if stage=='cloth' and drag is not None and integ!='xpbd':
            dk=drag[0]+N*drag[1]
            if not fixed[dk]:
                for i in range(3): F[dk][i]+=Kd*(drag[2][i]-P[dk][i])
        for k in range(len(P)):
            if fixed[k]: continue
            a=[F[k][0]/m, F[k][1]/m, F[k][2]/m-g0]
            if integ=='xpbd':
                pass  # moved by xpbd_step; the contacts below, once per step
            elif integ=='semi-implicit':
                for i in range(3): V[k][i]=(1-mu*dt)*V[k][i]+dt*a[i]; P[k][i]=P[k][i]+dt*V[k][i]
            else:
                for i in range(3): pn=P[k][i]+dt*V[k][i]; V[k][i]=(1-mu*dt)*V[k][i]+dt*a[i]; P[k][i]=pn
            if integ!='xpbd':  # xpbd: in its substeps
                contact(k,dt)
        if stage=='cloth' and self_d>0:
            dP=[[0.,0.,0.] for _ in P]; dV=[[0.,0.,0.] for _ in P]
            for i in range(len(P)):
                for j in range(i+1,len(P)):
                    if abs(i%N-j%N)<=2 and abs(i//N-j//N)<=2: continue
                    if fixed[i] and fixed[j]: continue
                    d=sub(P[i],P[j]); L=norm(d)
                    if not (0<L<self_d): continue
                    u=[d[0]/L,d[1]/L,d[2]/L]; c=(self_d-L)/2
                    w=sum((V[i][a]-V[j][a])*u[a] for a in range(3))
                    si=0. if fixed[i] else (2. if fixed[j] else 1.)
                    sj=0. if fixed[j] else (2. if fixed[i] else 1.)
                    for a in range(3):
                        dP[i][a]+=si*c*u[a]; dP[j][a]-=sj*c*u[a]
                        if w<0: dV[i][a]-=si*(w/2)*u[a]; dV[j][a]+=sj*(w/2)*u[a]
            for k in range(len(P)):
                for a in range(3): P[k][a]+=dP[k][a]; V[k][a]+=dV[k][a]
        if stage=='cloth' and tear>0:
            springs=[sp for sp in springs if norm(sub(P[sp[0]],P[sp[1]]))<=(1+tear)*sp[2]]
        record(s)
    return out
