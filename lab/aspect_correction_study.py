#!/usr/bin/env python3
"""Study (not used by kcreep): correct the area-normalised ellipse levels for the
staircase's aspect ratio as well, C(a/b) / C(r_s) with r_s = sqrt(Ixx/Iyy) of the
cells inside and the slope of C from Kalker's table (linear in ln a/b, nu), and
compare the default estimator (levels 16-48) against a reference from levels
56-128, with and without the correction. Needs numpy (/usr/bin/python3).

    /usr/bin/python3 lab/aspect_correction_study.py
"""
import sys as _sys

if __name__ == "__main__" and any(a in ("-h", "--help") for a in _sys.argv[1:]):
    print("usage: lab/aspect_correction_study.py\n" + __doc__)
    _sys.exit(0)
import math
import os
import statistics
import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
import sys  # noqa: E402
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "maintenance"))
from kcreep_levels import student_t95  # noqa: E402  (the library's table)
data = {}
def stair(r, mx, my):
    a, b = math.sqrt(r), 1/math.sqrt(r)
    dx, dy = 2*a/mx, 2*b/my
    x = -a + (np.arange(mx)+0.5)*dx; y = -b + (np.arange(my)+0.5)*dy
    X, Y = np.meshgrid(x, y, indexing='ij')
    ins = (X/a)**2 + (Y/b)**2 <= 1
    A = ins.sum()*dx*dy
    Ixx = ((X**2)[ins].sum() + ins.sum()*dx**2/12)*dx*dy
    Iyy = ((Y**2)[ins].sum() + ins.sum()*dy**2/12)*dx*dy
    return A, Ixx, Iyy
# log-slope of C wrt ln(a/b) from Kalker's table at nu (finite difference of ln C)
tab={}
for line in open(os.path.join(ROOT, 'data', 'kalker-table-E3.dat')):
    if line.startswith('#') or not line.strip(): continue
    p=line.split(); g=float(p[1]); r=g if p[0]=='a/b' else 1/g
    tab[r]=[float(v) for v in p[2:]]
rs=sorted(tab)
def C(r,nu,k):  # k 0,1,2 -> C11,C22,C23; linear interp in ln r and nu
    lr=math.log(r); L=[math.log(x) for x in rs]
    i=max(0,min(len(rs)-2, np.searchsorted(L,lr)-1))
    nus=[0,0.25,0.5]
    def at(j):
        v=tab[rs[j]][3*k:3*k+3]; return np.interp(nu,nus,v)
    w=(lr-L[i])/(L[i+1]-L[i])
    return math.exp((1-w)*math.log(at(i))+w*math.log(at(i+1)))
for line in open(os.path.join(ROOT, 'lab', 'data', 'error_calibration_levels.dat')):
    if line.startswith('#'): continue
    p=line.split(); r,nu,N=float(p[0]),float(p[1]),int(p[2])
    data.setdefault((r,nu),{})[N]=dict(mx=int(p[3]),my=int(p[4]),c11=float(p[6]),c22=float(p[7]),c23=float(p[8]))
def corrected(r,nu,x,k,j):
    A,Ixx,Iyy=stair(r,x['mx'],x['my']); rs=math.sqrt(Ixx/Iyy)
    return x[k]*C(r,nu,j)/C(rs,nu,j)
def fit(Ns,fs):
    h=np.array([1/N for N in Ns]); f=np.array(fs); m=len(h)
    A=np.column_stack([np.ones(m),h]); c=np.linalg.lstsq(A,f,rcond=None)[0]
    s2=((f-A@c)**2).sum()/(m-2); return c[0], math.sqrt(s2*np.linalg.inv(A.T@A)[0,0]), m-2
S=[16,20,24,28,32,36,40,48]; R=[56,64,96,128]
for corr in (False,True):
    print('aspect correction' if corr else 'area only')
    for j,k in enumerate(('c11','c22','c23')):
        b=bu=n=0; errs=[];ests=[]
        for (r,nu),lv in sorted(data.items()):
            rn=[N for N in R if N in lv]
            if len(rn)<3 or not all(N in lv for N in S): continue
            val=(lambda N: corrected(r,nu,lv[N],k,j)) if corr else (lambda N: lv[N][k])
            ref,se,d=fit(rn,[val(N) for N in rn]); u=student_t95(d)*se/abs(ref)
            f0,s,d=fit(S,[val(N) for N in S]); est=student_t95(d)*s/abs(f0); err=abs(f0-ref)/abs(ref)
            n+=1; b+=est>=err; bu+=est+u>=err; errs.append(err); ests.append(est)
        print(f'  {k}: bounded {b}/{n} (+u {bu}) median err {100*statistics.median(errs):.3f}% worst {100*max(errs):.3f}% median est {100*statistics.median(ests):.3f}% max est {100*max(ests):.3f}%')
