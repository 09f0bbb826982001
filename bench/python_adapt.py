"""`metrica adapt MESH -m METRIC --threads N -o OUT` from Python, for timing
the module against the command side by side (docs/benchmarks.md):

    PYTHONPATH=build/python python3 bench/python_adapt.py MESH METRIC OUT [THREADS]
"""
import sys

import metrica

mesh_path, metric_path, out = sys.argv[1:4]
threads = int(sys.argv[4]) if len(sys.argv) > 4 else None
mesh = metrica.read(mesh_path)
(metric,) = metrica.read_field(metric_path)
adapted, _ = metrica.adapt(mesh, metric, threads=threads)
metrica.write(adapted, out)
