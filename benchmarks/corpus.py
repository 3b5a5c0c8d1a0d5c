"""The roof corpus (issue 17): every roof of examples/corpus (and the Great Court) through the
whole pipeline with strain and with curvature guidance, defaults only; one table of every
stage's key metrics and time, each checked against the issue's targets.

    bash benchmarks/corpus.sh                 # builds, then runs this; ~5 min on 2 cores
    PYTHONPATH=build/python python3 benchmarks/corpus.py [--set KEY=VALUE ...] [--roofs a,b]

Writes benchmarks/corpus.md (the table, misses in bold with the reason, and a gallery of the
level lines of every run) and benchmarks/corpus.csv (every number). Uses the Python
module: one process; each run writes its files into a temporary folder (stage seconds include
writing them, as on the command line), of which figures/levelsets.svg becomes
docs/corpus/<roof>_<source>.png (rsvg-convert and pngquant; corpus.sh installs them).
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
try:
    import pqlayout
except ImportError:
    sys.path.insert(0, str(ROOT / "build" / "python"))
    import pqlayout

# (column, what it measures, the target as a predicate of (value, h), the target's text)
TARGETS = [
    ("alignment", "levelset: alignment RMS where weight > 0.5, ° (n/a: no face has weight > 0.5, nothing to align)",
     lambda v, h: v is None or v <= 8.0, "≤ 8°"),
    ("foldovers", "levelset: fold-overs", lambda v, h: v == 0, "0"),
    ("min_crossing", "levelset: min crossing angle, °", lambda v, h: v >= 25.0, "≥ 25°"),
    ("area_below_30", "levelset: area fraction crossing below 30°", lambda v, h: v <= 0.01, "≤ 1 %"),
    ("spacing_cv", "levelset: spacing CV, max of φ and ψ", lambda v, h: v <= 0.25, "≤ 0.25"),
    ("quad_fraction", "extract: quads / faces", lambda v, h: v >= 0.80, "≥ 0.80"),
    ("interior_non_quads", "extract: non-quads touching no boundary", lambda v, h: v == 0, "0"),
    ("boundary_deviation_h", "extract: boundary deviation / h", lambda v, h: v <= 0.01, "≤ 0.01 h"),
    ("edge_min_h", "extract: shortest edge / h", lambda v, h: v >= 0.2, "≥ 0.2 h"),
    ("planarity_max", "planarize: δ max", lambda v, h: v <= 1e-3, "≤ 1e-3"),
    ("closeness_h", "planarize: closeness max / h", lambda v, h: v <= 0.02, "≤ 0.02 h"),
]
INFO = ["faces", "panels", "planarized_quads", "folded_panels", "planarized_edge_min_h", "compliance_ratio", "compliance_J", "braced_quads", "bracing_ratio", "levelset_s", "extract_s", "planarize_s", "stiffen_s", "total_s"]


def measure(report):
    s = report["stages"]
    h = report["config"]["layout"]["spacing"]
    lv, ex, pl = s["levelset"], s["extract"], s["planarize"]
    return {
        "alignment": lv["alignment_rms_deg_weight_above_half"] if s["guidance"]["area_weight_above_half"] > 0 else None,
        "foldovers": lv["foldovers"],
        "min_crossing": lv["min_crossing_angle_deg"],
        "area_below_30": lv["area_fraction_below_min_angle"],
        "spacing_cv": max(lv["spacing_cv_phi"], lv["spacing_cv_psi"]),
        "quad_fraction": ex["quad_fraction"],
        "interior_non_quads": len(ex.get("interior_non_quads", [])),
        "boundary_deviation_h": ex["boundary_deviation"] / h,
        "edge_min_h": ex["edge_length_min"],  # extract reports edge lengths relative to h
        "planarity_max": pl["planarity_max"],
        "closeness_h": pl["closeness_max"] / h,
        "faces": s["surface"]["n_faces"],
        "panels": ex["n_faces"],
        "planarized_quads": pl.get("quad_fraction"),
        "folded_panels": pl.get("folded_faces"),
        "planarized_edge_min_h": pl.get("edge_length_min"),
        "compliance_ratio": s.get("stiffen", {}).get("compliance_ratio"),
        "compliance_J": s.get("stiffen", {}).get("compliance_after"),
        "braced_quads": s.get("stiffen", {}).get("bracing", {}).get("braced_quads"),
        "bracing_ratio": s.get("stiffen", {}).get("bracing", {}).get("compliance_ratio"),
        "levelset_s": lv["seconds"], "extract_s": ex["seconds"], "planarize_s": pl["seconds"],
        "stiffen_s": s.get("stiffen", {}).get("seconds"),
        "total_s": report["run"]["total_seconds"],
    }


def roofs(selected):
    configs = sorted((ROOT / "examples" / "corpus").glob("*.yaml")) + [ROOT / "examples" / "great_court.yaml"]
    return [c for c in configs if not selected or c.stem in selected]


def fmt(value):
    if value is None:
        return "n/a"
    if isinstance(value, float):
        return f"{value:.3g}" if abs(value) < 1e3 else f"{value:.0f}"
    return str(value)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--set", action="append", default=[], help="KEY=VALUE for every run")
    parser.add_argument("--roofs", default="", help="comma-separated roof names (default: all)")
    parser.add_argument("--out", default=str(HERE / "corpus"), help="output stem (.md, .csv)")
    parser.add_argument("--figures", default=None,
                        help="folder for the gallery's PNGs ('' for none; default docs/corpus, or STEM_figures "
                             "with --out, so that an experiment leaves the README's gallery alone)")
    args = parser.parse_args()
    if args.figures is None:
        args.figures = str(ROOT / "docs" / "corpus") if args.out == str(HERE / "corpus") else args.out + "_figures"
    figures = Path(args.figures) if args.figures and shutil.which("rsvg-convert") else None
    if args.figures and figures is None:
        print("corpus: rsvg-convert not found, no gallery", file=sys.stderr)
    if figures:
        figures.mkdir(parents=True, exist_ok=True)
    scratch = tempfile.TemporaryDirectory(prefix="pq_corpus_")
    rows = []
    for config in roofs([r for r in args.roofs.split(",") if r]):
        for source in ("strain", "curvature"):
            start = time.monotonic()
            row = {"roof": config.stem, "source": source}
            try:
                out = Path(scratch.name) / f"{config.stem}_{source}"
                result = pqlayout.run(config, set=args.set + [f"guidance.source={source}"], out=out)
                row.update(measure(result.report))
                if figures:
                    row["figure"] = thumbnail(out / "figures" / "levelsets.svg", figures / f"{out.name}.png")
                row["warnings"] = len(result.report.get("warnings", []))
                row["causes"] = [(t["name"], t["value"], t["target"], t["cause"])
                                 for t in result.report["targets"]["list"] if not t["met"]]
            except pqlayout.Error as e:
                row["error"] = str(e)
            misses = [name for name, _, ok, _ in TARGETS if name in row and not ok(row[name], None)]
            row["misses"] = len(misses) if "error" not in row else None
            print(f"{config.stem:>16} {source:>9}: {time.monotonic() - start:6.1f} s, "
                  + (row.get("error") or f"{row['misses']} targets missed {misses}"), flush=True)
            rows.append(row)
    write_csv(rows, Path(args.out + ".csv"))
    write_markdown(rows, Path(args.out + ".md"), args.set)


def thumbnail(svg, png, width=360):
    """svg as a PNG `width` pixels wide (colours quantised if pngquant is there); its path."""
    subprocess.run(["rsvg-convert", "-w", str(width), str(svg), "-o", str(png)], check=True)
    if shutil.which("pngquant"):
        subprocess.run(["pngquant", "--quality=60-85", "--speed", "1", "-f", "-o", str(png), str(png)], check=True)
    return png


def write_csv(rows, path):
    columns = ["roof", "source"] + [t[0] for t in TARGETS] + INFO + ["misses", "warnings", "error"]
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        for row in rows:
            w.writerow({k: row.get(k, "") for k in columns})


def write_markdown(rows, path, sets):
    lines = ["# Roof corpus: every roof × both guidance sources, defaults only", "",
             f"`bash benchmarks/corpus.sh{''.join(' --set ' + s for s in sets)}` on {time.strftime('%Y-%m-%d')}, "
             f"pqlayout {pqlayout.version()}. A target missed is **bold**. Columns:", ""]
    lines += [f"- `{name}`: {what}, target {text}" for name, what, _, text in TARGETS]
    lines += ["- then: reference triangles, panels, the quad fraction after planarisation's panel repair "
              "(planarize.close_edges: closed edges and darts make triangles), the panels convex when extracted "
              "that planarisation folded or "
              "turned a corner inside out, and its shortest edge / h (no target in issue 17; README, planarisation), "
              "stiffen's compliance ratio (of the shell it stiffened) and its compliance after, J (the whole roof's self-weight on the frame; compare runs of one roof only), the quads "
              "on free edges cut into triangles and the compliance after stiffen with them over without "
              "(extract.brace_free_edges = paying), seconds of level sets, "
              "extraction, planarisation, stiffen and the whole run", ""]
    header = ["roof", "source"] + [t[0] for t in TARGETS] + INFO
    lines += ["| " + " | ".join(header) + " |", "|" + "---|" * 2 + "---:|" * (len(header) - 2)]
    for row in rows:
        if "error" in row:
            lines.append(f"| {row['roof']} | {row['source']} | **refused or failed: {row['error']}** |")
            continue
        cells = [row["roof"], row["source"]]
        for name, _, ok, _ in TARGETS:
            cells.append(fmt(row[name]) if ok(row[name], None) else f"**{fmt(row[name])}**")
        cells += [fmt(row.get(k)) for k in INFO]
        lines.append("| " + " | ".join(cells) + " |")
    met = sum(1 for r in rows if r.get("misses") == 0)
    lines += ["", f"All targets met: {met} of {len(rows)} runs.", "",
              "## Every miss and its cause", "",
              "As report.json `targets` gives it (pipeline/layout_targets.h: measured from the run: "
              "where the worst element is and what lies there).", ""]
    for row in rows:
        for name, value, target, cause in row.get("causes", []):
            lines.append(f"- **{row['roof']} × {row['source']}**, `{name}` {fmt(value)} (target {target}): {cause}")
    figures = {(r["roof"], r["source"]): r["figure"] for r in rows if "figure" in r}
    if figures:
        lines += ["", "## Gallery", "",
                  "The level lines of every run: φ (black) along the guidance, ψ (blue) conjugate, hatched "
                  "where the guidance is too weak to align to (figures/levelsets.svg of each run).", "", "| roof | strain | curvature |", "|---|---|---|"]
        for roof in dict.fromkeys(r["roof"] for r in rows):
            cells = []
            for source in ("strain", "curvature"):
                f = figures.get((roof, source))
                # relative to benchmarks/, where corpus.md lives in the repository, wherever --out wrote it
                cells.append(f"![{roof} × {source}]({Path(os.path.relpath(Path(f).resolve(), HERE.resolve())).as_posix()})"
                             if f else "")
            lines.append(f"| {roof} | " + " | ".join(cells) + " |")
    path.write_text("\n".join(lines) + "\n")
    print(f"wrote {path} and {path.with_suffix('.csv')}: all targets met in {met} of {len(rows)} runs")


if __name__ == "__main__":
    main()
