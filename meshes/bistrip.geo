// The bistrip of thesis chapter 3 (Fig. 3.1b, Fig. 3.10a) in its bonded state: strip B
// (lower, stress-free) has the cross-section w x h; strip A (upper) was stretched by lambda
// along its length before bonding, so its cross-section has shrunk to (lt w) x (lt h), lt the
// lateral stretch of that uniaxial stretch. Both are L long along z; A sits centred on B's top
// face y = 0, the two glued by a conforming mesh. Structured hexahedra: the cross-section's
// quadrilaterals extruded in nz layers, so that the slabs of thesis Fig. 3.4b are the cell
// layers.
// Cross-section cells: nx across A's width (and B under it), ns across each of B's two
// overhangs, nb through B's thickness, na through A's.
DefineConstant[ w = 5, h = 3, L = 300, lt = 0.566, nz = 100, nx = 2, ns = 1, nb = 1, na = 1 ];
wa = lt * w;
ha = lt * h;
Point(1) = {-w / 2, -h, 0};
Point(2) = {-wa / 2, -h, 0};
Point(3) = {wa / 2, -h, 0};
Point(4) = {w / 2, -h, 0};
Point(5) = {-w / 2, 0, 0};
Point(6) = {-wa / 2, 0, 0};
Point(7) = {wa / 2, 0, 0};
Point(8) = {w / 2, 0, 0};
Point(9) = {-wa / 2, ha, 0};
Point(10) = {wa / 2, ha, 0};
// Across: B's bottom, B's top (A's bottom), A's top
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4};
Line(4) = {5, 6}; Line(5) = {6, 7}; Line(6) = {7, 8};
Line(7) = {9, 10};
// Through the thickness: B's four verticals, A's two
Line(8) = {1, 5}; Line(9) = {2, 6}; Line(10) = {3, 7}; Line(11) = {4, 8};
Line(12) = {6, 9}; Line(13) = {7, 10};
Curve Loop(1) = {1, 9, -4, -8}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 10, -5, -9}; Plane Surface(2) = {2};
Curve Loop(3) = {3, 11, -6, -10}; Plane Surface(3) = {3};
Curve Loop(4) = {5, 13, -7, -12}; Plane Surface(4) = {4};
Transfinite Curve{1, 3, 4, 6} = ns + 1;
Transfinite Curve{2, 5, 7} = nx + 1;
Transfinite Curve{8, 9, 10, 11} = nb + 1;
Transfinite Curve{12, 13} = na + 1;
Transfinite Surface{1, 2, 3, 4};
Recombine Surface{1, 2, 3, 4};
b1[] = Extrude {0, 0, L} { Surface{1}; Layers{nz}; Recombine; };
b2[] = Extrude {0, 0, L} { Surface{2}; Layers{nz}; Recombine; };
b3[] = Extrude {0, 0, L} { Surface{3}; Layers{nz}; Recombine; };
a[] = Extrude {0, 0, L} { Surface{4}; Layers{nz}; Recombine; };
// Extrude returns the top surface first, then the volume
Physical Volume("A", 1) = {a[1]};
Physical Volume("B", 2) = {b1[1], b2[1], b3[1]};
Physical Surface("fixed", 1) = {1, 2, 3, 4};
Physical Surface("moving", 2) = {b1[0], b2[0], b3[0], a[0]};
