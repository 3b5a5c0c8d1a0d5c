"""The Python module against the CLI: the same config gives the same numbers, in memory and on
disk; errors are exceptions with the CLI's message; shapes and dtypes as documented.

Run by ctest (python/CMakeLists.txt sets PYTHONPATH to build/python and PQLAYOUT_CLI to the
CLI binary): `python3 -m pytest python/tests`.
"""

import csv
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import pqlayout

SOURCE = Path(os.environ.get("PQLAYOUT_SOURCE_DIR", Path(__file__).resolve().parents[2]))
CLI = os.environ.get("PQLAYOUT_CLI", str(SOURCE / "build" / "cli" / "pqlayout"))
GREAT_COURT = SOURCE / "examples" / "great_court.yaml"


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, values = rows[0], np.array(rows[1:], dtype=float)
    return {name: values[:, i] for i, name in enumerate(header)}


def read_obj(path):
    vertices, faces = [], []
    for line in Path(path).read_text().splitlines():
        if line.startswith("v "):
            vertices.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            faces.append([int(x.split("/")[0]) - 1 for x in line.split()[1:]])
    return np.array(vertices), faces


@pytest.fixture(scope="session")
def cli_run(tmp_path_factory):
    """The Great Court example through the CLI, into a folder."""
    out = tmp_path_factory.mktemp("cli") / "gc"
    subprocess.run([CLI, "run", str(GREAT_COURT), "--out", str(out), "-q"], check=True)
    return out


@pytest.fixture(scope="session")
def module_run():
    """The same config through the module, no files."""
    events = []
    result = pqlayout.run(GREAT_COURT, progress=lambda stage, event, seconds: events.append((stage, event, seconds)))
    return result, events


def test_arrays_equal_the_cli_files(cli_run, module_run):
    r, _ = module_run
    vertices, faces = read_obj(cli_run / "quads.obj")
    assert np.array_equal(r.quads.vertices, vertices)  # OBJ keeps 17 digits: exact
    assert r.quads.faces() == faces
    v0, f0 = read_obj(cli_run / "quads_initial.obj")
    assert np.array_equal(r.quads_initial.vertices, v0) and r.quads_initial.faces() == f0
    v1, f1 = read_obj(cli_run / "quads_planarized.obj")
    assert np.array_equal(r.quads_planarized.vertices, v1) and r.quads_planarized.faces() == f1
    sv, sf = read_obj(cli_run / "surface.obj")
    assert np.array_equal(r.surface.vertices, sv) and r.surface.faces.tolist() == sf
    # CSV files keep 12 significant digits.
    nodes = read_csv(cli_run / "analysis" / "nodes.csv")
    for name, column in r.analysis["nodes"].items():
        np.testing.assert_allclose(column, nodes[name], rtol=1e-11, atol=1e-300, err_msg=name)
    members = read_csv(cli_run / "analysis" / "members.csv")
    for name, column in r.analysis["members"].items():
        np.testing.assert_allclose(column, members[name], rtol=1e-11, atol=1e-9, err_msg=name)
    faces_csv = read_csv(cli_run / "fields" / "faces.csv")
    np.testing.assert_allclose(r.fields["guidance"], np.column_stack([faces_csv[k] for k in ("dx", "dy", "dz")]),
                               rtol=1e-11, atol=1e-12)
    for name in ("strain_max", "strain_min", "weight"):
        np.testing.assert_allclose(r.fields[name], faces_csv[name], rtol=1e-11, atol=1e-300, err_msg=name)
    np.testing.assert_allclose(r.fields["v_z"], read_csv(cli_run / "fields" / "vertices.csv")["vz"], rtol=1e-11,
                               atol=1e-300)
    levelsets = read_csv(cli_run / "fields" / "levelsets.csv")
    np.testing.assert_allclose(r.fields["phi"], levelsets["phi"], rtol=1e-11, atol=1e-10)
    np.testing.assert_allclose(r.fields["psi"], levelsets["psi"], rtol=1e-11, atol=1e-10)


def test_report_matches_the_cli_report(cli_run, module_run):
    import json
    r, _ = module_run
    cli = json.loads((cli_run / "report.json").read_text())
    assert r.report["run"]["completed_stages"] == pqlayout.stages()
    for stage in ("levelset", "extract", "planarize", "stiffen", "analyze"):
        for key, value in cli["stages"][stage].items():
            if key in ("seconds", "peak_memory_mb") or isinstance(value, (dict, list)):
                continue
            if key.endswith("seconds") or key.endswith("_time"):
                continue
            assert r.report["stages"][stage][key] == value, f"{stage}.{key}"
    assert r.compliance == pytest.approx(cli["stages"]["analyze"]["compliance_total"], rel=0)
    # The total compliance is the sum of the nodal ones, f·u.
    assert r.analysis["nodes"]["compliance"].sum() == pytest.approx(r.compliance, rel=1e-9)


def test_shapes_and_dtypes(module_run):
    r, _ = module_run
    n, m = len(r.surface.vertices), len(r.surface.faces)
    assert r.surface.vertices.shape == (n, 3) and r.surface.vertices.dtype == np.float64
    assert r.surface.faces.shape == (m, 3) and r.surface.faces.dtype == np.int64
    assert r.surface.faces.min() == 0 and r.surface.faces.max() == n - 1
    assert r.fields["v_z"].shape == (n,) and r.fields["phi"].shape == (n,) and r.fields["psi"].shape == (n,)
    assert r.fields["guidance"].shape == (m, 3) and r.fields["weight"].shape == (m,)
    np.testing.assert_allclose(np.linalg.norm(r.fields["guidance"], axis=1)[r.fields["weight"] > 0], 1.0, rtol=1e-12)
    q = r.quads
    assert q.vertices.dtype == np.float64 and q.vertices.shape[1] == 3
    assert q.face_offsets.dtype == np.int64 and q.face_offsets[0] == 0
    assert q.face_offsets[-1] == len(q.face_vertices) and np.all(q.face_sizes() >= 3)
    # planarize may close edges and cut darts (planarize.close_edges), stiffen brace free edges
    braced = r.report["stages"].get("stiffen", {}).get("bracing", {}).get("braced_quads", 0)
    assert q.n_faces == r.report["stages"]["planarize"]["n_faces"] + braced
    assert len(r.analysis["nodes"]["compliance"]) == len(q.vertices)
    assert r.displacement.shape == (len(q.vertices), 3)
    assert np.all(r.analysis["members"]["length"] > 0)


def test_progress_reports_every_stage_in_order(module_run):
    _, events = module_run
    names = pqlayout.stages()
    assert [e[:2] for e in events] == [(s, ev) for s in names for ev in ("started", "done")]
    assert all(seconds >= 0 for _, _, seconds in events)


def test_no_files_without_out(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    before = set(os.listdir("/tmp"))
    r = pqlayout.run({"surface": {"generator": "dome", "edge_length": 2.0}, "layout": {"spacing": 4.0}},
                     until="extract")
    assert os.listdir(tmp_path) == []
    assert not [p for p in set(os.listdir("/tmp")) - before if p.startswith("pqlayout-")]
    assert r.quads_initial is not None and r.quads is None and r.analysis is None
    assert r.report["run"]["completed_stages"][-1] == "extract"


def test_out_writes_what_the_cli_writes(tmp_path, cli_run):
    pqlayout.run(str(GREAT_COURT), out=tmp_path / "gc")
    for name in ("quads.obj", "quads_initial.obj", "analysis/nodes.csv", "analysis/members.csv", "fields/faces.csv"):
        assert (tmp_path / "gc" / name).read_bytes() == (cli_run / name).read_bytes(), name
    assert (tmp_path / "gc" / "report.html").exists()


def test_dict_config_and_set(tmp_path):
    r = pqlayout.run({"surface": {"generator": "dome", "edge_length": 2.0}}, set={"layout.spacing": 4.0},
                     until="guidance")
    assert r.report["config"]["layout"]["spacing"] == 4.0
    assert r.report["config"]["surface"]["generator"] == "dome"
    r2 = pqlayout.run({"surface": {"generator": "dome", "edge_length": np.float32(2.0)}}, set=["layout.spacing=5"],
                      until="surface")
    assert r2.report["config"]["layout"]["spacing"] == 5.0
    r3 = pqlayout.run(GREAT_COURT, set={"layout.spacing": np.int64(4), "levelset.min_angle": np.array(25.0)},
                      until="surface")
    assert r3.report["config"]["layout"]["spacing"] == 4.0 and r3.report["config"]["levelset"]["min_angle"] == 25.0
    with pytest.raises(TypeError, match="config"):
        pqlayout.run(42)
    with pytest.raises(TypeError, match="set"):
        pqlayout.run(GREAT_COURT, set="layout.spacing=2")


def test_stiffen_off_keeps_the_planarised_shell():
    r = pqlayout.run({"surface": {"generator": "dome", "edge_length": 2.0}, "layout": {"spacing": 4.0}},
                     set={"stiffen.tolerance": 0})
    assert np.array_equal(r.quads.vertices, r.quads_planarized.vertices)
    assert r.report["stages"]["stiffen"]["compliance_ratio"] == 1.0
    assert r.report["stages"]["analyze"]["compliance_total"] > 0


def test_stiffen_without_slide_keeps_vertices_on_their_normals():
    """stiffen.slide = 0 (the boxes have no tangential width) used to fail in Ceres' bounds.
    Whatever the optimiser reaches, the shell handed on keeps δ ≤ target (or is the planarised one)."""
    config = {"surface": {"generator": "hypar", "edge_length": 2.0, "width": 20, "depth": 16, "rise": 3},
              "layout": {"spacing": 3.0}}
    r = pqlayout.run(config, set={"stiffen.slide": 0})
    stiffen = r.report["stages"]["stiffen"]
    assert stiffen["planarity_max"] <= 1e-3 and stiffen["compliance_ratio"] <= 1.0
    if stiffen["kept_planarised"]:
        assert np.array_equal(r.quads.vertices, r.quads_planarized.vertices)
        assert stiffen["compliance_ratio"] == 1.0


def test_bad_key_raises_config_error_naming_it():
    with pytest.raises(pqlayout.ConfigError, match="layout.spacnig"):
        pqlayout.run(GREAT_COURT, set={"layout.spacnig": 2.0})
    with pytest.raises(pqlayout.ConfigError, match="layout.spacing"):
        pqlayout.run(GREAT_COURT, set={"layout.spacing": -1})
    with pytest.raises(pqlayout.ConfigError, match="until"):
        pqlayout.run(GREAT_COURT, until="stiffness")
    with pytest.raises(pqlayout.ConfigError, match="no_such.yaml"):
        pqlayout.run("no_such.yaml")
    assert issubclass(pqlayout.ConfigError, pqlayout.Error)


def test_bad_input_raises_input_error_naming_the_file(tmp_path):
    broken = tmp_path / "roof.obj"
    broken.write_text("v 0 0 0\nv 1 0 0\nf 1 2 3\n")
    with pytest.raises(pqlayout.InputError, match="roof.obj"):
        pqlayout.run({"surface": {"file": str(broken)}}, until="surface")


def test_an_exception_in_the_callback_stops_the_run_and_is_raised(tmp_path):
    class Stop(Exception):
        pass

    def progress(stage, event, seconds):
        if stage == "levelset" and event == "started":
            raise Stop(stage)

    with pytest.raises(Stop, match="levelset"):
        pqlayout.run(GREAT_COURT, progress=progress, out=tmp_path / "stopped")
    assert not (tmp_path / "stopped" / "report.json").exists()
    # The next run in the same process is not stopped by the last one's request.
    assert pqlayout.run(GREAT_COURT, until="guidance").report["run"]["completed_stages"][-1] == "guidance"


def test_runs_from_two_threads_take_turns_and_agree():
    import threading
    config = {"surface": {"generator": "hypar", "edge_length": 2.0}, "layout": {"spacing": 4.0}}
    alone = pqlayout.run(config, until="planarize")
    results = [None, None]

    def work(i):
        results[i] = pqlayout.run(config, until="planarize")

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        assert np.array_equal(r.quads.vertices, alone.quads.vertices)
        assert r.quads.faces() == alone.quads.faces()


def test_keys_and_version():
    keys = pqlayout.keys()
    spacing = next(k for k in keys if k["key"] == "layout.spacing")
    assert spacing["default"] == 3.0 and spacing["meaning"]
    assert {"key", "type", "default", "meaning"} <= set(spacing)
    assert len(keys) == len({k["key"] for k in keys}) > 50
    out = subprocess.run([CLI, "--version"], capture_output=True, text=True, check=True).stdout
    assert pqlayout.version().split()[0] in out


def test_ctrl_c_stops_a_run_with_keyboard_interrupt(tmp_path):
    """SIGINT to the interpreter while the run holds no GIL: KeyboardInterrupt within an
    iteration, no output, the interpreter alive."""
    script = f"""
import os, signal, threading, time, pqlayout
threading.Timer(1.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
start = time.monotonic()
try:
    pqlayout.run({str(GREAT_COURT)!r}, out={str(tmp_path / 'gc')!r})
    print("finished")
except KeyboardInterrupt:
    print("interrupted after %.1f s" % (time.monotonic() - start))
"""
    done = subprocess.run(["python3" if not os.path.exists("/usr/bin/python3") else "/usr/bin/python3", "-c", script],
                          capture_output=True, text=True, timeout=120, env=os.environ)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("interrupted after"), done.stdout + done.stderr
    assert float(done.stdout.split()[2]) < 5.0
    assert not (tmp_path / "gc").exists()
