#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Boundary-layer metric on the unit cube as Medit .mesh + .sol (issue 12/13 validity check):
# h_x = h_y = 0.1, h_z = 0.1/STRETCH + 0.3 z, on a Kuhn background graded along z.
# usage: make-boundary-layer.py STRETCH OUTPREFIX   (writes OUTPREFIX.mesh, OUTPREFIX.sol)
import sys
stretch = float(sys.argv[1]); out = sys.argv[2]
hx = 0.1; hmin = hx / stretch
hz = lambda z: hmin + 0.3 * z
zs = [0.0]
while zs[-1] < 1.0:
    zs.append(min(1.0, zs[-1] + 0.5 * hz(zs[-1])))
if 1.0 - zs[-2] < 0.25 * hz(zs[-2]): zs.pop(-2)
n = 21
xs = [i / (n - 1) for i in range(n)]
pts = []
idx = {}
for k, z in enumerate(zs):
    for j, y in enumerate(xs):
        for i, x in enumerate(xs):
            idx[(i, j, k)] = len(pts) + 1
            pts.append((x, y, z))
tets = []
for k in range(len(zs) - 1):
    for j in range(n - 1):
        for i in range(n - 1):
            c = [idx[(i + a, j + b, k + d)] for d in (0, 1) for b in (0, 1) for a in (0, 1)]
            # Kuhn split of the hex (corners 0..7 = bit pattern x + 2y + 4z)
            for p in ((1, 2, 4), (1, 4, 2), (2, 1, 4), (2, 4, 1), (4, 1, 2), (4, 2, 1)):
                v = [0]; s = 0
                for q in p:
                    s += q; v.append(s)
                t = [c[x] for x in v]
                tets.append(t)
def orient(t):
    a, b, c, d = [pts[x - 1] for x in t]
    u = [b[i] - a[i] for i in range(3)]; v = [c[i] - a[i] for i in range(3)]; w = [d[i] - a[i] for i in range(3)]
    det = u[0]*(v[1]*w[2]-v[2]*w[1]) - u[1]*(v[0]*w[2]-v[2]*w[0]) + u[2]*(v[0]*w[1]-v[1]*w[0])
    return t if det > 0 else [t[0], t[1], t[3], t[2]]
tets = [orient(t) for t in tets]
with open(out + '.mesh', 'w') as f:
    f.write('MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n' % len(pts))
    for p in pts: f.write('%.17g %.17g %.17g 0\n' % p)
    f.write('Tetrahedra\n%d\n' % len(tets))
    for t in tets: f.write('%d %d %d %d 0\n' % tuple(t))
    f.write('End\n')
with open(out + '.sol', 'w') as f:
    f.write('MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n%d\n1 3\n' % len(pts))
    for p in pts:
        f.write('%.17g 0 %.17g 0 0 %.17g\n' % (1 / hx**2, 1 / hx**2, 1 / hz(p[2])**2))
    f.write('End\n')
print(len(pts), 'points', len(tets), 'tets', len(zs), 'layers')
