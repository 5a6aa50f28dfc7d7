#pragma once
/// @file shell.h
/// A Mooney-Rivlin (neo-Hookean by default) spherical shell inflated by a cavity pressure: one
/// octant with its symmetry planes (meshes/sphere_shell.geo) or a narrow sector
/// (meshes/sphere_sector.geo), forms/sphere.py, and the closed form of its pressure-stretch
/// law.

#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Function.h>
#include <gelx/systems/boundary.h>
#include <gelx/systems/constraints.h>
#include <gelx/systems/forms.h>
#include <gelx/io/mesh.h>
#include <gelx/systems/problem.h>
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
  double G = 1.0;    ///< initial shear modulus, G = 2 (C10 + C01)
  double K = 1000.0; ///< bulk modulus (K/G large: nearly incompressible)
  /// C01 / C10 of the Mooney-Rivlin law (0: neo-Hookean). Below about 0.21 the pressure of a
  /// thin shell rises, falls and rises again (an N-shaped law: a snap under pressure control)
  double C01_over_C10 = 0.0;
  double rho = 1.0; ///< mass density (damped dynamics only)
  double C10() const { return G / (2 * (1 + C01_over_C10)); }
  double C01() const { return C01_over_C10 * C10(); }
  /// How the symmetry planes x = 0, y = 0 (and z = 0) hold the body: "rollers" (Dirichlet
  /// conditions on the normal component) or "constraints" (gelx::MultipointConstraint::slip,
  /// the same condition through the reduced space: to show that continuation composes with
  /// constraints)
  std::string symmetry = "rollers";
  /// The part of the shell modelled: "octant" (meshes/sphere_shell.geo: three symmetry
  /// planes), "quarter" (the same file with lower = 1: x, y >= 0, two planes, so that modes
  /// odd in z, a pear shape, are free) or "sector" (meshes/sphere_sector.geo: 0 <= x, y <= t z,
  /// its inclined sides held by slip constraints), which carries only spherically symmetric
  /// deformations
  std::string domain = "octant";
  double t = 0.1; ///< the sector's half-width tan(angle) (domain "sector")
};

class InflatedShell
{
public:
  InflatedShell(MPI_Comm comm, const std::string& geo_file, ShellParameters p);

  NonlinearProblem& problem() { return *_problem; }
  /// The system to solve: the problem, or its reduced space with the symmetry constraints
  /// (the sector's sides always).
  NonlinearSystem& system();
  const TaggedMesh& mesh() const { return _geo; }
  std::shared_ptr<dolfinx::fem::Function<double>> displacement() const { return _u; }
  /// The Cauchy stress and the strain energy density, per cell (gelx::FieldSet output)
  std::shared_ptr<const dolfinx::fem::Expression<double>> stress() const;
  std::shared_ptr<const dolfinx::fem::Expression<double>> energy_density() const;

  /// Set the cavity pressure to p = lambda G.
  void set_load_factor(double lambda);

  /// Mean current radius of the inner surface's vertices over A: the inner hoop stretch.
  double inner_stretch() const;
  /// (largest - smallest) / mean of the inner surface's vertex radii: 0 for a sphere, a
  /// measure of how far the shell has left the spherical shape. Collective.
  double asphericity() const;

  /// The consistent mass matrix's form, rho inner(du, v) dx (gelx::DampedDynamics).
  std::shared_ptr<dolfinx::fem::Form<double>> mass_form() const;
  /// The stored energy of the octant at the current state. Collective.
  double strain_energy() const;

  /// Incompressible closed form p(la) of the pressure at inner hoop stretch la:
  ///   p = 4 C10 [(1/lb - 1/la) + (lb^-4 - la^-4)/4] + 4 C01 [(la - lb) + (lb^-2 - la^-2)/2],
  ///   lb^3 = 1 + (la^3 - 1)(A/B)^3,
  /// from integrating dsigma_rr/dr = 2(sigma_tt - sigma_rr)/r across the wall, where
  /// sigma_tt - sigma_rr = 2 (l^2 - l^-4)(C10 + C01 l^2) at hoop stretch l.
  static double closed_form_pressure(const ShellParameters& p, double la);

  /// The maximum of closed_form_pressure, the first one past la = 1: (stretch, pressure).
  static std::pair<double, double> closed_form_maximum(const ShellParameters& p);
  /// The minimum that follows it, when the law is N-shaped (Mooney-Rivlin with a small
  /// C01/C10): (stretch, pressure); NaNs when the pressure falls for ever (C01 = 0).
  static std::pair<double, double> closed_form_minimum(const ShellParameters& p);
  /// The stretch of pressure `pressure` on the branch past the minimum (the far stable branch
  /// a shell snaps to): the root of closed_form_pressure - pressure beyond the minimum.
  static double closed_form_far_stretch(const ShellParameters& p, double pressure);

private:
  ShellParameters _p;
  TaggedMesh _geo;
  std::shared_ptr<dolfinx::fem::Function<double>> _u;
  std::unique_ptr<FormBinding> _forms;
  std::unique_ptr<DirichletConditions> _bcs;
  std::unique_ptr<NonlinearProblem> _problem;
  std::unique_ptr<MultipointConstraint> _symmetry;
  /// The stored-energy functional, built once (DampedDynamics evaluates it every step)
  std::shared_ptr<dolfinx::fem::Form<double>> _strain_energy;
  std::vector<std::int32_t> _inner_nodes; // owned vertices of the inner surface
  /// The current radii of the inner surface's vertices, all ranks. Collective.
  struct InnerRadii
  {
    double smallest, largest, mean;
  };
  InnerRadii inner_radii() const;
  std::vector<double> _X;                 // reference coordinates of the nodes
};

} // namespace gelx::scenes
