#!/usr/bin/env python3
"""Writes examples/simulate/d_andrews.adm: Andrews' squeezing mechanism (Test Set for IVP
Solvers, Bari, release 2.3; the definition of Ex_andrews.f, see ../shared/research/constraints.md
section 3.1) as 7 parts on 10 revolute joints at its consistent initial angles."""
from math import cos, sin, sqrt
m=[.04325,.00365,.02373,.00706,.07050,.00706,.05498]
i=[2.194e-6,4.410e-7,5.255e-6,5.667e-7,1.169e-5,5.667e-7,1.912e-5]
xa,ya,xb,yb,xc,yc,c0=-.06934,-.00227,-0.03635,.03273,.014,.072,4530
d,da,e,ea,rr,ra,l0=28e-3,115e-4,2e-2,1421e-5,7e-3,92e-5,7785e-5
ss,sa,sb,sc,sd,ta,tb,u,ua,ub=35e-3,1874e-5,1043e-5,18e-3,2e-2,2308e-5,916e-5,4e-2,1228e-5,449e-5
zf,zt,fa,mom=2e-2,4e-2,1421e-5,33e-3
b,th,g,ph,de,om,ep=(-0.0617138900142764496358948458001,0,0.455279819163070380255912382449,0.222668390165885884674473185609,0.487364979543842550225598953530,-0.222668390165885884674473185609,1.23054744454982119249735015568)
O=(0.0,0.0); A=(xa,ya); B=(xb,yb); C=(xc,yc)
F=(rr*cos(b), rr*sin(b))
E=(F[0]-d*cos(b+th), F[1]-d*sin(b+th))
G=(xa+zt*cos(de), ya+zt*sin(de))
H=(xa+u*sin(ep), ya-u*cos(ep))
D=(sd*cos(g)+sc*sin(g)+xb, sd*sin(g)-sc*cos(g)+yb)
# checks: E from the other chains
E3=(xb+ss*sin(g), yb-ss*cos(g)); E4=(G[0]+e*sin(ph+de), G[1]-e*cos(ph+de)); E6=(H[0]+zf*cos(om+ep), H[1]+zf*sin(om+ep))
for X in (E3,E4,E6): assert abs(X[0]-E[0])<1e-14 and abs(X[1]-E[1])<1e-14, (X,E)
cm=[None]*7
cm[0]=(ra*cos(b), ra*sin(b))
cm[1]=(F[0]-da*cos(b+th), F[1]-da*sin(b+th))
cm[2]=(xb+sa*sin(g)+sb*cos(g), yb-sa*cos(g)+sb*sin(g))
cm[3]=(G[0]+(e-ea)*sin(ph+de), G[1]-(e-ea)*cos(ph+de))
cm[4]=(xa+ta*cos(de)-tb*sin(de), ya+ta*sin(de)+tb*cos(de))
cm[5]=(H[0]+(zf-fa)*cos(om+ep), H[1]+(zf-fa)*sin(om+ep))
cm[6]=(xa+ua*sin(ep)+ub*cos(ep), ya-ua*cos(ep)+ub*sin(ep))
def f(x): return repr(float(x))
out=["Andrews' squeezing mechanism (Test Set for IVP Solvers, Bari, release 2.3): 7 parts, 10 revolute joints",
"!",
"! Written from the test set's definition (Ex_andrews.f): each part's centre of",
"! mass and joint points at the consistent initial angles, parts at the",
"! ground's origin unrotated (their markers in ground coordinates), every",
"! joint's z axis along ground z; the spring C-D and the driving torque MOM on",
"! the crank; no gravity. Written by scripts/andrews_dataset.py; tests/joints.rs",
"! checks the seven angles at t = 0.03 against the test set's reference.",
"!",
"PART/1, GROUND",
"MARKER/1, PART = 1",
f"MARKER/2, PART = 1, QP = {f(xa)}, {f(ya)}, 0",
f"MARKER/3, PART = 1, QP = {f(xb)}, {f(yb)}, 0",
f"MARKER/4, PART = 1, QP = {f(xc)}, {f(yc)}, 0"]
pts={}
for k in range(7):
    p=k+2
    out.append(f"PART/{p}, MASS = {f(m[k])}, CM = {p}00, IP = {f(i[k])}, {f(i[k])}, {f(i[k])}")
    out.append(f"MARKER/{p}00, PART = {p}, QP = {f(cm[k][0])}, {f(cm[k][1])}, 0")
def mk(part, idx, P):
    out.append(f"MARKER/{part}{idx:02d}, PART = {part}, QP = {f(P[0])}, {f(P[1])}, 0")
    return int(f"{part}{idx:02d}")
joints=[]
joints.append((mk(2,1,O),1))          # crank at O
joints.append((mk(3,1,F),mk(2,2,F)))  # body 2 on the crank at F
e3=mk(4,1,E); e2=mk(3,2,E); joints.append((e3,e2))
e4=mk(5,1,E); e2b=mk(3,3,E); joints.append((e4,e2b))
e6=mk(7,1,E); e2c=mk(3,4,E); joints.append((e6,e2c))
joints.append((mk(4,2,B),3))
joints.append((mk(6,1,A),2))
joints.append((mk(5,2,G),mk(6,2,G)))
joints.append((mk(8,1,A),2))
joints.append((mk(7,2,H),mk(8,2,H)))
dm=mk(4,3,D)
for n,(I,J) in enumerate(joints):
    out.append(f"JOINT/{n+1}, REVOLUTE, I = {I}, J = {J}")
out.append(f"SFORCE/1, TRANSLATIONAL, I = {dm}, J = 4, FUNCTION = -{c0} * (DM({dm}, 4) - {f(l0)})")
out.append(f"SFORCE/2, ROTATIONAL, I = 201, J = 1, FUNCTION = {mom}")
out.append("END")
if __name__ == "__main__":
    print("\n".join(out))
