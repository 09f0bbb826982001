"""CD and CL of the delta wing against the vertex count: the adaptive loop
(examples/openfoam/run's history.csv) and, when given, the meshes that are
not adapted (examples/openfoam/uniform's uniform.csv), with the seed's
final values drawn in and the 1% band around them.

    /usr/bin/python3 examples/openfoam/plot.py HISTORY.csv [UNIFORM.csv] -o PLOT.png

Needs matplotlib (scripts/setup --examples).
"""
import argparse
import csv
import sys

REFERENCES = {"cd": 0.165396, "cl": 0.346937}


def rows(path):
    with open(path) as f:
        table = list(csv.DictReader(f))
    for key in ("vertices", "cd", "cl"):
        if not table or key not in table[0]:
            sys.exit(f"plot.py: {path} has no column {key}")
    return [(int(r["vertices"]), float(r["cd"]), float(r["cl"])) for r in table]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("history")
    parser.add_argument("uniform", nargs="?")
    parser.add_argument("-o", "--output", default="delta-wing.png")
    args = parser.parse_args()
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        sys.exit("plot.py: needs matplotlib (scripts/setup --examples installs python3-matplotlib)")
    series = [("adapted (Metrica)", rows(args.history), "o-")]
    if args.uniform:
        series.append(("not adapted (gmsh, graded field scaled)", rows(args.uniform), "s--"))
    figure, axes = plt.subplots(1, 2, figsize=(10, 4))
    for axis, (column, name) in zip(axes, ((1, "cd"), (2, "cl"))):
        reference = REFERENCES[name]
        axis.axhspan(0.99 * reference, 1.01 * reference, color="0.9", label="reference ±1%")
        axis.axhline(reference, color="k", lw=0.8, label=f"reference {reference}")
        for label, table, style in series:
            axis.plot([r[0] for r in table], [r[column] for r in table], style, label=label)
        axis.set_xscale("log")
        axis.set_xlabel("vertices")
        axis.set_ylabel(name.upper())
        axis.grid(True, which="both", lw=0.3)
    axes[0].legend(fontsize=8)
    figure.suptitle("Laminar delta wing, Mach 0.3, 12.5°, Re 4,000: rhoSimpleFoam")
    figure.tight_layout()
    figure.savefig(args.output, dpi=120)
    print(f"plot.py: wrote {args.output}")


if __name__ == "__main__":
    main()
