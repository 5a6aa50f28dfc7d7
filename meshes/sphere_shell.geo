// One octant of a spherical shell, inner radius A, outer radius B, with its three symmetry
// planes; or, with lower = 1, the quarter x, y >= 0 (the octant and its mirror image below
// z = 0: two symmetry planes). Parameters (gmsh -setnumber, or a scene's options): A, B, mesh
// size h, lower.
DefineConstant[ A = 1.0, B = 1.25, h = 0.1, lower = 0 ];
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, B};
Sphere(2) = {0, 0, 0, A};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(4) = {0, 0, -2 * B * lower, 2 * B, 2 * B, 2 * B * (1 + lower)};
BooleanIntersection(5) = { Volume{3}; Delete; }{ Volume{4}; Delete; };
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
Mesh.Algorithm3D = 1;

e = 1e-6 * B;
z0 = -(A + e) * lower - e;
inner() = Surface In BoundingBox{-e, -e, z0, A + e, A + e, A + e};
z0 = -(B + e) * lower - e;
sym_x() = Surface In BoundingBox{-e, -e, z0, e, B + e, B + e};
sym_y() = Surface In BoundingBox{-e, -e, z0, B + e, e, B + e};
sym_z() = Surface In BoundingBox{-e, -e, -e, B + e, B + e, e};
Physical Volume("shell", 1) = {5};
Physical Surface("inner", 1) = {inner()};
Physical Surface("sym_x", 2) = {sym_x()};
Physical Surface("sym_y", 3) = {sym_y()};
If (lower == 0)
  Physical Surface("sym_z", 4) = {sym_z()};
EndIf
