// A torus (major radius 0.3, minor radius 0.12) centred in the unit cube:
// a curved boundary for adaptations without a model.
SetFactory("OpenCASCADE");
Torus(1) = {0.5, 0.5, 0.5, 0.3, 0.12};
