#pragma once
/// @file pyramid.h
/// An elastomeric pyramid on its base pressed by a rigid substrate (thesis ch. 2): one quarter
/// of the unit cell (pyramid_mesh.h), incompressible neo-Hookean or Mooney-Rivlin in mixed u-p
/// form on Q2-Q1 hexahedra (forms/mixed_hex.py), frictionless contact with the plane
/// (gelx::RigidPlaneContact).

#include "pyramid_mesh.h"

#include <array>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <gelx/boundary.h>
#include <gelx/contact.h>
#include <gelx/problem.h>
#include <memory>
#include <vector>

namespace gelx::scenes
{

/// The contact at one indentation, for the whole pyramid (four quarters).
struct ContactMeasures
{
  double force = 0;        ///< compression force f (G times um^2: uN for G in MPa)
  double width = 0;        ///< contact width l_c: the patch's extent along a base edge
  double area = 0;         ///< contact area A_c
  std::int64_t active = 0; ///< nodes in contact (in the quarter)
  double penetration = 0;  ///< largest node distance behind the substrate
};

class PressedPyramid
{
public:
  /// Shear modulus G; mooney_share = C01 / (C10 + C01): 0 is neo-Hookean (Eq. 1.10), > 0 the
  /// incompressible Mooney-Rivlin solid with C10 + C01 = G/2 (chapter 2's constitutive check).
  PressedPyramid(MPI_Comm comm, const PyramidGeometry& geometry, double G, double mooney_share);

  double height() const { return _H; }
  NonlinearSystem& system() { return *_contact; }
  const TaggedMesh& mesh() const { return _mesh; }
  /// The mixed unknown (u, p)
  std::shared_ptr<dolfinx::fem::Function<double>> state() const { return _w; }

  /// Move the substrate by d toward the base from its first touch of the apex.
  void set_indentation(double d);

  /// Force, width, area, active set and penetration at the current state; refreshes
  /// displacement(). Collective.
  ContactMeasures measure();

  /// The contact nodes of all four quarters (x, y current, force), on rank 0 (others: empty).
  std::vector<std::array<double, 3>> patch() const;

  /// Cauchy stress expression (for gelx::CellField) and the displacement as a plain function.
  std::shared_ptr<const dolfinx::fem::Expression<double>> stress() const { return _stress; }
  std::shared_ptr<dolfinx::fem::Function<double>> displacement();

private:
  PyramidGeometry _g;
  double _H;
  TaggedMesh _mesh;
  std::shared_ptr<dolfinx::fem::Function<double>> _w, _u;
  std::unique_ptr<DirichletConditions> _bcs;
  std::unique_ptr<NonlinearProblem> _problem;
  std::unique_ptr<RigidPlaneContact> _contact;
  std::shared_ptr<const dolfinx::fem::Expression<double>> _stress;
  std::shared_ptr<dolfinx::fem::Form<double>> _area;
};

} // namespace gelx::scenes
