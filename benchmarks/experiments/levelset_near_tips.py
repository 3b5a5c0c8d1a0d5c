#!/usr/bin/env python3
"""What the level sets look like round the branch points (sign -1 seam tips), from the per-face
dumps of levelset_face_diagnostics.diff (one CSV per LevelSetProblem::Measure call; the last is
the stage's end, the first the initial guess, the Poisson fits, before any Ceres solve).

    git apply benchmarks/experiments/levelset_face_diagnostics.diff && ninja -C build cli/pqlayout
    PQ_DIAG=/tmp/dg_ build/cli/pqlayout run examples/great_court.yaml --set guidance.source=curvature --until levelset --out /tmp/x -q
    /usr/bin/python3 benchmarks/experiments/levelset_near_tips.py /tmp/dg_ [index]

Per ring of distance r to the nearest tip: the crossing angle of the level lines (median / 10th
percentile), the angle the conjugacy term asks for given phi's direction ("ideal"), h|grad phi|,
h|grad psi|; then the winding of the guidance and of both gradients round each tip, in units of
pi (as line fields, 16 polar bins, doubled-angle means; -1 is an index -1/2 trisector).
"""
import glob
import re
import sys

import numpy as np


def load(stem, index):
    files = sorted(glob.glob(stem + "*.csv"), key=lambda f: int(re.findall(r"(\d+)\.csv$", f)[0]))
    return np.genfromtxt(files[index], delimiter=",", names=True)


def winding(angle, polar, bins=16):
    z = np.exp(2j * angle)
    b = ((polar + np.pi) / (2 * np.pi) * bins).astype(int) % bins
    if any(not (b == k).any() for k in range(bins)):
        return float("nan")
    a = np.angle(np.array([z[b == k].mean() for k in range(bins)])) / 2
    d = np.diff(np.append(a, a[0]))
    d = (d + np.pi / 2) % np.pi - np.pi / 2
    return d.sum() / np.pi


def main():
    d = load(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else -1)
    for lo, hi in ((0, 1.5), (1.5, 3), (3, 6), (6, 9), (9, 15), (15, 999)):
        m = (d["tipdist"] >= lo) & (d["tipdist"] < hi)
        if not m.any():
            continue
        print(f"r {lo:>4}-{hi:<4} m: {m.sum():5d} faces, crossing median {np.median(d['cross'][m]):5.1f} p10 "
              f"{np.percentile(d['cross'][m], 10):5.1f}, ideal {np.median(d['ideal'][m]):5.1f}, "
              f"h|grad phi| {np.median(d['hgphi'][m]):.2f}, h|grad psi| {np.median(d['hgpsi'][m]):.2f}")
    order = np.argsort(d["tipdist"])
    tips = []  # the face nearest each tip stands for it
    for i in order[d["tipdist"][order] < 0.75]:
        if all(np.hypot(d["x"][i] - x, d["y"][i] - y) > 5.0 for x, y in tips):
            tips.append((d["x"][i], d["y"][i]))
    for x, y in tips:
        rows = []
        for r in (2, 3, 4.5, 6, 9):
            m = np.abs(np.hypot(d["x"] - x, d["y"] - y) - r) < 0.5
            polar = np.arctan2(d["y"][m] - y, d["x"][m] - x)
            rows.append(f"r {r}: guidance {winding(d['ad'][m], polar):+.0f}, phi {winding(d['a1'][m], polar):+.0f}, "
                        f"psi {winding(d['a2'][m], polar):+.0f}")
        print(f"tip near ({x:.1f}, {y:.1f}): " + "; ".join(rows))


if __name__ == "__main__":
    main()
