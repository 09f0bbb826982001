"""A mesh through meshio and back: read any format meshio reads, adapt it
with Metrica, write it with meshio (here to VTK's .vtu).

    PYTHONPATH=build/python python3 examples/python/meshio_round_trip.py tests/data/msh/box_sphere_41.msh out.vtu
"""
import sys

import meshio

import metrica

m = meshio.read(sys.argv[1])
mesh = metrica.from_meshio(m)
print(mesh, mesh.info()["regions"])
metric = metrica.analytic_metric(mesh, "linear")
adapted, report = metrica.adapt(mesh, metric)
print(f"{adapted}: {100 * report['quality']['unit_length_share']:.1f}% of edges of unit length")
meshio.write(sys.argv[2] if len(sys.argv) > 2 else "out.vtu", metrica.to_meshio(adapted))
