"""Metrica from Python: metric-based anisotropic adaptation of tetrahedral
meshes, with meshes and metrics as numpy arrays.

    import metrica
    mesh = metrica.read("cube.meshb")
    adapted, report = metrica.adapt(mesh, analytic="linear", iterations=2)
    metrica.write(adapted, "linear.meshb")

Every function checks its input as the `metrica` command does and raises
`metrica.InputError` (a ValueError) with the command's message. See
docs/python.md.
"""

import logging

from ._metrica import (
    InputError,
    Mesh,
    analytic_metric,
    quality,
    read,
    read_field,
    write,
    write_field,
)
from . import _metrica

__all__ = [
    "InputError",
    "Mesh",
    "adapt",
    "analytic_metric",
    "quality",
    "read",
    "read_field",
    "write",
    "write_field",
]

_log = logging.getLogger("metrica")


def _log_cycle(cycle):
    ops = " | ".join(
        f"{name} {s['applied']}/{s['tried']}" for name, s in cycle["ops"].items() if s["tried"] or s["candidates"]
    )
    _log.info(
        "%s %2d: %9d vertices %10d tets | %s | in range %5.1f%% min Q %.3f | %.2f s",
        cycle["kind"], cycle["cycle"], cycle["vertices"], cycle["tets"], ops,
        100.0 * cycle["in_range"], cycle["min_quality"], cycle["seconds"],
    )


def adapt(mesh, metric=None, *, analytic=None, iterations=1, threads=None, concurrency="speculative",
          space="log-euclidean", precision="filtered", on_cycle=None, **options):
    """Adapts a copy of `mesh` to a metric and returns (adapted mesh, report).

    metric:      an (n, 6) float64 array at the mesh's vertices (xx, xy, yy,
                 xz, yz, zz), or
    analytic:    "linear", "polar-1" or "polar-2": new vertices take the
                 exact metric, re-evaluated between `iterations`.
    concurrency: "speculative" (threads) or "serial" (the command's serial
                 output, to the bit); space: "log-euclidean", "anisotropic",
                 "isotropic"; precision: "filtered", "exact", "fast".
    options:     those of `metrica adapt`, '-' written '_': cycles,
                 quality_passes, repair_rounds, repair_below, max_length,
                 min_length, collapse_max_length, shape_floor, smooth_below,
                 points ("edge", "centroid"), hmin, hmax.

    Each cycle is logged to the "metrica" logger (INFO) and passed to
    `on_cycle(dict)` when given. The report holds the cycles, the
    operations' counts and the quality report. The GIL is released while it
    runs; Ctrl-C raises KeyboardInterrupt after the current cycle, the
    input mesh untouched.
    """
    def each(cycle):
        if _log.isEnabledFor(logging.INFO):
            _log_cycle(cycle)
        if on_cycle is not None:
            on_cycle(cycle)

    return _metrica._adapt(mesh, metric, analytic or "", int(iterations), int(threads or 0), concurrency, space,
                           precision, dict(options), each)
