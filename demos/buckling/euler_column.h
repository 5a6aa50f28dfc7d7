#pragma once
/// @file euler_column.h
/// A slender 3-D column of compressible neo-Hookean solid (forms/column.py) under axial
/// compression: Euler's critical loads and the elastica, its post-buckling closed form.

#include <array>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <gelx/systems/boundary.h>
#include <gelx/solvers/buckling.h>
#include <gelx/io/mesh.h>
#include <gelx/io/parameters.h>
#include <gelx/solvers/path.h>
#include <gelx/systems/problem.h>
#include <map>
#include <memory>
#include <mpi.h>
#include <ufcx.h>
#include <string>
#include <vector>

namespace gelx::scenes
{

struct ColumnParameters
{
  double tx = 1.0;  ///< cross-section width along x (tx < ty: the column buckles in x)
  double ty = 1.5;  ///< cross-section depth along y
  double L = 30.0;  ///< length along z
  std::array<int, 3> cells{2, 3, 40}; ///< box cells along x, y, z (six tetrahedra each)
  double G = 1.0;   ///< shear modulus
  double nu = 0.3;  ///< Poisson's ratio (bulk modulus K = 2G(1 + nu)/(3(1 - 2nu)))
  double rho = 1.0; ///< mass density (damped dynamics only)
  std::string ends = "clamped-free"; ///< or "clamped-clamped"
  /// "clamped" (u = 0) or "sliding": the end z = 0 slides in its plane (u_z = 0; u_x = 0 on
  /// its mid-line x = tx/2 and u_y = 0 on y = ty/2 pin the rigid motions), so that its
  /// Poisson expansion is free and the straight column is a homogeneous state, which the mesh
  /// represents exactly: the perfect column stays straight past its critical loads. The
  /// clamped end holds the expansion back, and on the box mesh, not mirror-symmetric, that acts
  /// as a small imperfection: the straight path bends over at P_cr. Either end is clamped
  /// against rotation.
  std::string base = "clamped";
  /// "neo_hookean" (Eq. 3.1) or "linear_elastic" (small strain, the same G and nu: a linear
  /// problem, for the tests of time integrators; the scene's stress and energy-density
  /// fields are neo-Hookean's, so it is not a scene parameter)
  std::string law = "neo_hookean";
  bool clamped_clamped() const { return ends == "clamped-clamped"; }
  /// Bind the members but rho to scene parameters (sections "geometry" and "material"), the
  /// current values as their defaults.
  void bind(Parameters& prm);
  /// Throws InputError unless ty > tx (the column must buckle in x).
  void check() const;
};

/// The column on [0, tx] x [0, ty] x [0, L], clamped at z = 0.
///
/// Clamped-free: a dead axial traction loads the free end z = L (effective length 2L).
/// Clamped-clamped: the end z = L is held laterally and shortened by a prescribed uniform u_z,
/// which also keeps it from rotating (effective length L/2).
/// Load factors are measured in Euler loads: lambda = 1 is P = pi^2 E I / (K L)^2 (a traction
/// lambda times that over the area, or the shortening that carries it in the straight column).
class EulerColumn
{
public:
  EulerColumn(MPI_Comm comm, ColumnParameters p);

  NonlinearProblem& problem() { return *_problem; }
  const TaggedMesh& mesh() const { return _box; }
  std::shared_ptr<dolfinx::fem::Function<double>> displacement() const { return _u; }
  /// The Cauchy stress and the strain energy density, per cell (gelx::FieldSet output)
  std::shared_ptr<const dolfinx::fem::Expression<double>> stress() const;
  std::shared_ptr<const dolfinx::fem::Expression<double>> energy_density() const;
  double youngs_modulus() const { return 2 * _p.G * (1 + _p.nu); }
  /// Slenderness K L / r, r = tx / sqrt(12) the radius of gyration about the buckling axis.
  double slenderness() const;

  /// Euler's critical load pi^2 E I / (K L)^2, I = ty tx^3 / 12.
  double euler_load() const;

  /// Set the load to lambda Euler loads (traction, or prescribed shortening).
  void set_load_factor(double lambda);

  /// The compressive axial force the column carries now (force units): the reaction on the
  /// clamped end z = 0, which carries the whole load in either set-up. Collective.
  double axial_force() const;

  /// Linear buckling about the unloaded state (thesis Eq. 1.13, gelx::LinearBuckling): the
  /// `num_modes` lowest modes, their load factors in Euler loads. Leaves the column unloaded.
  std::vector<BucklingMode> buckling_modes(int num_modes);

  /// The consistent mass matrix's form, rho inner(du, v) dx (gelx::DampedDynamics).
  std::shared_ptr<dolfinx::fem::Form<double>> mass_form() const;
  /// The strain energy stored in the column now, int psi dx. Collective.
  double strain_energy() const;

  /// The largest lateral (x) displacement of the column over L.
  double lateral_deflection() const;
  /// The lateral displacement (x, y) of the loaded end z = L over L, signed (the middle of its
  /// range over that face). Collective.
  std::array<double, 2> tip_deflection() const;
  /// The potential energy of the elastic column and its dead load. Collective.
  double potential_energy() const;
  /// A lateral displacement along `axis` (0: x, 1: y) growing as (z/L)^2 to `tip` at the
  /// free end, in the layout of problem().create_vector(): it breaks the straight column's
  /// symmetry (deflation's initial guesses; Newton's step keeps a straight column straight).
  OwnedVec lateral_perturbation(int axis, double tip) const;

  /// P / P_cr of the elastica (inextensible Euler-Bernoulli beam) at lateral deflection d/L:
  /// the tip deflection of a cantilever; for clamped ends, each quarter of the column is a
  /// cantilever of length L/4 whose tip deflection is half the mid-span deflection.
  double elastica_load_ratio(double deflection_over_L) const;

  /// Symmetry of a mode's lateral deflection v_x about mid-length: |int v_x (z - L/2)| /
  /// int |v_x (z - L/2)| (odd part) and |int v_x| / int |v_x| (even part), each in [0, 1].
  std::array<double, 2> mode_odd_even_parts(
      std::shared_ptr<const dolfinx::fem::Function<double>> mode) const;

private:
  bool linear() const { return _p.law == "linear_elastic"; }
  std::shared_ptr<dolfinx::fem::Form<double>>
  form(ufcx_form* f, std::vector<std::shared_ptr<const dolfinx::fem::FunctionSpace>> spaces,
       std::shared_ptr<const dolfinx::fem::Function<double>> mode = nullptr) const;

  ColumnParameters _p;
  TaggedMesh _box;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> _load_facets; // ds(2): the top end
  std::shared_ptr<dolfinx::fem::Function<double>> _u;
  std::shared_ptr<dolfinx::fem::Constant<double>> _traction;
  std::map<std::string, std::shared_ptr<const dolfinx::fem::Constant<double>>> _constants;
  std::unique_ptr<DirichletConditions> _bcs;
  std::unique_ptr<NonlinearProblem> _problem;
};

} // namespace gelx::scenes
