// Verification: effective stiffness of a periodic two-phase laminate (gelx::MultipointConstraint
// with macro unknowns).
//
// A unit cube of two layers normal to z, phase 1 (G1 = 1, K1 = 3) for z < f1 = 0.25 and phase 2
// (G2 = 10, K2 = 20) above, moduli per cell (forms/mpc_laminate.py), P1 on 2 x 2 x 4 boxes of
// six tetrahedra, so the interface lies on mesh facets. Periodic on all three face pairs with
// the nine macro unknowns U_ij = (F - I)_ij L_j of tests/mpc_homogeneous_cell.cpp (lower ones
// zero, upper shear ones free and unloaded), the corner X = 0 pinned. With P-wave modulus
// M = K + 4G/3 and Lame lambda = K - 2G/3 per phase, the exact laminate (layer-wise uniform
// strain, which P1 contains) gives
//  * across the layers, macro strain eps_zz with no lateral strain (U_xx = U_yy = 0): sigma_zz
//    is continuous, so C_zz = 1 / (f1/M1 + f2/M2) (harmonic, Reuss-type);
//  * along the layers, eps_xx with eps_yy = 0 and U_zz free (zero macro sigma_zz): every layer
//    has the same eps_xx and sigma_zz = 0, so C_xx = sum f_i (M_i - lambda_i^2 / M_i)
//    (arithmetic, Voigt-type) and U_zz / L = -eps_xx sum f_i lambda_i / M_i.
// The macro stress is the macro force of the prescribed U over the face area. Small-strain
// linear elasticity must reproduce these to round-off; neo-Hookean at eps = 1e-4 within
// 5e-4 relative: its finite-strain terms are O(eps) relative (measured 0.8 eps across and
// 1.1 eps along the layers). Finite strain, neo-Hookean, stretch 1.3 across the layers:
// each layer is homogeneous in uniaxial strain, F_i = diag(1, 1, lambda_i), with equal nominal
// stress P_zz(lambda_1) = P_zz(lambda_2) and f1 lambda_1 + f2 lambda_2 = 1.3 (bisection): the
// macro force and the piecewise-linear displacement to round-off. At 1 and 2 ranks.

#include "mpc_laminate.h"
#include "support.h"

#include <cmath>
#include <dolfinx/fem/utils.h>
#include <gelx/systems/constraints.h>
#include <gelx/solvers/load_stepping.h>
#include <gelx/systems/problem.h>
#include <gelx/common/petsc_utils.h>
#include <petscsys.h>
#include <xtensor/xtensor.hpp>

using namespace dolfinx;

namespace
{
struct Phase
{
  double G, K;
  double M() const { return K + 4 * G / 3; }
  double lame() const { return K - 2 * G / 3; }
  /// Nominal stress of Eq. 3.1 in uniaxial strain F = diag(1, 1, stretch)
  double uniaxial_strain_stress(double stretch) const
  {
    const double J = stretch, I1 = 2 + stretch * stretch;
    return G * std::pow(J, -5.0 / 3.0) * (stretch * stretch - I1 / 3) + K * (J - 1);
  }
};
const Phase soft{1, 3}, stiff{10, 20};
constexpr double f1 = 0.25, f2 = 1 - f1;

enum class Law
{
  linear,
  neo_hookean
};

struct Laminate
{
  std::shared_ptr<fem::FunctionSpace> V;
  std::shared_ptr<fem::Function<double>> u;
  std::unique_ptr<gelx::NonlinearProblem> problem;
  std::unique_ptr<gelx::MultipointConstraint> mpc;
  std::array<std::array<int, 3>, 3> U;
};

/// Cell-wise modulus: the phase's value at the cell midpoint (z below or above f1).
std::shared_ptr<fem::Function<double>> modulus(std::shared_ptr<mesh::Mesh> mesh,
                                               double below, double above)
{
  auto Q = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_mpc_laminate_residual_nh, "G", mesh));
  auto f = std::make_shared<fem::Function<double>>(Q);
  f->interpolate(
      [&](const xt::xtensor<double, 2>& x) -> xt::xarray<double>
      {
        xt::xarray<double> values = xt::zeros<double>({x.shape(1)});
        for (std::size_t i = 0; i < x.shape(1); ++i)
          values(i) = x(2, i) < f1 ? below : above;
        return values;
      });
  return f;
}

Laminate laminate(MPI_Comm comm, Law law)
{
  auto box = gelx::test::tagged_box(comm, {1, 1, 1}, {2, 2, 4});
  Laminate cell;
  cell.V = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_mpc_laminate_residual_nh, "u", box.mesh));
  cell.u = std::make_shared<fem::Function<double>>(cell.V);
  const std::map<std::string, std::shared_ptr<const fem::Function<double>>> coefficients
      = {{"u", cell.u},
         {"G", modulus(box.mesh, soft.G, stiff.G)},
         {"K", modulus(box.mesh, soft.K, stiff.K)}};
  const bool linear = law == Law::linear;
  auto residual = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      linear ? *form_mpc_laminate_residual_le : *form_mpc_laminate_residual_nh, {cell.V},
      coefficients, {}, {}));
  auto tangent = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      linear ? *form_mpc_laminate_tangent_le : *form_mpc_laminate_tangent_nh, {cell.V, cell.V},
      coefficients, {}, {}));

  std::vector<std::int32_t> corner = fem::locate_dofs_geometrical(
      *cell.V, [](const xt::xtensor<double, 2>& x)
      { return xt::eval(xt::sqrt(xt::sum(x * x, {0})) < 1e-10); });
  auto pin = std::make_shared<fem::DirichletBC<double>>(
      std::make_shared<fem::Constant<double>>(std::vector<double>{0, 0, 0}), std::move(corner),
      cell.V);
  cell.problem = std::make_unique<gelx::NonlinearProblem>(cell.u, residual, tangent,
                                                          gelx::NonlinearProblem::BCs{pin});
  cell.mpc = std::make_unique<gelx::MultipointConstraint>(*cell.problem, cell.V);
  for (auto& row : cell.U)
    for (int& k : row)
      k = cell.mpc->add_macro();
  using namespace gelx::test;
  const std::array<std::pair<int, int>, 3> pairs
      = {{{x_min, x_max}, {y_min, y_max}, {z_min, z_max}}};
  for (int j = 0; j < 3; ++j)
  {
    std::array<double, 3> offset = {0, 0, 0};
    offset[j] = 1;
    cell.mpc->periodic(*box.facets, pairs[j].first, pairs[j].second, offset,
                       {cell.U[0][j], cell.U[1][j], cell.U[2][j]});
  }
  cell.mpc->finalize();
  return cell;
}

/// Follow the load from u = 0: `prescribed` maps (i, j) to the value of U_ij at t = 1; every
/// other macro unknown with i > j is zero, and those with i <= j are free and unloaded.
void solve(Laminate& cell, const std::map<std::pair<int, int>, double>& prescribed)
{
  auto load = [&](double t)
  {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
      {
        auto it = prescribed.find({i, j});
        if (it != prescribed.end())
          cell.mpc->prescribe_macro(cell.U[i][j], t * it->second);
        else if (i > j)
          cell.mpc->prescribe_macro(cell.U[i][j], 0);
        else
          cell.mpc->load_macro(cell.U[i][j], 0);
      }
  };
  GELX_PETSC(VecSet(cell.mpc->unknowns(), 0.0));
  load(0);
  cell.mpc->unknowns_changed();
  gelx::NewtonSolver newton(cell.V->mesh()->comm());
  gelx::LoadSteppingOptions steps;
  steps.dt = 0.5;
  steps.dt_max = 0.5;
  gelx::LoadStepper(*cell.mpc, newton, steps, load).run();
}

void small_strain(gelx::test::Checks& checks, MPI_Comm comm, Law law)
{
  const double eps = 1e-4;
  // Round-off for the linear law (Newton converges in one step to |R| <= 1e-10 |R0|); for
  // neo-Hookean the O(eps) finite-strain terms
  const double tol = law == Law::linear ? 1e-8 : 5e-4;
  const std::string name = law == Law::linear ? "linear elastic" : "neo-Hookean, eps = 1e-4";
  Laminate cell = laminate(comm, law);

  solve(cell, {{{2, 2}, eps}, {{0, 0}, 0}, {{1, 1}, 0}});
  const double reuss = 1 / (f1 / soft.M() + f2 / stiff.M());
  checks.relative(name + ": across the layers, sigma_zz / eps_zz against 1/(f1/M1 + f2/M2)",
                  cell.mpc->macro_force(cell.U[2][2]) / eps, reuss, tol);

  solve(cell, {{{0, 0}, eps}, {{1, 1}, 0}});
  double voigt = 0, contraction = 0;
  for (auto [f, phase] : {std::pair{f1, soft}, {f2, stiff}})
  {
    voigt += f * (phase.M() - phase.lame() * phase.lame() / phase.M());
    contraction -= f * phase.lame() / phase.M();
  }
  checks.relative(name + ": along the layers, sigma_xx / eps_xx against sum f (M - lambda^2/M)",
                  cell.mpc->macro_force(cell.U[0][0]) / eps, voigt, tol);
  checks.relative(name + ": along the layers, U_zz / eps_xx against -sum f lambda / M",
                  cell.mpc->macro_value(cell.U[2][2]) / eps, contraction, tol);
  checks.absolute(name + ": along the layers, free U_zz carries no macro force / (eps G1)",
                  cell.mpc->macro_force(cell.U[2][2]) / (eps * soft.G), 0, 1e-8);
}

void finite_strain(gelx::test::Checks& checks, MPI_Comm comm)
{
  const double stretch = 1.3;
  // Layer stretches with equal nominal stress: P1(l1) - P2(l2(l1)) increases with l1
  double lo = 0.05, hi = 0.999 * stretch / f1;
  auto lambda2 = [&](double l1) { return (stretch - f1 * l1) / f2; };
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (soft.uniaxial_strain_stress(mid) > stiff.uniaxial_strain_stress(lambda2(mid)) ? hi : lo)
        = mid;
  }
  const double l1 = 0.5 * (lo + hi), l2 = lambda2(l1);
  const double P = soft.uniaxial_strain_stress(l1);

  Laminate cell = laminate(comm, Law::neo_hookean);
  solve(cell, {{{2, 2}, stretch - 1}, {{0, 0}, 0}, {{1, 1}, 0}});
  const std::string name = "neo-Hookean, stretch 1.3 across: ";
  checks.relative(name + "macro force of U_zz against P_zz (layer stretches "
                      + std::to_string(l1) + ", " + std::to_string(l2) + ")",
                  cell.mpc->macro_force(cell.U[2][2]), P, 1e-8);
  // The layer-wise homogeneous displacement: u_z piecewise linear in z, u_x = u_y = 0
  const std::vector<double> X = cell.V->tabulate_dof_coordinates(false);
  const auto& u = cell.u->x()->array();
  double error = 0;
  for (std::size_t node = 0; node < u.size() / 3; ++node)
  {
    const double z = X[3 * node + 2];
    const double uz = z < f1 ? (l1 - 1) * z : (l1 - 1) * f1 + (l2 - 1) * (z - f1);
    error = std::max({error, std::abs(u[3 * node]), std::abs(u[3 * node + 1]),
                      std::abs(u[3 * node + 2] - uz)});
  }
  MPI_Allreduce(MPI_IN_PLACE, &error, 1, MPI_DOUBLE, MPI_MAX, comm);
  checks.absolute(name + "max |u - layer-wise homogeneous u|", error, 0, 1e-8);
}
} // namespace

int main(int argc, char* argv[])
{
  return gelx::test::run_checks(argc, argv, [](MPI_Comm comm, gelx::test::Checks& checks)
  {
    small_strain(checks, comm, Law::linear);
    small_strain(checks, comm, Law::neo_hookean);
    finite_strain(checks, comm);
  });
}
