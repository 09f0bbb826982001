// Schäfer-Turek 3D-1Z (DFG benchmark "flow around a cylinder", steady, Re = 20):
// the channel [0, 2.5] x [0, 0.41] x [0, 0.41] less a cylinder of diameter 0.1
// with its axis along z through (0.5, 0.2), on the OpenCASCADE kernel.
// Surface tags (gmsh 4.8's numbering after the boolean difference, which the
// FreeFEM script uses as labels): 1 inlet x = 0, 6 outlet x = 2.5,
// 2-5 channel walls, 7 cylinder.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2.5, 0.41, 0.41};
Cylinder(2) = {0.5, 0.2, 0, 0, 0, 0.41, 0.05, 2*Pi};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
