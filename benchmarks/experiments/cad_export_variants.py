# CAD-export variants of a reference mesh (benchmarks/RESULTS.md, "CAD exports and
# georeferenced surfaces, probed"). Usage, in a folder:
#   pqlayout run examples/corpus/dome_circular.yaml --until surface --out s
#   python3 cad_export_variants.py s/surface.obj
# writes seam.obj, seam_eps.obj, flipped_half.obj, down.obj, two_shells.obj, stray.obj,
# isolated.obj, dropout.obj, utm.obj, utm_far.obj and a NAME.yaml for each (whole boundary
# fixed, spacing 1.5 m); then: pqlayout run NAME.yaml --out o_NAME -q
import sys

V, F = [], []
for line in open(sys.argv[1]):
    w = line.split()
    if w and w[0] == 'v': V.append([float(x) for x in w[1:4]])
    if w and w[0] == 'f': F.append([int(x.split('/')[0]) - 1 for x in w[1:]])

def write(name, V, F):
    with open(name + '.obj', 'w') as o:
        for v in V: o.write('v %.17g %.17g %.17g\n' % tuple(v))
        for f in F: o.write('f ' + ' '.join(str(i + 1) for i in f) + '\n')
    with open(name + '.yaml', 'w') as o:
        o.write('surface:\n  file: %s.obj\nboundary:\n  default: fixed\nlayout:\n  spacing: 1.5\n' % name)

cx = sum(v[0] for v in V) / len(V)
cy = sum(v[1] for v in V) / len(V)
right = lambda f: sum(V[i][0] for i in f) / 3 > cx

def seam(eps):  # faces right of x = cx get their own copies of the vertices both sides use
    left = set(i for f in F if not right(f) for i in f)
    shared = left & set(i for f in F if right(f) for i in f)
    V2, m = [v[:] for v in V], {}
    for i in sorted(shared):
        m[i] = len(V2)
        V2.append([V[i][0] + eps, V[i][1], V[i][2]])
    return V2, [[m.get(i, i) for i in f] if right(f) else f[:] for f in F]

n = len(V)
write('seam', *seam(0.0))
write('seam_eps', *seam(1e-6))
write('flipped_half', V, [f[::-1] if right(f) else f for f in F])
write('down', V, [f[::-1] for f in F])
write('two_shells', V + [[v[0] + 40, v[1], v[2]] for v in V], F + [[i + n for i in f] for f in F])
write('stray', V + [[100, 100, 0], [101, 100, 0], [100, 101, 0]], F + [[n, n + 1, n + 2]])
write('isolated', V + [[1e5, 0, 0], [0, 0, 0]], F)
near = sorted(range(len(F)), key=lambda k: sum((V[i][0] - cx) ** 2 + (V[i][1] - cy - 3) ** 2 for i in F[k]))
write('dropout', V, [F[k] for k in range(len(F)) if k not in set(near[:4])])
for name, off in (('utm', (500000, 5000000, 100)), ('utm_far', (5e6, 5e7, 1000))):
    write(name, [[v[0] + off[0], v[1] + off[1], v[2] + off[2]] for v in V], F)
