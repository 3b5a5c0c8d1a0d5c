# Coarse render meshes of a roof (benchmarks/RESULTS.md, "Coarse references"): a regular grid
# over a 24 m × 20 m plan, each cell cut by one diagonal (alternating), of a dome
# z = 6 (1 − (x/12)²)(1 − (y/10)²) or an elliptic saddle z = 0.03 (x² − 1.5 y²) + 0.5 sin(0.3 x),
# with a config each (whole boundary fixed, spacing 1.5 m). Optionally the grid's triangles are
# split 1-to-4 at their midpoints k times: the same facets on finer triangles.
#   python3 coarse_reference.py dome 1.5 [k]     # writes dome_1.5[s k].obj and .yaml
#   pqlayout run dome_1.5.yaml --out o_dome_1.5 -q
import math
import sys

shape, cell = sys.argv[1], float(sys.argv[2])
splits = int(sys.argv[3]) if len(sys.argv) > 3 else 0
height = {'dome': lambda x, y: 6.0 * (1 - (x / 12) ** 2) * (1 - (y / 10) ** 2),
          'saddle': lambda x, y: 0.03 * (x * x - 1.5 * y * y) + 0.5 * math.sin(0.3 * x)}[shape]
W, H = 24.0, 20.0
nx, ny = max(2, round(W / cell)), max(2, round(H / cell))
V = [(-W / 2 + W * i / nx, -H / 2 + H * j / ny) for j in range(ny + 1) for i in range(nx + 1)]
V = [(x, y, height(x, y)) for x, y in V]
F = []
for j in range(ny):
    for i in range(nx):
        a = j * (nx + 1) + i; b = a + 1; c = a + nx + 1; d = c + 1
        F += [[a, b, d], [a, d, c]] if (i + j) % 2 else [[a, b, c], [b, d, c]]
for _ in range(splits):
    middle = {}
    def m(a, b):
        key = (min(a, b), max(a, b))
        if key not in middle:
            middle[key] = len(V)
            V.append(tuple((V[a][k] + V[b][k]) / 2 for k in range(3)))
        return middle[key]
    F = [g for a, b, c in F for g in ([a, m(a, b), m(c, a)], [m(a, b), b, m(b, c)], [m(c, a), m(b, c), c],
                                       [m(a, b), m(b, c), m(c, a)])]
name = '%s_%s' % (shape, sys.argv[2]) + ('s%d' % splits if splits else '')
with open(name + '.obj', 'w') as o:
    for v in V: o.write('v %.17g %.17g %.17g\n' % v)
    for f in F: o.write('f %d %d %d\n' % tuple(i + 1 for i in f))
with open(name + '.yaml', 'w') as o:
    o.write('surface:\n  file: %s.obj\nboundary:\n  default: fixed\nlayout:\n  spacing: 1.5\n' % name)
