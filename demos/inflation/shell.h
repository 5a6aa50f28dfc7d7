#pragma once
/// @file shell.h
/// A neo-Hookean spherical shell inflated by a cavity pressure: one octant with its symmetry
/// planes (meshes/sphere_shell.geo, forms/sphere.py), and the closed form of its
/// pressure-stretch law.

#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Function.h>
#include <gelx/boundary.h>
#include <gelx/constraints.h>
#include <gelx/forms.h>
#include <gelx/mesh.h>
#include <gelx/problem.h>
#include <memory>
#include <mpi.h>
#include <utility>

namespace gelx::scenes
{

struct ShellParameters
{
  double A = 1.0;    ///< inner radius
  double B = 1.25;   ///< outer radius
  double h = 0.125;  ///< mesh size
  double G = 1.0;    ///< shear modulus
  double K = 1000.0; ///< bulk modulus (K/G large: nearly incompressible)
  /// How the three symmetry planes hold the octant: "rollers" (Dirichlet conditions on the
  /// normal component) or "constraints" (gelx::MultipointConstraint::slip, the same condition
  /// through the reduced space: to show that continuation composes with constraints)
  std::string symmetry = "rollers";
};

class InflatedShell
{
public:
  InflatedShell(MPI_Comm comm, const std::string& geo_file, ShellParameters p);

  NonlinearProblem& problem() { return *_problem; }
  /// The system to solve: the problem, or its reduced space with the symmetry constraints.
  NonlinearSystem& system();
  const TaggedMesh& mesh() const { return _geo; }
  std::shared_ptr<dolfinx::fem::Function<double>> displacement() const { return _u; }

  /// Set the cavity pressure to p = lambda G.
  void set_load_factor(double lambda);

  /// Mean current radius of the inner-surface nodes over A: the inner hoop stretch.
  double inner_stretch() const;

  /// Incompressible closed form p(la) of the pressure at inner hoop stretch la:
  ///   p = 2G [(1/lb - 1/la) + (lb^-4 - la^-4)/4],  lb^3 = 1 + (la^3 - 1)(A/B)^3,
  /// from integrating dsigma_rr/dr = 2(sigma_tt - sigma_rr)/r across the wall.
  static double closed_form_pressure(const ShellParameters& p, double la);

  /// The maximum of closed_form_pressure: (stretch, pressure).
  static std::pair<double, double> closed_form_maximum(const ShellParameters& p);

private:
  ShellParameters _p;
  TaggedMesh _geo;
  std::shared_ptr<dolfinx::fem::Function<double>> _u;
  std::unique_ptr<FormBinding> _forms;
  std::unique_ptr<DirichletConditions> _bcs;
  std::unique_ptr<NonlinearProblem> _problem;
  std::unique_ptr<MultipointConstraint> _symmetry;
  std::vector<std::int32_t> _inner_nodes; // owned nodes on the inner surface
  std::vector<double> _X;                 // reference coordinates of the nodes
};

} // namespace gelx::scenes
