"""The adaptive loop with an analytic field in place of a solver: for each
complexity, five rounds of multiscale metric (L2 norm) and adaptation, then
the L2 interpolation error; plots the error against the complexity (it
falls as N^(-2/3) for a P1 field in 3D) to multiscale_loop.png.

    PYTHONPATH=build/python python3 examples/python/multiscale_loop.py cube.meshb
(cube.meshb from `metrica cube --n 3 -o cube.meshb`)
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import metrica

start = metrica.read(sys.argv[1] if len(sys.argv) > 1 else "cube.meshb")
field = "tanh3"
complexities, errors = [], []
for n in (1000, 2000, 4000, 8000, 16000):
    mesh = start
    for _ in range(5):
        u = metrica.analytic_field(mesh, field)
        metric = metrica.multiscale_metric(mesh, u, complexity=n, gradation=3.0)
        mesh, _ = metrica.adapt(mesh, metric)
    error = metrica.error(mesh, metrica.analytic_field(mesh, field), exact=field)
    print(f"complexity {n:6d}: {mesh.num_vertices:7d} vertices, L2 error {error:.3e}")
    complexities.append(n)
    errors.append(error)

plt.loglog(complexities, errors, "o-", label=f"{field}, L2")
plt.loglog(complexities, [errors[0] * (n / complexities[0]) ** (-2 / 3) for n in complexities], "k--",
           label="N^(-2/3)")
plt.xlabel("complexity N")
plt.ylabel("L2 interpolation error")
plt.legend()
plt.savefig("multiscale_loop.png", dpi=120)
