// Verification: homogeneous uniaxial stretch of a compressible neo-Hookean block (Eq. 3.1).
//
// A box with symmetry rollers on x = 0, y = 0, z = 0 and free lateral faces x = Lx, y = Ly is
// stretched to lambda along z. The exact solution is homogeneous, F = diag(mu, mu, lambda), with
// the lateral stretch mu fixed by sigma_xx = 0:
//   G J^(-5/3) (mu^2 - (lambda^2 + 2 mu^2)/3) + K (J - 1) = 0,   J = lambda mu^2,
// solved here by bisection, independently of the finite-element code. The P2 solution contains
// the exact (linear) displacement, so it must reproduce mu and sigma_zz to solver round-off.

#include "block.h"
#include "support.h"

#include <cmath>
#include <dolfinx/fem/utils.h>
#include <gelx/systems/boundary.h>
#include <gelx/solvers/load_stepping.h>
#include <gelx/systems/problem.h>
#include <gelx/io/output.h>
#include <petscsys.h>

using namespace dolfinx;

namespace
{
struct Uniaxial
{
  double mu, sigma_zz;
};

/// Closed form of the homogeneous state for Eq. 3.1.
Uniaxial closed_form(double G, double K, double lambda)
{
  auto sigma = [&](double mu, int axis)
  {
    const double J = lambda * mu * mu, I1 = lambda * lambda + 2 * mu * mu;
    const double b = axis == 2 ? lambda * lambda : mu * mu;
    return G * std::pow(J, -5.0 / 3.0) * (b - I1 / 3) + K * (J - 1);
  };
  // sigma_xx is increasing in mu: bisect on a bracket that contains the root
  double lo = 0.1, hi = 10;
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (sigma(mid, 0) > 0 ? hi : lo) = mid;
  }
  const double mu = 0.5 * (lo + hi);
  return {mu, sigma(mu, 2)};
}
} // namespace

int main(int argc, char* argv[])
{
  PetscInitialize(&argc, &argv, nullptr, nullptr);
  int status;
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    gelx::test::Checks checks(comm);
    const std::array<double, 3> L = {1.0, 1.0, 2.0};
    const double G = 1.0, K = 10.0;
    auto box = gelx::test::tagged_box(comm, L, {2, 2, 4});

    auto V = std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(functionspace_form_block_residual_nh_p2, "u_p2", box.mesh));
    auto u = std::make_shared<fem::Function<double>>(V);
    const std::map<std::string, std::shared_ptr<const fem::Constant<double>>> material
        = {{"G", std::make_shared<fem::Constant<double>>(G)},
           {"K", std::make_shared<fem::Constant<double>>(K)}};
    auto residual = std::make_shared<fem::Form<double>>(
        fem::create_form<double>(*form_block_residual_nh_p2, {V}, {{"u_p2", u}}, material, {}));
    auto tangent = std::make_shared<fem::Form<double>>(
        fem::create_form<double>(*form_block_tangent_nh_p2, {V, V}, {{"u_p2", u}}, material, {}));
    auto expression = [&](ufcx_expression* e)
    {
      return std::make_shared<fem::Expression<double>>(
          fem::create_expression<double>(*e, {{"u_p2", u}}, material, box.mesh));
    };
    gelx::CellField stress("sigma", expression(expression_block_stress_nh_p2));

    for (double lambda : {1.5, 0.7}) // tension and compression
    {
      gelx::DirichletConditions bcs(V, box.facets);
      bcs.fix(gelx::test::x_min, 0);
      bcs.fix(gelx::test::y_min, 1);
      bcs.fix(gelx::test::z_min, 2);
      bcs.prescribe(gelx::test::z_max, 2,
                    [&](double t, auto&) { return t * (lambda - 1) * L[2]; });
      u->x()->set(0.0);
      gelx::NonlinearProblem problem(u, residual, tangent, bcs.bcs(),
                                     expression(expression_block_det_F_p2));
      gelx::NewtonSolver newton(comm);
      gelx::LoadStepper stepper(problem, newton, {}, [&](double t) { bcs.update(t); });
      gelx::test::NewtonTolerance tolerance;
      stepper.run(tolerance.observer());

      const Uniaxial exact = closed_form(G, K, lambda);
      auto r = gelx::boundary_resultant(problem, *box.facets, gelx::test::z_max);
      stress.update();
      double s_min = INFINITY, s_max = -INFINITY;
      for (double s : stress.functions()[2]->x()->array()) // sigma_zz in every cell
      {
        s_min = std::min(s_min, s);
        s_max = std::max(s_max, s);
      }
      double s_lat = 0; // largest lateral stress, to be zero
      for (int k : {0, 1, 3, 4, 5})
        for (double s : stress.functions()[k]->x()->array())
          s_lat = std::max(s_lat, std::abs(s));
      MPI_Allreduce(MPI_IN_PLACE, &s_min, 1, MPI_DOUBLE, MPI_MIN, comm);
      MPI_Allreduce(MPI_IN_PLACE, &s_max, 1, MPI_DOUBLE, MPI_MAX, comm);
      MPI_Allreduce(MPI_IN_PLACE, &s_lat, 1, MPI_DOUBLE, MPI_MAX, comm);

      // Lateral stretch: every node of the free face x = Lx has u_x = (mu - 1) Lx
      auto [ux_min, ux_max] = gelx::test::component_range(*u, *box.facets, gelx::test::x_max, 0);
      const std::string tag = "lambda = " + std::to_string(lambda) + ": ";
      // Tolerances: the discrete solution is exact up to the Newton tolerance (relative
      // residual 1e-10) and round-off; 1e-8 leaves two digits of margin.
      tolerance.check(checks, tag + "the path");
      checks.relative(tag + "sigma_zz (min over cells)", s_min, exact.sigma_zz, 1e-8);
      checks.relative(tag + "sigma_zz (max over cells)", s_max, exact.sigma_zz, 1e-8);
      checks.absolute(tag + "max |lateral and shear stress| / G", s_lat / G, 0.0, 1e-8);
      checks.relative(tag + "lateral stretch (min over face x = Lx)", 1 + ux_min / L[0],
                      exact.mu, 1e-8);
      checks.relative(tag + "lateral stretch (max over face x = Lx)", 1 + ux_max / L[0],
                      exact.mu, 1e-8);
      // The top reaction is sigma_zz times the current cross-section (mu Lx)(mu Ly)
      checks.relative(tag + "axial force", r.force[2],
                      exact.sigma_zz * exact.mu * exact.mu * L[0] * L[1], 1e-8);
    }
    status = checks.finish();
  }
  PetscFinalize();
  return status;
}
