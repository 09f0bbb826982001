// A full cylinder (radius 0.5, height 1) in OpenCASCADE: its lateral surface
// is periodic in u (seam: curve 2), its top and bottom circles are closed
// curves. Written for the tests of the geometry policy (seam handling).
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 0, 0, 1, 0.5, 2*Pi};
