// DERIVED FILE (not from a public repository): a hand transcription of
// UGAWG/solution-adapt-cases:delta-wing/geometry/delta.csm (OpenCSM) into a gmsh
// OpenCASCADE script, so the UGAWG / High-Order-Workshop delta wing can be used
// without ESP/EGADS.  Same numbers as the .csm:
//   farfield box  x in [-6.3694, 6.3694], y in [0, 5.3079], z in [-5.3079, 5.3079]
//   wing profile (csm sketch in xy, then rotatex 90 => lies in the xz-plane at y=0):
//     (0,0,0) (1,0,0) (1,0,-0.024416) (0.157828,0,-0.024416)   [top, back, bottom, bevel]
//   extruded along (1, 0.267949, 0) (75 deg swept leading edge), trimmed at x = 1,
//   then subtracted from the box (half model, symmetry plane y = 0).
// Root chord 1, half span 0.267949, planform area 0.133974596.
SetFactory("OpenCASCADE");
xd = 6.36942720413208008 + 6.36942720413208008;
yd = 5.30785608291625977;
zd = 5.30785608291625977 + 5.30785608291625977;
Box(1) = {-6.36942720413208008, 0, -5.30785608291625977, xd, yd, zd};

Point(101) = {0, 0, 0};
Point(102) = {1, 0, 0};
Point(103) = {1, 0, -0.0244161374866962433};
Point(104) = {0.157828390598297119, 0, -0.0244161374866962433};
Line(101) = {101, 102};
Line(102) = {102, 103};
Line(103) = {103, 104};
Line(104) = {104, 101};
Curve Loop(101) = {101, 102, 103, 104};
Plane Surface(101) = {101};
ext[] = Extrude {1, 0.267949223518371582, 0} { Surface{101}; };

Box(3) = {1, -1, -1, 2, 2, 2};
BooleanDifference(4) = { Volume{ext[1]}; Delete; }{ Volume{3}; Delete; };
BooleanDifference(5) = { Volume{1}; Delete; }{ Volume{4}; Delete; };

// The first mesh (metrica bootstrap) graded from the wing: gmsh's size field,
// sizes from 0.03 on the wing's faces to 1.5 four chords away.
wing() = Surface In BoundingBox{-0.01, -0.01, -0.03, 1.01, 0.28, 0.01};
Field[1] = Distance;
Field[1].FacesList = {wing()};
Field[1].NumPointsPerCurve = 40;
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.03;
Field[2].SizeMax = 1.5;
Field[2].DistMin = 0.02;
Field[2].DistMax = 4;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Physical Volume(1) = {5};
s() = Surface{:};
For i In {0:#s()-1}
  Physical Surface(s(i)) = {s(i)};
EndFor
