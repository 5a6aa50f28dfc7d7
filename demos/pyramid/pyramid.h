#pragma once
/// @file pyramid.h
/// An elastomeric pyramid on its base pressed by a rigid substrate (thesis ch. 2): one quarter
/// (or eighth, or half) of the unit cell (pyramid_mesh.h), an incompressible law in mixed u-p form on Q2-Q1
/// (forms/mixed_hex.py) or Q1-P0 hexahedra (forms/mixed_hex_q1.py), frictionless contact with
/// the plane (gelx::RigidPlaneContact).

#include "pyramid_mesh.h"

#include <array>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <gelx/systems/boundary.h>
#include <gelx/systems/constraints.h>
#include <gelx/systems/contact.h>
#include <gelx/io/output.h>
#include <gelx/systems/problem.h>
#include <memory>
#include <string>
#include <vector>

namespace gelx::scenes
{

/// The contact at one indentation, for the whole pyramid.
struct ContactMeasures
{
  double force = 0;        ///< compression force f (G times um^2: uN for G in MPa)
  double width = 0;        ///< contact width l_c: the patch's extent along a base edge
  /// l_c with the corner located by the gap's 3/2 law beyond it (converges faster)
  double width_gap_law = 0;
  double area = 0;         ///< contact area A_c
  std::int64_t active = 0; ///< nodes in contact (in the modelled part)
  double penetration = 0;  ///< largest node distance behind the substrate
};

/// The elastomer: an incompressible law of forms/_mixed.py and its element.
struct PyramidMaterial
{
  /// "nh" neo-Hookean (Eq. 1.10), "mr" Mooney-Rivlin, "le" small-strain linear elasticity
  /// (chapter 2's constitutive check)
  std::string law = "nh";
  double G = 1.0;            ///< initial shear modulus (MPa)
  double mooney_share = 0.5; ///< Mooney-Rivlin C01 / (C10 + C01), with C10 + C01 = G/2
  int order = 1;             ///< displacement degree: 1 (Q1-P0) or 2 (Q2-Q1)
};

/// The pyramid on the domain of PyramidGeometry::domain with its symmetry conditions: zero
/// normal displacement on the mirror planes x = 0, y = 0 and x, y = W/2 of the periodic array
/// (Dirichlet rollers), and on the eighth's diagonal plane x = y, which is not axis-aligned,
/// frictionless slip u.n = 0 (gelx::MultipointConstraint::slip); the contact acts on that
/// constrained system.
class PressedPyramid
{
public:
  PressedPyramid(MPI_Comm comm, const PyramidGeometry& geometry,
                 const PyramidMaterial& material);

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

  /// The stored energy of the whole pyramid (the modelled part times its images), in the units
  /// of force times length. Collective.
  double strain_energy() const;

  /// The candidate nodes of the whole pyramid (current x, y, contact force, 1 in contact or
  /// 0) within twice the patch's reach of the axis, on rank 0 (others: empty): a pressure map
  /// that shows the patch's edges between contact and free nodes, at the last measure(). Each
  /// node appears once, with its force in the whole pyramid (on a mirror plane: the forces of
  /// the parts that share it).
  /// Collective.
  std::vector<std::array<double, 4>> patch() const;

  /// The deformed lateral faces of the whole pyramid (the modelled part and its images), from
  /// the vertex displacement u_p1, on rank 0 (for STL). Collective.
  std::vector<Triangle> contact_side_surface(const dolfinx::fem::Function<double>& u_p1) const;

  /// Cauchy stress expression (for gelx::CellField) and the displacement as a plain function.
  std::shared_ptr<const dolfinx::fem::Expression<double>> stress() const { return _stress; }
  /// The strain energy density per cell (gelx::CellField)
  std::shared_ptr<const dolfinx::fem::Expression<double>> energy_density() const
  {
    return _energy_density;
  }
  std::shared_ptr<dolfinx::fem::Function<double>> displacement();
  /// The contact status, gap and force at the candidate vertices (RigidPlaneContact::
  /// state_fields), at the last measure().
  std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>> contact_fields() const
  {
    return _contact->state_fields();
  }

private:
  /// A reflection (or the identity) that maps the modelled part onto part of the whole pyramid:
  /// (x, y) -> (sx x, sy y), after swapping x and y (the reflection in x = y) if `swap`.
  struct Image
  {
    bool swap;
    double sx, sy;
    std::array<double, 2> operator()(double x, double y) const
    {
      return swap ? std::array<double, 2>{sx * y, sy * x} : std::array<double, 2>{sx * x, sy * y};
    }
    /// Whether it reverses orientation (turns a triangle inside out)
    bool reflects() const { return (sx * sy < 0) != swap; }
  };
  static std::vector<Image> images(const std::string& domain);

  PyramidGeometry _g;
  double _H;
  std::vector<Image> _images;
  TaggedMesh _mesh;
  std::shared_ptr<dolfinx::fem::Function<double>> _w, _u;
  std::unique_ptr<DirichletConditions> _bcs;
  std::unique_ptr<NonlinearProblem> _problem;
  std::unique_ptr<MultipointConstraint> _diagonal_slip; ///< the eighth's only
  std::unique_ptr<RigidPlaneContact> _contact;
  std::shared_ptr<const dolfinx::fem::Expression<double>> _stress, _energy_density;
  std::shared_ptr<dolfinx::fem::Form<double>> _area, _energy;
};

} // namespace gelx::scenes
