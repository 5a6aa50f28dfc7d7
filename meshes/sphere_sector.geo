// A narrow sector of a spherical shell, inner radius A, outer radius B: the part with
// 0 <= x <= t z and 0 <= y <= t z (a square pyramid of half-angle atan t about the z axis,
// its apex at the centre). Every plane through the centre is a symmetry plane of a spherically
// symmetric deformation, so the sector carries it with slip on its four sides: the octant's
// answer on a fraction t^2 / (pi / 2) of its volume, meshed that much finer for the same cost.
// Parameters (gmsh -setnumber, or a scene's options): A, B, mesh size h, t.
DefineConstant[ A = 1.0, B = 1.25, h = 0.04, t = 0.1 ];
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, B};
Sphere(2) = {0, 0, 0, A};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
H = 2 * B;
Point(101) = {0, 0, 0};
Point(102) = {0, 0, H};
Point(103) = {t * H, 0, H};
Point(104) = {t * H, t * H, H};
Point(105) = {0, t * H, H};
Line(101) = {101, 102}; Line(102) = {101, 103}; Line(103) = {101, 104}; Line(104) = {101, 105};
Line(105) = {102, 103}; Line(106) = {103, 104}; Line(107) = {104, 105}; Line(108) = {105, 102};
Curve Loop(101) = {101, 105, -102}; Plane Surface(101) = {101};
Curve Loop(102) = {102, 106, -103}; Plane Surface(102) = {102};
Curve Loop(103) = {103, 107, -104}; Plane Surface(103) = {103};
Curve Loop(104) = {104, 108, -101}; Plane Surface(104) = {104};
Curve Loop(105) = {105, 106, 107, 108}; Plane Surface(105) = {105};
Surface Loop(101) = {101, 102, 103, 104, 105};
Volume(4) = {101};
BooleanIntersection(5) = { Volume{3}; Delete; }{ Volume{4}; Delete; };
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
Mesh.Algorithm3D = 1;

// Faces by bounding box: the inner patch lies within r <= A; the planes x = 0 and y = 0 in
// boxes of zero width; the inclined sides are the only faces whose x (resp. y) stays above
// t z_min > 0, z_min = A / sqrt(1 + 2 t^2) their lowest point
e = 1e-6 * B;
s = 0.5 * t * A / Sqrt(1 + 2 * t * t);
inner() = Surface In BoundingBox{-e, -e, -e, A + e, A + e, A + e};
sym_x() = Surface In BoundingBox{-e, -e, -e, e, B + e, B + e};
sym_y() = Surface In BoundingBox{-e, -e, -e, B + e, e, B + e};
side_x() = Surface In BoundingBox{s, -e, -e, B + e, B + e, B + e};
side_y() = Surface In BoundingBox{-e, s, -e, B + e, B + e, B + e};
Physical Volume("shell", 1) = {5};
Physical Surface("inner", 1) = {inner()};
Physical Surface("sym_x", 2) = {sym_x()};
Physical Surface("sym_y", 3) = {sym_y()};
Physical Surface("side_x", 4) = {side_x()};
Physical Surface("side_y", 5) = {side_y()};
