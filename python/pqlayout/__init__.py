"""pqlayout: statics-sensitive layout of planar quadrilateral grid shells, from Python.

    import pqlayout
    r = pqlayout.run("examples/great_court.yaml", set={"layout.spacing": 2.0})
    r.report["stages"]["analyze"]["compliance_total"]   # report.json as a dict
    r.quads.vertices, r.quads.faces()                    # the final grid shell
    r.analysis["nodes"]["compliance"]                    # per node, as analysis/nodes.csv

The pipeline runs in this process (the C++ library, no subprocess). Files are written only
when ``out`` is given, and then exactly as ``pqlayout run --out`` writes them.
"""

import json as _json
import os as _os
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Union

import numpy as np

from . import _pqlayout
from ._pqlayout import ConfigError, Error, InputError, RunError

__all__ = ["run", "keys", "version", "stages", "Result", "PolyMesh", "TriMesh",
           "Error", "ConfigError", "InputError", "RunError"]


@dataclass
class TriMesh:
    """The reference surface: vertices (N, 3) float64 in metres, faces (M, 3) int64."""
    vertices: np.ndarray
    faces: np.ndarray


@dataclass
class PolyMesh:
    """A polygon mesh (quad-dominant grid): vertices (V, 3) float64; face f is
    face_vertices[face_offsets[f]:face_offsets[f + 1]] (int64), in the OBJ file's order."""
    vertices: np.ndarray
    face_offsets: np.ndarray
    face_vertices: np.ndarray

    @property
    def n_faces(self) -> int:
        return len(self.face_offsets) - 1

    def faces(self) -> List[List[int]]:
        """The faces as lists of vertex indices."""
        o, v = self.face_offsets, self.face_vertices
        return [v[o[f]:o[f + 1]].tolist() for f in range(self.n_faces)]

    def face_sizes(self) -> np.ndarray:
        return np.diff(self.face_offsets)


@dataclass
class Result:
    """What a run produced. A member is None when its stage did not run (see ``until``).

    report:          report.json's content (dict)
    surface:         TriMesh, the reference surface (stage surface)
    fields:          dict of numpy arrays on the reference: "v_z" (N,) membrane displacement;
                     "guidance" (M, 3), "strain_max", "strain_min", "weight" (M,) per face;
                     "phi", "psi" (N,) the level-set functions (level lines at integers)
    quads_initial:   PolyMesh as extracted (quads_initial.obj)
    quads_planarized: PolyMesh after planarisation (quads_planarized.obj)
    quads:           PolyMesh, the final grid shell (quads.obj: stiffened, or planarised)
    analysis:        {"nodes": {...}, "members": {...}}: the columns of analysis/nodes.csv
                     (x, y, z, load_z, ux, uy, uz, compliance) and analysis/members.csv
                     (node_a, node_b, length, axial_force, torsion, moments, utilisation)
    """
    report: Dict[str, Any]
    surface: Optional[TriMesh] = None
    fields: Dict[str, np.ndarray] = field(default_factory=dict)
    quads_initial: Optional[PolyMesh] = None
    quads_planarized: Optional[PolyMesh] = None
    quads: Optional[PolyMesh] = None
    analysis: Optional[Dict[str, Dict[str, np.ndarray]]] = None

    @property
    def displacement(self) -> Optional[np.ndarray]:
        """(V, 3) displacement of each node of ``quads`` under the dead load, m."""
        if self.analysis is None:
            return None
        n = self.analysis["nodes"]
        return np.column_stack([n["ux"], n["uy"], n["uz"]])

    @property
    def compliance(self) -> Optional[float]:
        """The frame's compliance f·u in J (report: stages.analyze.compliance_total)."""
        return self.report["stages"].get("analyze", {}).get("compliance_total")


def _plain(value: Any) -> Any:
    """numpy scalars and arrays as plain Python values, for json.dumps."""
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, _os.PathLike):
        return _os.fspath(value)
    raise TypeError(f"{type(value).__name__} is not a config value (numbers, strings, lists, dicts)")


def _assignments(overrides: Union[None, Mapping[str, Any], Sequence[str]]) -> List[str]:
    """KEY=VALUE strings as for --set; a dict's values are written as JSON (which is YAML)."""
    if overrides is None:
        return []
    if isinstance(overrides, Mapping):
        return [f"{key}={_json.dumps(value, default=_plain)}" for key, value in overrides.items()]
    if isinstance(overrides, str):
        raise TypeError("set: a dict {key: value} or a list of 'key=value' strings, not a string")
    return [str(item) for item in overrides]


def run(config: Union[str, "_os.PathLike[str]", Mapping[str, Any]],
        set: Union[None, Mapping[str, Any], Sequence[str]] = None,
        until: str = "analyze",
        out: Union[None, str, "_os.PathLike[str]"] = None,
        progress: Optional[Callable[[str, str, float], None]] = None,
        verbose: bool = False) -> Result:
    """Runs the pipeline and returns a Result.

    config:   a YAML config file's path, or a dict with the same nesting
              ({"layout": {"spacing": 2.0}}; relative paths against the working directory)
    set:      overrides applied after the config, {"layout.spacing": 2.0} or ["layout.spacing=2"]
    until:    the last stage: surface, membrane, guidance, levelset, extract, planarize,
              stiffen or analyze
    out:      folder to write the run's files into (as `pqlayout run --out`); None: no files
    progress: called as progress(stage, event, seconds) with event "started" or "done";
              an exception it raises stops the run and is re-raised
    verbose:  the CLI's progress lines on stderr (otherwise warnings only)

    Raises ConfigError (bad key or value, named), InputError (bad input file), RunError (the
    run could not complete), KeyboardInterrupt (Ctrl-C stops the run within one iteration).
    """
    if isinstance(config, Mapping):
        path, text = None, _json.dumps(config, default=_plain)
    elif isinstance(config, (str, _os.PathLike)):
        path, text = _os.fspath(config), None
    else:
        raise TypeError("config: a path or a dict, not " + type(config).__name__)
    if progress is not None and not callable(progress):
        raise TypeError("progress: a callable (stage, event, seconds)")
    raw = _pqlayout.run(path, text, _assignments(set), until,
                        None if out is None else _os.fspath(out), progress, bool(verbose))
    return _result(raw)


def _poly(d: Optional[Dict[str, np.ndarray]]) -> Optional[PolyMesh]:
    return None if d is None else PolyMesh(d["vertices"], d["face_offsets"], d["face_vertices"])


def _result(raw: Dict[str, Any]) -> Result:
    surface = raw.get("surface")
    return Result(report=_json.loads(raw["report"]),
                  surface=None if surface is None else TriMesh(surface["vertices"], surface["faces"]),
                  fields=dict(raw.get("fields", {})),
                  quads_initial=_poly(raw.get("quads_initial")),
                  quads_planarized=_poly(raw.get("quads_planarized")),
                  quads=_poly(raw.get("quads")),
                  analysis=raw.get("analysis"))


def keys() -> List[Dict[str, Any]]:
    """The config reference: one dict per key, {"key", "type", "default", "meaning"}."""
    return _json.loads(_pqlayout.keys())


def version() -> str:
    """pqlayout's version and git revision, e.g. "0.1.0 (git 1999bf0)"."""
    return _pqlayout.version()


def stages() -> List[str]:
    """The stage names in order (the values of ``until``)."""
    return list(_pqlayout.stages())
