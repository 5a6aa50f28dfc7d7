// Verification: volumetric locking in bending (issue #3).
//
// A cantilever L x b x h = 10 x 1 x 1 is clamped at x = 0 and carries a dead shear traction
// tau e_z on its end x = L, small enough for a linear response (tip deflection ~1e-3 L). The
// solid is compressible neo-Hookean (Eq. 3.1), G = 1, K/G = 10, 100, 1e3, 1e4
// (nu = 0.452 ... 0.49995). The measured deflection d is the mean displacement of the end face
// along the load: the work of the traction divided by its resultant (forms/cantilever.py).
//
// Two discretisations of the same energy on one coarse mesh (20 x 2 x 2 boxes of six
// tetrahedra) are compared with a converged reference:
//  - displacement-only P1: J - 1 is one constant per cell, and a nearly incompressible body
//    must bend with nearly no volume change in every cell, which the few P1 modes cannot do:
//    the deflection locks, falling far below the reference as K/G grows;
//  - mixed u-p P2-P1 (Taylor-Hood, inf-sup stable): stays within its discretisation error for
//    every K/G.
// Reference: the mixed formulation on three finer meshes (10k x k x k boxes, k = 3, 4, 5),
// Richardson-extrapolated with the order observed on them. Timoshenko's beam deflection
// P L^3/(3 E I) + P L/(kappa G A) (Cowper's kappa of a rectangle) is printed beside it.

#include "cantilever.h"
#include "common.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <gelx/systems/boundary.h>
#include <gelx/solvers/load_stepping.h>
#include <gelx/systems/problem.h>
#include <gelx/common/petsc_utils.h>
#include <petscsys.h>
#include <span>
#include <stdexcept>

using namespace dolfinx;
using namespace gelx::test;

namespace
{
constexpr double L = 10, b = 1, h = 1, G = 1;
constexpr double A = b * h, I = b * h * h * h / 12;
// Traction for which an incompressible Euler-Bernoulli beam (E = 3G) deflects by 1e-3 L
constexpr double tau = 3 * (3 * G) * I * (1e-3 * L) / (A * L * L * L);
// ds(2) of forms/cantilever.py is the loaded end face
static_assert(x_max == 2, "tagged_box must tag the face x = L with 2");

/// One discretisation of forms/cantilever.py.
struct Discretisation
{
  ufcx_function_space* (*space)(const char*);
  ufcx_form *residual, *tangent, *load_work;
  const char* unknown; ///< the coefficient's name
  bool mixed;
};
const Discretisation p1 = {functionspace_form_cantilever_residual_p1,
                           form_cantilever_residual_p1,
                           form_cantilever_tangent_p1,
                           form_cantilever_load_work_p1,
                           "u_p1",
                           false};
const Discretisation mixed = {functionspace_form_cantilever_residual_mixed,
                              form_cantilever_residual_mixed,
                              form_cantilever_tangent_mixed,
                              form_cantilever_load_work_mixed,
                              "w",
                              true};

/// Mean deflection of the loaded end along the load, on a mesh of 10k x k x k boxes.
double tip_deflection(MPI_Comm comm, const Discretisation& disc, std::size_t k, double K)
{
  auto box = tagged_box(comm, {L, b, h}, {10 * k, k, k});
  auto V = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(disc.space, disc.unknown, box.mesh));
  auto u = std::make_shared<fem::Function<double>>(V);
  const std::array<double, 3> unloaded = {0, 0, 0};
  auto traction = std::make_shared<fem::Constant<double>>(std::span<const double>(unloaded));
  Constants constants
      = const_constants(make_constants({{"G", G}, {"K", K}, {"bulk_compliance", 1 / K}}));
  constants["traction"] = traction;
  const Coefficients coefficients = {{disc.unknown, u}};
  const std::map<fem::IntegralType, const mesh::MeshTags<int>*> facets
      = {{fem::IntegralType::exterior_facet, box.facets.get()}};
  auto form = [&](ufcx_form* f, std::vector<std::shared_ptr<const fem::FunctionSpace>> spaces)
  {
    return std::make_shared<fem::Form<double>>(
        fem::create_form<double>(*f, spaces, coefficients, constants, facets, box.mesh));
  };
  auto residual = form(disc.residual, {V});
  auto tangent = form(disc.tangent, {V, V});
  auto load_work = form(disc.load_work, {});

  gelx::DirichletConditions bcs(disc.mixed ? V->sub({0}) : V, box.facets);
  bcs.clamp(x_min);
  bcs.update(0.0);
  gelx::NonlinearProblem problem(u, residual, tangent, bcs.bcs());
  gelx::NewtonSolver newton(comm);
  gelx::LoadSteppingOptions one_step; // linear regime: the whole load at once
  one_step.dt = one_step.dt_max = 1.0;
  gelx::LoadStepper(problem, newton, one_step,
                    [&](double t) { traction->value = {0, 0, t * tau}; })
      .run();
  return gelx::assemble_global_scalar(*load_work) / (tau * A);
}

/// Limit and observed order p of d_k = d_inf - C k^-p through three levels k0 < k1 < k2.
struct Extrapolation
{
  double limit, order;
};

Extrapolation richardson(std::array<double, 3> k, std::array<double, 3> d)
{
  // The ratio of successive differences fixes p; it grows with p, so bisect on [0.1, 10]
  // (a non-monotone sequence ends at an end of that interval, which the order check rejects)
  auto difference_ratio = [&](double p)
  {
    return (std::pow(k[0], -p) - std::pow(k[1], -p)) / (std::pow(k[1], -p) - std::pow(k[2], -p));
  };
  const double measured = (d[1] - d[0]) / (d[2] - d[1]);
  double lo = 0.1, hi = 10;
  for (int i = 0; i < 100; ++i)
  {
    const double p = 0.5 * (lo + hi);
    (difference_ratio(p) < measured ? lo : hi) = p;
  }
  const double p = 0.5 * (lo + hi);
  const double C = (d[2] - d[1]) / (std::pow(k[1], -p) - std::pow(k[2], -p));
  return {d[2] + C * std::pow(k[2], -p), p};
}
} // namespace

int main(int argc, char* argv[])
{
  PetscInitialize(&argc, &argv, nullptr, nullptr);
  int status;
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    Checks checks(comm);
    const bool root = dolfinx::MPI::rank(comm) == 0;
    // At K/G = 1e4 the P1 residual stalls at ~2e-6 |R0|: K (J - 1) comes from det F in double
    // precision, whose round-off times K is stress noise of ~1e-12 against a traction of 7.5e-6.
    // Every solve here meets 1e-5 at its second Newton iterate; a third, where the default
    // 1e-10 can be reached, changes the deflections by a few 1e-9 relative at most (measured).
    gelx::set_default_option("newton_", "snes_rtol", "1e-5");

    const std::size_t coarse = 2;
    // Reference meshes 10k x k x k; -reference_levels 5,6,8 cross-checks the default on finer
    // ones (1.5 minutes on 2 ranks)
    std::array<PetscInt, 3> k = {3, 4, 5};
    PetscInt n_levels = k.size();
    PetscBool given;
    PetscOptionsGetIntArray(nullptr, nullptr, "-reference_levels", k.data(), &n_levels, &given);
    if ((given && n_levels != 3) || !(PetscInt(coarse) < k[0] && k[0] < k[1] && k[1] < k[2]))
      throw std::runtime_error("-reference_levels takes three increasing levels above 2");
    const std::array<double, 3> levels = {double(k[0]), double(k[1]), double(k[2])};
    const std::vector<double> bulk_ratios = {10, 100, 1e3, 1e4};
    std::vector<double> p1_ratio, mixed_ratio;
    if (root)
      std::printf("%-7s %-9s %-13s %-7s %-14s %-10s %-10s\n", "K/G", "nu", "reference d/L",
                  "order", "Timoshenko/ref", "P1/ref", "mixed/ref");
    for (double KG : bulk_ratios)
    {
      const double K = KG * G;
      const double E = 9 * K * G / (3 * K + G), nu = (3 * K - 2 * G) / (2 * (3 * K + G));
      const double kappa = 10 * (1 + nu) / (12 + 11 * nu);
      const double P = tau * A;
      const double timoshenko = P * L * L * L / (3 * E * I) + P * L / (kappa * G * A);

      std::array<double, 3> fine;
      for (std::size_t i = 0; i < levels.size(); ++i)
        fine[i] = tip_deflection(comm, mixed, std::size_t(levels[i]), K);
      const Extrapolation ref = richardson(levels, fine);
      p1_ratio.push_back(tip_deflection(comm, p1, coarse, K) / ref.limit);
      mixed_ratio.push_back(tip_deflection(comm, mixed, coarse, K) / ref.limit);
      if (root)
        std::printf("%-7g %-9.6f %-13.6e %-7.3f %-14.6f %-10.6f %-10.6f\n", KG, nu,
                    ref.limit / L, ref.order, timoshenko / ref.limit, p1_ratio.back(),
                    mixed_ratio.back());

      const std::string at = "K/G = " + std::to_string(int(KG)) + ": ";
      // Between the rate the clamped edges' singularity allows (~1) and P2's 4 for smooth
      // solutions; measured 1.74 ... 1.79. An erratic or non-monotone sequence leaves [1, 3].
      checks.require(at + "observed order of the reference meshes " + std::to_string(ref.order)
                         + " in [1, 3]",
                     ref.order >= 1 && ref.order <= 3);
      // Beam theory misses the clamped root's constraint on the Poisson contraction and the
      // end warping, which stiffen the body, more so as nu -> 1/2: Timoshenko's deflection is
      // measured 1.6 % (K/G = 10) to 2.1 % (1e4) above the reference; 3 % still fails for a
      // wrong load, modulus or bulk compliance.
      checks.relative(at + "reference against Timoshenko", ref.limit, timoshenko, 0.03);
      // The coarse mixed error is discretisation error, measured 0.73 % (K/G = 10) to 0.92 %
      // (1e4); the reference moves by <= 4.6e-4 when extrapolated from meshes up to 80 x 8 x 8
      // instead (forms/README.md). 1.5 % keeps a margin over both, far below P1's error
      // (70 % already at K/G = 10).
      checks.relative(at + "mixed P2-P1 (coarse mesh) against the reference", mixed_ratio.back(),
                      1.0, 0.015);
    }
    // Compared with the reference of its own K/G, the mixed error hardly depends on K/G:
    // measured spread 1.9e-3 (nu 0.45 -> 0.5 shifts the discretisation error), while P1's ratio
    // changes by a factor of 28; 5e-3 fails for any onset of locking.
    const auto [lo, hi] = std::minmax_element(mixed_ratio.begin(), mixed_ratio.end());
    checks.absolute("mixed/reference: spread over K/G", *hi - *lo, 0.0, 5e-3);
    for (std::size_t i = 1; i < bulk_ratios.size(); ++i)
      checks.require("P1 locks: its ratio to the reference drops from K/G = "
                         + std::to_string(int(bulk_ratios[i - 1])) + " to "
                         + std::to_string(int(bulk_ratios[i])) + " ("
                         + std::to_string(p1_ratio[i - 1]) + " -> " + std::to_string(p1_ratio[i])
                         + ")",
                     p1_ratio[i] < p1_ratio[i - 1]);
    // Measured 0.0106 at K/G = 1e4 (0.30 at K/G = 10): 0.05 leaves a factor 5 and is far from
    // the ~1 of any element that does not lock; positive: it still deflects along the load.
    checks.require("P1 at K/G = 1e4 is locked: 0 < P1/reference = "
                       + std::to_string(p1_ratio.back()) + " < 0.05",
                   p1_ratio.back() > 0 && p1_ratio.back() < 0.05);
    status = checks.finish();
  }
  PetscFinalize();
  return status;
}
