"""The OpenFOAM side of examples/openfoam/run: a metrica mesh made into a
laminar compressible rhoSimpleFoam case of the delta wing, and what comes
back from a solve (the force coefficients, the Mach number at the mesh's
vertices).

    foam_case.py case DIR MESH.meshb   the case in DIR (mesh, fields, dictionaries)
    foam_case.py forces DIR            "CD CL DRIFT" of the last iteration; DRIFT is the
                                       largest relative change of CD and CL over the
                                       last 100 iterations (how converged the solve is)
    foam_case.py decompose DIR N       system/decomposeParDict for N processes
    foam_case.py mach DIR MESH.meshb OUT.sol
                                       the Mach number at MESH's vertices

Needs the metrica module (PYTHONPATH=build/python), METRICA (the command),
and OpenFOAM's gmshToFoam and foamToVTK on PATH (Debian's openfoam).

The flow (the High-Order Workshops' laminar delta wing, the seed's case):
Mach 0.3, angle of attack 12.5 degrees, Reynolds 4,000 on the root chord 1,
isothermal no-slip wall at the free-stream temperature 273.15 K, Prandtl
0.72, constant viscosity; air as a perfect gas (28.97 g/mol, gamma 1.4);
free-stream pressure 1e5 Pa (any value: the flow scales with it). The
half model's planform area 0.133974596 is the reference area.
"""
import math
import os
import re
import subprocess
import sys

import numpy as np

import metrica

MACH, TEMPERATURE, PRESSURE, REYNOLDS = 0.3, 273.15, 1.0e5, 4000.0
CHORD, AREA, ALPHA = 1.0, 0.133974596, math.radians(12.5)
MOL_WEIGHT, GAMMA, PRANDTL = 28.97, 1.4, 0.72

GAS = 8314.46261815324 / MOL_WEIGHT
CP = GAMMA * GAS / (GAMMA - 1)
SPEED = MACH * math.sqrt(GAMMA * GAS * TEMPERATURE)
DENSITY = PRESSURE / (GAS * TEMPERATURE)
VISCOSITY = DENSITY * SPEED * CHORD / REYNOLDS
VELOCITY = (SPEED * math.cos(ALPHA), 0.0, SPEED * math.sin(ALPHA))
LIFT = (-math.sin(ALPHA), 0.0, math.cos(ALPHA))
DRAG = (math.cos(ALPHA), 0.0, math.sin(ALPHA))


def run(*command, cwd=None):
    result = subprocess.run(command, cwd=cwd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"foam_case.py: {' '.join(command)} failed:\n{result.stdout[-2000:]}{result.stderr[-2000:]}")
    return result.stdout


def surface_groups(mesh):
    """Each surface id of the mesh: "symmetry" (the plane y = 0), "farfield"
    (a face of the box) or "wing"."""
    p, tri, ids = mesh.points, mesh.triangles, mesh.triangle_ids
    lo, hi = p.min(axis=0), p.max(axis=0)
    groups = {}
    for s in np.unique(ids):
        corners = p[tri[ids == s]].reshape(-1, 3)
        if np.all(np.abs(corners[:, 1]) < 1e-9):
            groups[int(s)] = "symmetry"
        elif any(np.all(np.abs(corners[:, k] - b[k]) < 1e-6 * (1 + abs(b[k]))) for b in (lo, hi) for k in range(3)):
            groups[int(s)] = "farfield"
        else:
            groups[int(s)] = "wing"
    if sorted(set(groups.values())) != ["farfield", "symmetry", "wing"]:
        sys.exit(f"foam_case.py: the surfaces are not a wing in a box with a symmetry plane: {groups}")
    return groups


def header(cls, name):
    return f"FoamFile {{ version 2.0; format ascii; class {cls}; object {name}; }}\n"


def vector(v):
    return f"({v[0]:.12g} {v[1]:.12g} {v[2]:.12g})"


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def field(name, cls, dimensions, value, wing, farfield):
    return header(cls, name) + f"""dimensions {dimensions};
internalField uniform {value};
boundaryField
{{
    "wing_.*" {{ {wing} }}
    "symmetry_.*" {{ type symmetryPlane; }}
    "farfield_.*" {{ {farfield} }}
}}
"""


def make_case(folder, mesh_path):
    """The case: the mesh through gmsh's format (gmshToFoam), its patches
    named after the surfaces' groups and ids, the dictionaries."""
    mesh = metrica.read(mesh_path)
    groups = surface_groups(mesh)
    os.makedirs(folder, exist_ok=True)
    msh = os.path.join(folder, "mesh.msh")
    run(os.environ.get("METRICA", "metrica"), "convert", mesh_path, msh, "--format-version", "2", "-q")
    # gmshToFoam names a patch after its physical group's name.
    text = open(msh).read()
    names = "".join(f'2 {s} "{g}_{s}"\n' for s, g in sorted(groups.items()))
    names += "".join(f'3 {r} "region_{r}"\n' for r in sorted(set(int(r) for r in mesh.tet_ids)))
    count = len(groups) + len(set(int(r) for r in mesh.tet_ids))
    text = text.replace("$EndMeshFormat\n", f"$EndMeshFormat\n$PhysicalNames\n{count}\n{names}$EndPhysicalNames\n", 1)
    # gmshToFoam orders the patches as their faces come: the triangles by
    # surface id, so that every iteration's case has its patches in the
    # same order (mapFields -consistent needs it).
    head, rest = text.split("$Elements\n", 1)
    body, tail = rest.split("$EndElements\n", 1)
    rows = [line.split() for line in body.splitlines()[1:]]
    rows.sort(key=lambda r: (r[1] != "2", int(r[3]) if r[1] == "2" else 0))
    lines = "".join(" ".join([str(i + 1)] + r[1:]) + "\n" for i, r in enumerate(rows))
    open(msh, "w").write(f"{head}$Elements\n{len(rows)}\n{lines}$EndElements\n{tail}")
    write(os.path.join(folder, "system", "controlDict"), control_dict(1))
    run("gmshToFoam", "mesh.msh", cwd=folder)
    os.remove(msh)
    boundary = os.path.join(folder, "constant", "polyMesh", "boundary")

    def typed(m):
        name, body = m.group(1), m.group(2)
        kind = {"symmetry": "symmetryPlane", "wing": "wall"}.get(name.split("_")[0], "patch")
        body = re.sub(r"\s*physicalType\s+\w+;", "", re.sub(r"type\s+\w+;", f"type {kind};", body))
        return f"{name}\n    {{{body}}}"

    write(boundary, re.sub(r"(\w+)\n    \{(.*?)\}", typed, open(boundary).read(), flags=re.S))
    write(os.path.join(folder, "constant", "thermophysicalProperties"), header("dictionary", "thermophysicalProperties") + f"""
thermoType
{{
    type hePsiThermo; mixture pureMixture; transport const; thermo hConst;
    equationOfState perfectGas; specie specie; energy sensibleInternalEnergy;
}}
mixture
{{
    specie {{ molWeight {MOL_WEIGHT}; }}
    thermodynamics {{ Cp {CP:.12g}; Hf 0; }}
    transport {{ mu {VISCOSITY:.12g}; Pr {PRANDTL}; }}
}}
""")
    write(os.path.join(folder, "constant", "turbulenceProperties"),
          header("dictionary", "turbulenceProperties") + "simulationType laminar;\n")
    u = vector(VELOCITY)
    write(os.path.join(folder, "0", "U"), field("U", "volVectorField", "[0 1 -1 0 0 0 0]", u, "type noSlip;",
                                                  f"type freestreamVelocity; freestreamValue uniform {u};"))
    write(os.path.join(folder, "0", "p"), field("p", "volScalarField", "[1 -1 -2 0 0 0 0]", PRESSURE,
                                                  "type zeroGradient;",
                                                  f"type freestreamPressure; freestreamValue uniform {PRESSURE};"))
    write(os.path.join(folder, "0", "T"), field("T", "volScalarField", "[0 0 0 1 0 0 0]", TEMPERATURE,
                                                  f"type fixedValue; value uniform {TEMPERATURE};",
                                                  f"type inletOutlet; inletValue uniform {TEMPERATURE}; "
                                                  f"value uniform {TEMPERATURE};"))
    # Gradients without a limiter (a limiter smears the leading-edge vortex:
    # the lift comes out far too high, docs/solver-loop.md); the
    # non-orthogonal correction limited to half its size, which keeps the
    # solve converging on stretched tets.
    write(os.path.join(folder, "system", "fvSchemes"), header("dictionary", "fvSchemes") + """
ddtSchemes { default steadyState; }
gradSchemes { default Gauss linear; }
divSchemes
{
    default none;
    div(phi,U) bounded Gauss linearUpwind grad(U);
    div(phi,e) bounded Gauss linearUpwind grad(e);
    div(phi,K) bounded Gauss linear;
    div(phi,Ekp) bounded Gauss linear;
    div(phid,p) Gauss upwind;
    div(((rho*nuEff)*dev2(T(grad(U))))) Gauss linear;
}
laplacianSchemes { default Gauss linear limited corrected 0.5; }
interpolationSchemes { default linear; }
snGradSchemes { default limited corrected 0.5; }
""")
    write(os.path.join(folder, "system", "fvSolution"), header("dictionary", "fvSolution") + """
solvers
{
    p { solver GAMG; smoother GaussSeidel; tolerance 1e-10; relTol 0.05; }
    "(U|e)" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-10; relTol 0.1; }
}
SIMPLE
{
    nNonOrthogonalCorrectors 2; consistent yes; transonic no; pMinFactor 0.5; pMaxFactor 2;
    residualControl { p 1e-7; U 1e-7; e 1e-7; }
}
relaxationFactors { fields { p 1; rho 1; } equations { U 0.9; e 0.9; } }
""")


def control_dict(iterations):
    """rhoSimpleFoam for `iterations` iterations at most (fewer when every
    initial residual is below fvSolution's 1e-7), the force coefficients at
    every iteration, the Mach number at the end."""
    return header("dictionary", "controlDict") + f"""
application rhoSimpleFoam;
startFrom latestTime; startTime 0; stopAt endTime; endTime {iterations}; deltaT 1;
writeControl timeStep; writeInterval {iterations}; writeFormat ascii; writePrecision 12; runTimeModifiable false;
functions
{{
    coefficients
    {{
        type forceCoeffs; libs ("libforces.so"); writeControl timeStep; writeInterval 1; log false;
        patches ("wing_.*"); rho rho; rhoInf {DENSITY:.12g}; magUInf {SPEED:.12g};
        pRef {PRESSURE};  // the wing's surface is open at the symmetry plane
        lRef {CHORD}; Aref {AREA}; CofR (0.25 0 0);
        liftDir {vector(LIFT)}; dragDir {vector(DRAG)}; pitchAxis (0 1 0);
    }}
    Mach {{ type MachNo; libs ("libfieldFunctionObjects.so"); executeControl writeTime; writeControl writeTime; }}
}}
"""


def forces(folder):
    """CD and CL of the last iteration (forceCoeffs' columns: Time Cd Cs Cl
    ...), and the largest relative change of either over the last 100
    iterations (over the second half of a solve of fewer than 200)."""
    path = os.path.join(folder, "postProcessing", "coefficients", "0", "coefficient.dat")
    rows = [line.split() for line in open(path) if line.strip() and not line.startswith("#")]
    if not rows:
        sys.exit(f"foam_case.py: {path} holds no iteration")
    cd, cl = float(rows[-1][1]), float(rows[-1][3])
    back = rows[max(len(rows) // 2, len(rows) - 101)]
    drift = max(abs(cd - float(back[1])) / abs(cd), abs(cl - float(back[3])) / abs(cl))
    return cd, cl, drift


def decompose_dict(processes):
    """The case cut into `processes` parts of equal cell counts along x, for
    `mpirun -np N rhoSimpleFoam -parallel` (Debian's OpenFOAM is built
    without scotch and metis: their methods are stubs)."""
    return header("dictionary", "decomposeParDict") + f"""numberOfSubdomains {processes};
method hierarchical;
hierarchicalCoeffs {{ n ({processes} 1 1); delta 0.001; order xyz; }}
"""


def mach(folder, mesh_path, out):
    """The Mach number at the vertices: OpenFOAM's cell values interpolated
    to the points (foamToVTK's point data), its points checked against the
    mesh's (gmshToFoam keeps the file's order)."""
    run("foamToVTK", "-latestTime", "-fields", "(Ma)", "-legacy", "-ascii", "-no-boundary", "-name", "VTK",
        cwd=folder)
    vtk = sorted(f for f in os.listdir(os.path.join(folder, "VTK")) if f.endswith(".vtk"))[-1]
    words = open(os.path.join(folder, "VTK", vtk)).read().split()
    n = int(words[words.index("POINTS") + 1])
    at = words.index("POINTS") + 3
    points = np.array(words[at:at + 3 * n], dtype=float).reshape(n, 3)
    data = words.index("POINT_DATA")
    ma = words.index("Ma", data)
    values = np.array(words[ma + 4:ma + 4 + n], dtype=float)
    mesh = metrica.read(mesh_path)
    if points.shape != mesh.points.shape or np.abs(points - mesh.points).max() > 1e-5:
        sys.exit("foam_case.py: OpenFOAM's points are not the mesh's vertices in order")
    metrica.write_field(out, values)


if __name__ == "__main__":
    command = sys.argv[1] if len(sys.argv) > 1 else ""
    if command == "case" and len(sys.argv) == 4:
        make_case(sys.argv[2], sys.argv[3])
    elif command == "control" and len(sys.argv) == 4:
        write(os.path.join(sys.argv[2], "system", "controlDict"), control_dict(int(sys.argv[3])))
    elif command == "forces" and len(sys.argv) == 3:
        print("%.8g %.8g %.3g" % forces(sys.argv[2]))
    elif command == "decompose" and len(sys.argv) == 4:
        write(os.path.join(sys.argv[2], "system", "decomposeParDict"), decompose_dict(int(sys.argv[3])))
    elif command == "mach" and len(sys.argv) == 5:
        mach(sys.argv[2], sys.argv[3], sys.argv[4])
    else:
        sys.exit(__doc__)
