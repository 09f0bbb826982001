// A unit cube with a sphere of radius 0.3 at its centre: two volumes
// (BooleanFragments) with the sphere as the surface between them.
// Regions: 2 outside the sphere, 3 inside; surface ids: 100 for the
// sphere, each face of the cube its own entity tag.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Sphere(2) = {0.5, 0.5, 0.5, 0.3};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Mesh.CharacteristicLengthMax = 0.25;
inner() = Volume In BoundingBox{0.19, 0.19, 0.19, 0.81, 0.81, 0.81};
sphere() = Surface In BoundingBox{0.19, 0.19, 0.19, 0.81, 0.81, 0.81};
all() = Volume{:};
outer() = Surface{:};
outer() -= sphere();
all() -= inner();
Physical Volume(3) = {inner()};
Physical Volume(2) = {all()};
Physical Surface(100) = {sphere()};
For i In {0:#outer()-1}
  Physical Surface(outer(i)) = {outer(i)};
EndFor
