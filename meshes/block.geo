// Rectangular block W x W x H standing on z = 0, axis along z, centred on the z-axis.
// Parameters (override with gmsh -setnumber, or the scene's --width/--height/--h):
DefineConstant[ W = 1.0, H = 2.0, h = 0.25 ];
SetFactory("OpenCASCADE");
Box(1) = {-W/2, -W/2, 0, W, W, H};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
Mesh.Algorithm3D = 1; // Delaunay: deterministic, so runs on 1 and 2 ranks see the same mesh

// Faces of the OCC box: 5 is z = 0, 6 is z = H
Physical Volume("block", 1) = {1};
Physical Surface("bottom", 1) = {5};
Physical Surface("top", 2) = {6};
