# Independent check of ENSO: MINPACK (scipy least_squares method="lm"), started at
# the certified values, and the LRE of each parameter. Needs numpy and scipy.
# Run: python3 enso_minpack.py $BRDF_DATA/nist_strd/ENSO.dat
import numpy as np
from scipy.optimize import least_squares
import sys
L=open(sys.argv[1]).read().splitlines()[60:]
d=np.array([[float(v) for v in l.split()] for l in L if l.strip()])
y,x=d[:,0],d[:,1]
def f(b):
    t=2*np.pi*x
    return b[0]+b[1]*np.cos(t/12)+b[2]*np.sin(t/12)+b[4]*np.cos(t/b[3])+b[5]*np.sin(t/b[3])+b[7]*np.cos(t/b[6])+b[8]*np.sin(t/b[6])-y
c=[1.0510749193E+01,3.0762128085E+00,5.3280138227E-01,4.4311088700E+01,-1.6231428586E+00,5.2554493756E-01,2.6887614440E+01,2.1232288488E-01,1.4966870418E+00]
r=least_squares(f,c,xtol=1e-15,ftol=1e-15,gtol=1e-15,method='lm')
print(r.x, (r.fun**2).sum())
print(['%.2f'%(-np.log10(abs(a-b)/abs(b))) for a,b in zip(r.x,c)])
