"""Metrica from Python: metric-based anisotropic adaptation of tetrahedral
meshes, with meshes and metrics as numpy arrays.

    import metrica
    mesh = metrica.read("cube.meshb")
    adapted, report = metrica.adapt(mesh, analytic="linear", iterations=2)
    metrica.write(adapted, "linear.meshb")

Every function checks its input as the `metrica` command does and raises
`metrica.InputError` (a ValueError) with the command's message; messages
number vertices and tets from 0, as the arrays' rows. metrica.fem.dolfinx
(imported on its own) puts FEniCSx in the loop. See docs/python.md.
"""

import logging as _logging
import os as _os

import numpy as _np


class MetricaWarning(UserWarning):
    """A warning of the library (a mesh reoriented, a field left out, a run
    made again serially): what the command prints as "warning: ...". Other
    messages go to the "metrica" logger."""

# OpenMP's threads sleep as soon as they wait unless the environment
# chooses, as for the command (cli/main.cpp): spinning, they slowed two
# threads 1.6x beside a busy process. libgomp reads this when it is
# loaded, by the import below unless something loaded it before.
_os.environ.setdefault("OMP_WAIT_POLICY", "passive")

from ._metrica import (
    InputError,
    Mesh,
    box,
    analytic_field,
    analytic_metric,
    complexity,
    error,
    hessian,
    hessian_metric,
    interpolate,
    intersect,
    multiscale_metric,
    quality,
    read,
    read_field,
    write,
    write_field,
)
from . import _metrica

__version__ = _metrica.__version__

__all__ = [
    "InputError",
    "Mesh",
    "MetricaWarning",
    "Pipeline",
    "adapt",
    "analytic_field",
    "analytic_metric",
    "box",
    "complexity",
    "error",
    "from_meshio",
    "hessian",
    "hessian_metric",
    "interpolate",
    "intersect",
    "multiscale_metric",
    "quality",
    "read",
    "read_field",
    "to_meshio",
    "write",
    "write_field",
]

_log = _logging.getLogger("metrica")


def _log_cycle(cycle):
    ops = " | ".join(
        f"{name} {s['applied']}/{s['tried']}" for name, s in cycle["ops"].items() if s["tried"] or s["candidates"]
    )
    # A quality pass before the phase's last does not measure the share in range (None).
    in_range = f"{100.0 * cycle['in_range']:5.1f}%" if cycle["in_range"] is not None else "    - "
    _log.info(
        "%s %2d: %9d vertices %10d tets | %s | in range %s min Q %.3f | %.2f s",
        cycle["kind"], cycle["cycle"], cycle["vertices"], cycle["tets"], ops, in_range,
        cycle["min_quality"], cycle["seconds"],
    )


def _whole(name, value, lo, hi):
    """`value` as an int in [lo, hi] (a bool or a fraction is refused)."""
    if isinstance(value, bool) or not isinstance(value, (int, _np.integer)) or not lo <= value <= hi:
        raise InputError(f"{name} must be a whole number in [{lo}, {hi}] (got {value!r})")
    return int(value)


def adapt(mesh, metric=None, *, analytic=None, iterations=1, threads=None, concurrency="speculative",
          space="log-euclidean", precision="filtered", geometry=None, on_cycle=None, max_tets=None, dry_run=False,
          **options):
    """Adapts a copy of `mesh` to a metric and returns (adapted mesh, report).

    metric:      an (n, 6) float64 array at the mesh's vertices (xx, xy, yy,
                 xz, yz, zz), or
    analytic:    "linear", "polar-1" or "polar-2": new vertices take the
                 exact metric, re-evaluated between `iterations`.
    concurrency: "speculative" (threads) or "serial" (the command's serial
                 output, to the bit); space: "log-euclidean", "anisotropic",
                 "isotropic"; precision (of the metric-Delaunay criterion's
                 insphere signs, the centroid rule's flips): "filtered", "exact", "fast".
    geometry:    a CAD model (.step, .iges, .brep, .geo) the boundary lies
                 on, as `metrica adapt --geometry`: its surface tags are the
                 mesh's surface ids; new boundary vertices go on the model.
    options:     those of `metrica adapt`, '-' written '_': points
                 ("edge", "centroid"), hmin, hmax, and (the command's
                 settings table: name, values, default)
{settings}

    threads:     the threads of the run (default: all cores).
    max_tets:    refuse, before any work, a run predicted to make more
                 tets than this (10 per unit of the metric's complexity;
                 default: what 90% of this machine's memory holds, 125
                 bytes a tet); dry_run=True returns (None, the prediction:
                 complexity, predicted_tets, predicted_bytes) and runs
                 nothing.

    The adapted mesh is checked as the command checks it; if a run on
    threads fails that check, it is made again from the input with
    concurrency="serial" (a MetricaWarning says so).

    Each cycle is logged to the "metrica" logger (INFO) and passed to
    `on_cycle(dict)` when given. The report holds the cycles, the
    operations' counts and the quality report. The GIL is released while it
    runs; Ctrl-C raises KeyboardInterrupt after the current cycle, the
    input mesh untouched.
    """
    def each(cycle):
        if _log.isEnabledFor(_logging.INFO):
            _log_cycle(cycle)
        if on_cycle is not None:
            on_cycle(cycle)

    threads = 0 if threads is None else _whole("adapt: threads", threads, 1, 4096)
    if max_tets is not None and (isinstance(max_tets, bool) or not isinstance(max_tets, (int, float, _np.number))
                                 or not max_tets > 0):
        raise InputError(f"adapt: max_tets must be a positive number (got {max_tets!r})")
    return _metrica._adapt(mesh, metric, analytic or "", _whole("adapt: iterations", iterations, 1, 1000), threads,
                           concurrency, space, precision, str(geometry or ""), dict(options), each,
                           float(max_tets or 0), bool(dry_run))


if adapt.__doc__:  # none under python -OO
    adapt.__doc__ = adapt.__doc__.replace("{settings}", "\n".join(
        f"                   {name:<20} {domain}, default {default:g}: {help}"
        for name, domain, default, help in _metrica._adapt_settings()))


class Pipeline:
    """A pipeline of the standard stages, composed here (examples/compose in
    C++). Each stage is a tuple (name, operation, options) or (operation,
    options), the name then the operation's; a name is the stage's key in
    the report and in the passes' epochs, so one list holds each name once.

        p = metrica.Pipeline(
            cycle=[("collapse", {}), ("split", {}),
                   ("delaunay", "flip", {"criterion": "metric-delaunay"}),
                   ("edge-weight", "flip", {"criterion": "edge-weight"}),
                   ("smooth", {"below": 0.3})],
            polish=[("flip", {}), ("smooth", {"below": 1.0})],
            cycles=8)
        adapted, report = p.run(mesh, analytic="polar-2", concurrency="serial")

    Operations and their options:
{stages}
    Rules (keyword arguments, the command's --cycles ... as metrica
    pipeline takes them):
{rules}
    The cycles run until the rules stop them, then the polish stages
    quality_passes times, then the repair stages while a tet is below
    repair_below. Runs in the log-Euclidean space with filtered predicates,
    serial or speculative.
    """

    def __init__(self, cycle=(), polish=(), repair=(), **rules):
        self.cycle = list(cycle)
        self.polish = list(polish)
        self.repair = list(repair)
        self.rules = rules

    def __repr__(self):
        rules = "".join(f", {name}={value!r}" for name, value in self.rules.items())
        return f"metrica.Pipeline(cycle={self.cycle!r}, polish={self.polish!r}, repair={self.repair!r}{rules})"

    @staticmethod
    def _specs(stages):
        out = []
        for stage in stages:
            if len(stage) == 2:
                op, options = stage
                out.append((op, op, dict(options)))
            elif len(stage) == 3:
                name, op, options = stage
                out.append((name, op, dict(options)))
            else:
                raise InputError(f"a stage is (name, operation, options) or (operation, options), got {stage!r}")
        return out

    def run(self, mesh, metric=None, *, analytic=None, concurrency="speculative", threads=None, on_cycle=None):
        """Runs the pipeline on a copy of `mesh`; returns (adapted, report) as adapt() does."""
        def each(cycle):
            if _log.isEnabledFor(_logging.INFO):
                _log_cycle(cycle)
            if on_cycle is not None:
                on_cycle(cycle)

        return _metrica._run_pipeline(mesh, metric, analytic or "", self._specs(self.cycle), self._specs(self.polish),
                                      self._specs(self.repair), dict(self.rules), concurrency,
                                      0 if threads is None else _whole("pipeline: threads", threads, 1, 4096), each)


def _stage_help():
    lines = []
    for op, help, options in _metrica._stage_kinds():
        lines.append(f"      {op:<10} {help}")
        lines.extend(f"        {name:<18} {domain}: {text}" for name, domain, text in options)
    return "\n".join(lines)


def _rule_help():
    return "\n".join(f"      {name:<20} {domain}, default {default:g}: {text}"
                     for name, domain, default, text in _metrica._pipeline_rules())


if Pipeline.__doc__:  # none under python -OO
    Pipeline.__doc__ = Pipeline.__doc__.replace("{stages}", _stage_help()).replace("{rules}", _rule_help())


def to_meshio(mesh):
    """The mesh as a meshio.Mesh: "tetra" and "triangle" cells, their ids as
    the cell data "ref" (needs meshio)."""
    import meshio

    return meshio.Mesh(
        mesh.points,
        [("tetra", mesh.tets), ("triangle", mesh.triangles)],
        cell_data={"ref": [mesh.tet_ids, mesh.triangle_ids]},
    )


def from_meshio(m, ref=None):
    """A Mesh from a meshio.Mesh: its "tetra" cells and its "triangle" cells
    (the boundary and internal surfaces), ids from the cell data `ref` (by
    default the first of "ref", "medit:ref", "gmsh:physical" it holds).
    Other cells are left out."""
    import numpy as np

    names = [ref] if ref else ["ref", "medit:ref", "gmsh:physical"]
    data = next((m.cell_data[n] for n in names if n in m.cell_data), None)
    tets, tet_ids, triangles, triangle_ids = [], [], [], []
    for k, block in enumerate(m.cells):
        ids = np.asarray(data[k]) if data is not None else np.zeros(len(block.data), dtype=np.int64)
        if ids.ndim == 2 and ids.shape[1] == 1:  # a .vtu's one-component cell data
            ids = ids[:, 0]
        if block.type == "tetra":
            tets.append(block.data)
            tet_ids.append(ids)
        elif block.type == "triangle":
            triangles.append(block.data)
            triangle_ids.append(ids)
    if not tets:
        raise InputError("from_meshio: the mesh has no tetra cells")
    cat = lambda parts: np.concatenate(parts) if parts else None
    return Mesh(np.asarray(m.points, dtype=np.float64), cat(tets), cat(triangles), cat(triangle_ids), cat(tet_ids))
