"""An adaptive loop with FEniCSx (dolfinx) as the solver: the Poisson problem
-laplace(u) = f on the unit cube with the sharp internal layer
u = tanh(50 (x + y + z - 1.5)) (f and the boundary values from u), solved
with P1 elements; metrica adapts the mesh to the multiscale metric of the
discrete solution. Then the same solve on dolfinx's uniform cubes of
comparable vertex counts, and the L2 errors side by side: a table on
standard output, fenicsx_loop.csv, and fenicsx_loop.png when matplotlib is
there.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/fenicsx_loop.py [N ...]

N: the complexities (default 1000 2000 4000); each takes 6 rounds of
solve, metric and adaptation from the previous complexity's mesh.
Needs Debian's python3-dolfinx (dolfinx 0.5).
"""
import sys

import numpy as np
import ufl
from dolfinx import fem, mesh as dmesh
from mpi4py import MPI

import metrica
from metrica.fem import dolfinx as mfx


def exact(x):
    return np.tanh(50.0 * (x[0] + x[1] + x[2] - 1.5))


def solve(domain):
    """The user's own FEniCSx code: P1 Poisson, u = exact on the boundary."""
    V = fem.FunctionSpace(domain, ("Lagrange", 1))
    x = ufl.SpatialCoordinate(domain)
    u_exact = ufl.tanh(50.0 * (x[0] + x[1] + x[2] - 1.5))
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    domain.topology.create_connectivity(2, 3)
    boundary = fem.locate_dofs_topological(V, 2, dmesh.exterior_facet_indices(domain.topology))
    g = fem.Function(V)
    g.interpolate(exact)
    problem = fem.petsc.LinearProblem(
        ufl.inner(ufl.grad(u), ufl.grad(v)) * ufl.dx,
        -ufl.div(ufl.grad(u_exact)) * v * ufl.dx(metadata={"quadrature_degree": 4}),
        bcs=[fem.dirichletbc(g, boundary)],
        petsc_options={"ksp_type": "cg", "pc_type": "gamg", "ksp_rtol": 1e-10},
    )
    return problem.solve()


def l2_error(mesh, u):
    """The L2 error of the P1 solution against the exact one."""
    return metrica.error(mesh, u, exact=lambda p: exact(p.T))


complexities = [float(n) for n in sys.argv[1:]] or [1000.0, 2000.0, 4000.0]
rounds = 6
rows = []
mesh = metrica.box(6)
for n in complexities:
    # The loop itself: the user's solve, then metrica.
    for _ in range(rounds):
        domain, regions, surfaces = mfx.to_dolfinx(mesh)
        u = mfx.vertex_values(solve(domain))
        metric = metrica.multiscale_metric(mesh, u, complexity=n, gradation=2.0)
        mesh, _ = metrica.adapt(mesh, metric)
    domain, _, _ = mfx.to_dolfinx(mesh)
    adapted = l2_error(mesh, mfx.vertex_values(solve(domain)))
    # dolfinx's uniform cube with about as many vertices.
    k = max(2, round(mesh.num_vertices ** (1 / 3)) - 1)
    cube = dmesh.create_unit_cube(MPI.COMM_SELF, k, k, k)
    uniform_mesh = mfx.from_dolfinx(cube)
    uniform = l2_error(uniform_mesh, mfx.vertex_values(solve(cube)))
    rows.append((n, mesh.num_vertices, adapted, uniform_mesh.num_vertices, uniform))
    print(f"complexity {n:7.0f}: adapted {mesh.num_vertices:6d} vertices, L2 error {adapted:.3e} | "
          f"uniform {uniform_mesh.num_vertices:6d} vertices, L2 error {uniform:.3e} | ratio {uniform / adapted:.0f}",
          flush=True)

with open("fenicsx_loop.csv", "w") as out:
    out.write("complexity,adapted_vertices,adapted_l2_error,uniform_vertices,uniform_l2_error\n")
    for row in rows:
        out.write("{:.0f},{},{:.6e},{},{:.6e}\n".format(*row))

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib not found: no plot (scripts/setup --examples installs it)")
else:
    plt.loglog([r[1] for r in rows], [r[2] for r in rows], "o-", label="metrica, adapted")
    plt.loglog([r[3] for r in rows], [r[4] for r in rows], "s-", label="dolfinx, uniform cubes")
    plt.xlabel("vertices")
    plt.ylabel("L2 error")
    plt.title("P1 Poisson, u = tanh(50 (x + y + z - 1.5))")
    plt.legend()
    plt.savefig("fenicsx_loop.png", dpi=120)
