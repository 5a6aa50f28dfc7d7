"""The discrete inf-sup test of the Q1-P0 pair (the element of forms/mixed_hex_q1.py): the
operators of the pressure Schur complement S = B A^-1 B^T and of the pressure mass M.

A is the vector Laplacian (the H1 seminorm of the displacement), B the divergence (q, div v),
M = diag(cell volumes). beta_h^2 is the smallest eigenvalue of S q = lambda M q; a pressure
with B^T q = 0, invisible to the momentum balance (a spurious mode), has lambda = 0.
"""
import ufl

cell = "hexahedron"
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 1))
Q = ufl.FunctionSpace(mesh, ufl.FiniteElement("DG", cell, 0))
u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
q = ufl.TestFunction(Q)

vector_laplacian = ufl.inner(ufl.grad(u), ufl.grad(v)) * ufl.dx
divergence = q * ufl.div(u) * ufl.dx
cell_volume = q * ufl.dx
forms = [vector_laplacian, divergence, cell_volume]
