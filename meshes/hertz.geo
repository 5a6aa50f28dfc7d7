// A spherical cap of radius R (centre (0, 0, R), apex at the origin, height R/2) on a block of
// width and depth L = 4R (its top face z = R/2 + L): a body that looks like Hertz's half-space
// from the contact, for contact with the plane z = d. One quarter (x, y >= 0; quarters = 1),
// one half (y >= 0; quarters = 2) or all of it (quarters = 4).
// Graded: size h_contact within r_contact of the apex, growing linearly to h over another
// 2 r_contact. Parameters (gmsh -setnumber, or a program's options): R, L, h, h_contact,
// r_contact, quarters.
DefineConstant[ R = 1.0, L = 4.0, h = 0.5, h_contact = 0.02, r_contact = 0.25, quarters = 1 ];
SetFactory("OpenCASCADE");
cap = 0.5 * R;
Sphere(1) = {0, 0, R, R};
Box(2) = {-R, -R, 0, 2 * R, 2 * R, cap};
BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(4) = {-L, -L, cap, 2 * L, 2 * L, L};
BooleanUnion(5) = { Volume{3}; Delete; }{ Volume{4}; Delete; };
If (quarters == 1)
  Box(6) = {0, 0, 0, L, L, cap + L};
ElseIf (quarters == 2)
  Box(6) = {-L, 0, 0, 2 * L, L, cap + L};
Else
  Box(6) = {-L, -L, 0, 2 * L, 2 * L, cap + L};
EndIf
BooleanIntersection(7) = { Volume{5}; Delete; }{ Volume{6}; Delete; };

Field[1] = MathEval;
Field[1].F = Sprintf("%g + %g * min(1, max(0, (sqrt(x*x + y*y + z*z) - %g) / %g))",
                     h_contact, h - h_contact, r_contact, 2 * r_contact);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm3D = 1;

e = 1e-6 * R;
sym_x() = Surface In BoundingBox{-e, -e, -e, e, L + e, cap + L + e};
sym_y() = Surface In BoundingBox{-L - e, -e, -e, L + e, e, cap + L + e};
top() = Surface In BoundingBox{-L - e, -L - e, cap + L - e, L + e, L + e, cap + L + e};
cap_surface() = Surface In BoundingBox{-R - e, -R - e, -e, R + e, R + e, cap + e};
contact() = cap_surface();
If (quarters <= 2)
  contact() -= {sym_y()};
  Physical Surface("sym_y", 4) = {sym_y()};
EndIf
If (quarters == 1)
  contact() -= {sym_x()};
  Physical Surface("sym_x", 3) = {sym_x()};
EndIf
Physical Volume("body", 1) = {7};
Physical Surface("contact", 1) = {contact()};
Physical Surface("top", 2) = {top()};
