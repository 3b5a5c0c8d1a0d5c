"""The README's alignment-weight sweep (paper Fig. 7a's trade-off) through the Python module.

    PYTHONPATH=build/python python3 examples/notebook.py     # or just python3 examples/notebook.py

Five level-set solves of the Great Court (~7 s each); prints the table and, where matplotlib
is installed, writes out/notebook/alignment_sweep.png.
"""
import sys
from pathlib import Path

here = Path(__file__).resolve().parent
try:
    import pqlayout
except ImportError:  # not installed: use the build tree's module
    sys.path.insert(0, str(here.parent / "build" / "python"))
    import pqlayout

# --- the sweep: ten lines ---------------------------------------------------------------
columns = {"alignment_rms_deg": "alignment RMS °", "alignment_rms_deg_weight_above_half": "where weight > 0.5",
           "spacing_cv_phi": "spacing CV φ", "spacing_cv_phi_weight_above_half": "where weight > 0.5",
           "spacing_cv_psi": "spacing CV ψ", "conjugacy_rms": "conjugacy RMS", "foldovers": "fold-overs",
           "min_crossing_angle_deg": "min crossing °", "area_fraction_below_min_angle": "area fraction < 30°"}
rows = []
for weight in [1, 3, 10, 30, 100]:
    r = pqlayout.run(here / "great_court.yaml", until="levelset", set={"levelset.weights.alignment": weight})
    rows.append([weight] + [r.report["stages"]["levelset"][key] for key in columns])
print("| alignment weight | " + " | ".join(columns.values()) + " |\n|" + "---:|" * (len(columns) + 1))
for row in rows:  # the README's table, as Markdown
    print("| " + " | ".join(f"{v:.3g}" if isinstance(v, float) else str(v) for v in row) + " |")

# --- a picture where matplotlib is installed --------------------------------------------
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit(0)
out = here.parent / "out" / "notebook"
out.mkdir(parents=True, exist_ok=True)
fig, ax = plt.subplots(figsize=(5, 3.5))
ax.plot([r[2] for r in rows], [r[4] for r in rows], "o-")
for row in rows:
    ax.annotate(f"w = {row[0]}", (row[2], row[4]), textcoords="offset points", xytext=(5, 5))
ax.set_xlabel("alignment RMS where weight > 0.5 (°)")
ax.set_ylabel("spacing CV of φ where weight > 0.5")
ax.set_title("Great Court, h = 3 m: alignment-weight sweep")
fig.tight_layout()
fig.savefig(out / "alignment_sweep.png", dpi=120)
print(f"wrote {out / 'alignment_sweep.png'}")
