"""A pipeline composed in Python (examples/compose in C++): the seed's
reconnection, metric Delaunay then max-min edge-weight flips each cycle,
against the standard adaptation, on UGAWG polar-2, serial.

    PYTHONPATH=build/python python3 examples/python/custom_pipeline.py cube.meshb
(cube.meshb from `metrica cube --n 3 -o cube.meshb`)
"""
import sys

import metrica

mesh = metrica.read(sys.argv[1] if len(sys.argv) > 1 else "cube.meshb")
seed = metrica.Pipeline(
    cycle=[("collapse", {}), ("split", {}),
           ("delaunay", "flip", {"criterion": "metric-delaunay"}),
           ("edge-weight", "flip", {"criterion": "edge-weight"}),
           ("smooth", {"below": 0.3})],
    polish=[("flip", {"seed_below": 0.75}), ("smooth", {"below": 1.0})],
    cycles=8)
for name, run in (("standard", lambda: metrica.adapt(mesh, analytic="polar-2", concurrency="serial")),
                  ("seed's flips", lambda: seed.run(mesh, analytic="polar-2", concurrency="serial"))):
    adapted, report = run()
    q = report["quality"]
    print(f"{name:>13}: {adapted.num_tets:6d} tets, {100 * q['unit_length_share']:.1f}% of edges in range, "
          f"worst tet {q['mean_ratio']['min']:.3f}, {report['seconds']:.2f} s")
