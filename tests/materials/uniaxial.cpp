// Verification: homogeneous uniaxial tension and compression against closed forms, for every
// law that has one.
//
// A box with symmetry rollers on x = 0, y = 0, z = 0 and free faces x = Lx, y = Ly is stretched
// to lambda along z (lambda = 1.5 and 0.7). The exact solution is homogeneous,
// F = diag(mu, mu, lambda), and lies in every discrete space used here (linear displacement,
// constant pressure), so the finite-element solution must reproduce it to solver round-off.
//
//  1. Incompressible neo-Hookean (Eq. 1.10), mixed u-p, P2-P1 tetrahedra and Q2-Q1 hexahedra:
//     mu = lambda^-1/2, sigma_zz = G (lambda^2 - 1/lambda), nominal stress
//     P = sigma_zz / lambda = G (lambda - lambda^-2), and the pressure field (mean stress)
//     p = sigma_zz / 3 everywhere.
//     The same on Q1-P0 hexahedra (trilinear displacement, constant pressure).
//  2. Incompressible Mooney-Rivlin, mixed P2-P1: sigma_zz = 2 (lambda^2 - 1/lambda)
//     (C10 + C01/lambda), p = sigma_zz / 3.
//  2b. Incompressible small-strain linear elasticity, mixed Q2-Q1, eps = 0.01: sigma_zz = 3 G eps,
//     lateral strain -eps/2, p = G eps.
//  3. Compressible Mooney-Rivlin, P2: principal stresses
//     sigma_i = J^-1 [C10 J^-2/3 (2 l_i^2 - 2 I1/3) + C01 J^-4/3 (2 l_i^2 (I1 - l_i^2) - 4 I2/3)]
//               + K (J - 1),
//     mu from sigma_xx = 0 by bisection (independent of the finite-element code).
//  4. Linear elasticity, P2, strain eps = 0.01: sigma_zz = E eps, lateral strain -nu eps.

#include "common.h"
#include "compressible.h"
#include "mixed_hex.h"
#include "mixed_hex_q1.h"
#include "mixed_tet.h"

#include <dolfinx/mesh/cell_types.h>
#include <gelx/systems/boundary.h>
#include <gelx/solvers/load_stepping.h>
#include <gelx/systems/problem.h>
#include <gelx/systems/mixed.h>
#include <petscsys.h>

using namespace dolfinx;
using namespace gelx::test;

namespace
{
const std::array<double, 3> L = {1.0, 1.0, 2.0};

/// What a run measured.
struct Measured
{
  double sigma_zz_min, sigma_zz_max; ///< over cells
  double lateral;                    ///< largest |sigma_ij| other than sigma_zz
  double mu_min, mu_max;             ///< lateral stretch on the face x = Lx
  double nominal;                    ///< top reaction / reference area
  bool has_pressure = false;         ///< a mixed form: the pressure field below is checked
  NewtonTolerance tolerance;         ///< what the tolerance of every check rests on
  double p_min = NAN, p_max = NAN;   ///< pressure field
};

/// Solve the stretch to lambda with the problem's forms; `displacement` is the displacement
/// (sub-)space, w the unknown.
Measured stretch(const TaggedBox& box, std::shared_ptr<fem::Function<double>> w,
                 std::shared_ptr<const fem::FunctionSpace> displacement, const Forms& forms,
                 std::shared_ptr<const fem::Expression<double>> stress,
                 std::shared_ptr<const fem::Expression<double>> det_F, double lambda, bool mixed)
{
  MPI_Comm comm = box.mesh->comm();
  gelx::DirichletConditions bcs(displacement, box.facets);
  bcs.fix(x_min, 0);
  bcs.fix(y_min, 1);
  bcs.fix(z_min, 2);
  bcs.prescribe(z_max, 2, [&](double t, auto&) { return t * (lambda - 1) * L[2]; });
  w->x()->set(0.0);
  gelx::NonlinearProblem problem(w, forms.residual, forms.tangent, bcs.bcs(), det_F);
  gelx::NewtonSolver newton(comm);
  gelx::LoadStepper stepper(problem, newton, {}, [&](double t) { bcs.update(t); });
  Measured m;
  stepper.run(m.tolerance.observer());

  gelx::CellField sigma("sigma", stress);
  sigma.update();
  std::tie(m.sigma_zz_min, m.sigma_zz_max) = value_range(*sigma.functions()[s_zz]);
  m.lateral = 0;
  for (int k : {s_xx, s_yy, s_yz, s_xz, s_xy})
  {
    auto [lo, hi] = value_range(*sigma.functions()[k]);
    m.lateral = std::max({m.lateral, std::abs(lo), std::abs(hi)});
  }
  std::shared_ptr<const fem::Function<double>> u = w;
  if (mixed)
    u = gelx::collapse_sub_function(*w, 0);
  auto [ux_min, ux_max] = component_range(*u, *box.facets, x_max, 0);
  m.mu_min = 1 + ux_min / L[0];
  m.mu_max = 1 + ux_max / L[0];
  m.nominal = gelx::reaction_force(problem, *displacement, *box.facets, z_max)[2] / (L[0] * L[1]);
  m.has_pressure = mixed;
  if (mixed)
    std::tie(m.p_min, m.p_max) = value_range(*gelx::collapse_sub_function(*w, 1));
  return m;
}

void check(Checks& checks, const std::string& name, const Measured& m, double sigma_zz,
           double mu, double nominal, double tol)
{
  m.tolerance.check(checks, name + "the path");
  checks.relative(name + "sigma_zz (min over cells)", m.sigma_zz_min, sigma_zz, tol);
  checks.relative(name + "sigma_zz (max over cells)", m.sigma_zz_max, sigma_zz, tol);
  checks.absolute(name + "max |other stress components| / |sigma_zz|",
                  m.lateral / std::abs(sigma_zz), 0.0, tol);
  checks.relative(name + "lateral stretch (min over x = Lx)", m.mu_min, mu, tol);
  checks.relative(name + "lateral stretch (max over x = Lx)", m.mu_max, mu, tol);
  checks.relative(name + "nominal stress (reaction / area)", m.nominal, nominal, tol);
  if (m.has_pressure) // a NaN pressure fails these checks
  {
    checks.relative(name + "pressure p = sigma_zz/3 (min over dofs)", m.p_min, sigma_zz / 3, tol);
    checks.relative(name + "pressure p = sigma_zz/3 (max over dofs)", m.p_max, sigma_zz / 3, tol);
  }
}

/// Principal Cauchy stress i of the compressible Mooney-Rivlin law at stretches l.
double mooney_rivlin_stress(std::array<double, 3> l, int i, double C10, double C01, double K)
{
  const double J = l[0] * l[1] * l[2];
  const double I1 = l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
  const double I2 = l[0] * l[0] * l[1] * l[1] + l[1] * l[1] * l[2] * l[2]
                    + l[2] * l[2] * l[0] * l[0];
  const double li2 = l[i] * l[i];
  return (C10 * std::pow(J, -2.0 / 3) * (2 * li2 - 2 * I1 / 3)
          + C01 * std::pow(J, -4.0 / 3) * (2 * li2 * (I1 - li2) - 4 * I2 / 3))
             / J
         + K * (J - 1);
}
} // namespace

int main(int argc, char* argv[])
{
  PetscInitialize(&argc, &argv, nullptr, nullptr);
  int status;
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    Checks checks(comm);
    // Tolerance for every check: the discrete solution is the exact one up to the Newton
    // tolerance (|R| <= 1e-10 |R0|) and round-off; 1e-8 leaves two digits of margin and still
    // fails for any error in a law, a form or the boundary conditions.
    const double tol = 1e-8;
    const double G = 1.0, C10 = 0.4, C01 = 0.1, K = 10.0;

    // 1-2. Mixed u-p forms, exactly incompressible (bulk_compliance = 0)
    struct MixedCase
    {
      std::string name;
      mesh::CellType cell;
      ufcx_function_space* (*space)(const char*);
      ufcx_form *residual, *tangent;
      ufcx_expression *stress, *det_F;
      enum Law { neo_hookean, mooney_rivlin, linear } law;
    };
    const std::vector<MixedCase> mixed_cases = {
        {"neo-Hookean P2-P1 tet", mesh::CellType::tetrahedron,
         functionspace_form_mixed_tet_residual_nh, form_mixed_tet_residual_nh,
         form_mixed_tet_tangent_nh, expression_mixed_tet_stress_nh, expression_mixed_tet_det_F,
         MixedCase::neo_hookean},
        {"neo-Hookean Q2-Q1 hex", mesh::CellType::hexahedron,
         functionspace_form_mixed_hex_residual_nh, form_mixed_hex_residual_nh,
         form_mixed_hex_tangent_nh, expression_mixed_hex_stress_nh, expression_mixed_hex_det_F,
         MixedCase::neo_hookean},
        {"neo-Hookean Q1-P0 hex", mesh::CellType::hexahedron,
         functionspace_form_mixed_hex_q1_residual_nh, form_mixed_hex_q1_residual_nh,
         form_mixed_hex_q1_tangent_nh, expression_mixed_hex_q1_stress_nh,
         expression_mixed_hex_q1_det_F, MixedCase::neo_hookean},
        {"linear incompressible Q2-Q1 hex", mesh::CellType::hexahedron,
         functionspace_form_mixed_hex_residual_le, form_mixed_hex_residual_le,
         form_mixed_hex_tangent_le, expression_mixed_hex_stress_le, expression_mixed_hex_det_F,
         MixedCase::linear},
        {"Mooney-Rivlin P2-P1 tet", mesh::CellType::tetrahedron,
         functionspace_form_mixed_tet_residual_mr, form_mixed_tet_residual_mr,
         form_mixed_tet_tangent_mr, expression_mixed_tet_stress_mr, expression_mixed_tet_det_F,
         MixedCase::mooney_rivlin},
    };
    for (const auto& c : mixed_cases)
    {
      auto box = tagged_box(comm, L, {2, 2, 2}, c.cell);
      auto W = std::make_shared<fem::FunctionSpace>(
          fem::create_functionspace(c.space, "w", box.mesh));
      auto w = std::make_shared<fem::Function<double>>(W);
      auto constants = const_constants(make_constants(
          {{"G", G}, {"C10", C10}, {"C01", C01}, {"bulk_compliance", 0.0}}));
      Coefficients coefficients = {{"w", w}};
      auto forms = make_forms(c.residual, c.tangent, W, coefficients, constants);
      auto stress = make_expression(c.stress, coefficients, constants, box.mesh);
      auto det_F = make_expression(c.det_F, coefficients, constants, box.mesh);
      if (c.law == MixedCase::linear)
      {
        // Small strain: the reaction is sigma_zz times the reference area
        const double eps = 0.01;
        Measured m = stretch(box, w, W->sub({0}), forms, stress, det_F, 1 + eps, true);
        check(checks, c.name + ", eps = 0.01: ", m, 3 * G * eps, 1 - eps / 2, 3 * G * eps, tol);
        continue;
      }
      for (double lambda : {1.5, 0.7})
      {
        Measured m = stretch(box, w, W->sub({0}), forms, stress, det_F, lambda, true);
        const double sigma_zz = c.law == MixedCase::mooney_rivlin
                                    ? 2 * (lambda * lambda - 1 / lambda) * (C10 + C01 / lambda)
                                    : G * (lambda * lambda - 1 / lambda);
        check(checks, c.name + ", lambda = " + std::to_string(lambda) + ": ", m, sigma_zz,
              1 / std::sqrt(lambda), sigma_zz / lambda, tol);
        if (c.law == MixedCase::neo_hookean)
          checks.relative(c.name + ": nominal stress against G (lambda - lambda^-2)", m.nominal,
                          G * (lambda - 1 / (lambda * lambda)), tol);
      }
    }

    // 3-4. Compressible Mooney-Rivlin and linear elasticity, displacement-only P2
    {
      auto box = tagged_box(comm, L, {2, 2, 2});
      auto constants
          = const_constants(make_constants({{"G", G}, {"K", K}, {"C10", C10}, {"C01", C01}}));
      for (bool linear : {false, true})
      {
        auto V = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(
            functionspace_form_compressible_residual_mr_p2, "u_p2", box.mesh));
        auto u = std::make_shared<fem::Function<double>>(V);
        Coefficients coefficients = {{"u_p2", u}};
        auto forms = linear ? make_forms(form_compressible_residual_le_p2,
                                         form_compressible_tangent_le_p2, V, coefficients,
                                         constants)
                            : make_forms(form_compressible_residual_mr_p2,
                                         form_compressible_tangent_mr_p2, V, coefficients,
                                         constants);
        auto stress = make_expression(linear ? expression_compressible_stress_le_p2
                                             : expression_compressible_stress_mr_p2,
                                      coefficients, constants, box.mesh);
        auto det_F
            = make_expression(expression_compressible_det_F_p2, coefficients, constants, box.mesh);
        if (linear)
        {
          const double eps = 0.01, E = 9 * K * G / (3 * K + G);
          const double nu = (3 * K - 2 * G) / (2 * (3 * K + G));
          Measured m = stretch(box, u, V, forms, stress, det_F, 1 + eps, false);
          // Small strain: the reaction is sigma_zz times the reference area
          check(checks, "linear elastic, eps = 0.01: ", m, E * eps, 1 - nu * eps, E * eps, tol);
          continue;
        }
        for (double lambda : {1.5, 0.7})
        {
          auto s = [&](double mu, int i)
          { return mooney_rivlin_stress({mu, mu, lambda}, i, C10, C01, K); };
          double lo = 0.3, hi = 3; // sigma_xx(lo) < 0 < sigma_xx(hi)
          for (int i = 0; i < 200; ++i)
            (s(0.5 * (lo + hi), 0) > 0 ? hi : lo) = 0.5 * (lo + hi);
          const double mu = 0.5 * (lo + hi);
          Measured m = stretch(box, u, V, forms, stress, det_F, lambda, false);
          check(checks, "Mooney-Rivlin compressible, lambda = " + std::to_string(lambda) + ": ",
                m, s(mu, 2), mu, s(mu, 2) * mu * mu, tol);
        }
      }
    }
    status = checks.finish();
  }
  PetscFinalize();
  return status;
}
