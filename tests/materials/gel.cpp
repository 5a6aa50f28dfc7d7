// Verification: the Flory-Rehner gel of Eq. 4.28 against the closed forms of section 4.2
// (thesis Fig. 4.5): free swelling (Eq. 4.7) and the uniaxially constrained gel (Eq. 4.10,
// 4.11), with the 0-D theory toolkit (cpp/theory, written independently) as the reference.
//
// Derivation. The mesh is the swollen reference state, isotropically stretched from the dry
// (molten) state by lambda0 = phi0^(-1/3). A mesh deformation F' gives the deformation from
// the dry state F = lambda0 F', so phi = 1/det F = phi0/J'. Eq. 4.28 is Eq. 4.25 per unit
// reference volume (V_m = phi0 V_0, Eq. 4.26-4.27), so its homogeneous equilibria are those of
// the theory:
//  * free swelling at chi: F' = lambda' I with zero stress (the box has rollers on three faces
//    and three free faces); zero osmotic pressure is Eq. 4.7, so phi = phi0 / lambda'^3 must
//    equal theory::phi_free(chi, n);
//  * uniaxial constraint: the longitudinal stretch from the dry state lambda_par = lambda0
//    lambda'_z is held, i.e. lambda'_z = lambda_par phi0^(1/3) prescribed on z = Lz, and the
//    transverse faces are free (sigma_1 = sigma_2 = 0, Eq. 4.9). Then phi = phi0 / J' must equal
//    theory::phi_constrained(chi, lambda_par, n) (Eq. 4.10), and the true stress sigma_zz in
//    units of kT/nu must equal theory::sigma3 (Eq. 4.11: n (phi/lambda_par)(1/phi_c - 1/phi),
//    phi_c = lambda_par^-3), negative for phi < phi_c and positive for phi > phi_c.
// chi = chi_A + chi_B T is changed through T from step to step (chi_A is chosen so that the
// mesh state is the free equilibrium at the initial T); kT/nu follows T.

#include "gel_box.h"
#include "theory/flory_rehner.h"

#include <gelx/solvers/load_stepping.h>
#include <gelx/systems/problem.h>
#include <petscsys.h>

using namespace dolfinx;
using namespace gelx::test;
namespace theory = gelx::theory;

namespace
{
/// Ramp T from its current value to T_next with the load stepper (t: 0 -> 1), recording the
/// Newton residuals in `tolerance`.
void ramp_temperature(GelBox& gel, gelx::NonlinearProblem& problem, gelx::NewtonSolver& newton,
                      double T_next, NewtonTolerance& tolerance)
{
  const double T_prev = gel.constants.at("T")->value[0];
  gelx::LoadStepper stepper(problem, newton, {},
                            [&](double t) { gel.set_temperature(T_prev + t * (T_next - T_prev)); });
  stepper.run(tolerance.observer());
}

/// Cauchy stress components (xx, yy, zz, ...) as ranges over the cells.
std::array<std::pair<double, double>, 6> stress_ranges(const GelBox& gel)
{
  gelx::CellField sigma("sigma", gel.stress);
  sigma.update();
  std::array<std::pair<double, double>, 6> r;
  for (int k = 0; k < 6; ++k)
    r[k] = value_range(*sigma.functions()[k]);
  return r;
}
} // namespace

int main(int argc, char* argv[])
{
  PetscInitialize(&argc, &argv, nullptr, nullptr);
  int status;
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    Checks checks(comm);
    GelParameters p;
    // The mesh state is the free equilibrium at the initial temperature
    p.chi_A = theory::chi_free(p.phi0, p.n) - p.chi_B * p.T;

    // 1. Free swelling (Fig. 4.5a): phi(chi) against Eq. 4.7 at five chi, swelling and
    //    shrinking from phi0 = 0.2
    {
      GelBox gel(comm, p, {2, 2, 2});
      gelx::NonlinearProblem problem(gel.u, gel.forms.residual, gel.forms.tangent,
                                     gel.bcs->bcs(), gel.margin);
      gelx::NewtonSolver newton(comm);
      NewtonTolerance tolerance;
      gel.bcs->update(1.0);
      for (double chi : {0.3, 0.45, 0.55, 0.65, 0.75})
      {
        const double T = p.temperature(chi);
        ramp_temperature(gel, problem, newton, T, tolerance);
        const double phi_exact = theory::phi_free(chi, p.n);
        auto s = gel.stretches();
        const double lambda_exact = std::cbrt(p.phi0 / phi_exact);
        char name[96];
        std::snprintf(name, sizeof name, "free, chi = %.2f (T = %.1f K): ", chi, T);
        // phi from the three stretches; 1e-6 is the bound, and the discrete state is
        // the exact homogeneous one up to the Newton tolerance (~1e-10 relative).
        const double phi = p.phi0 / (s[0].first * s[1].first * s[2].first);
        checks.absolute(std::string(name) + "phi against Eq. 4.7", phi, phi_exact, 1e-6);
        // Every face node on the same stretch (isotropic and homogeneous): 1e-8 relative,
        // the Newton tolerance with two digits of margin.
        for (int axis = 0; axis < 3; ++axis)
          for (double v : {s[axis].first, s[axis].second})
            checks.relative(std::string(name) + "stretch along axis " + std::to_string(axis), v,
                            lambda_exact, 1e-8);
        // Stress free: |sigma| / (kT/nu) below 1e-10, which is the residual tolerance relative
        // to stresses of order n kT/nu = 1e-2 kT/nu, with margin.
        double s_max = 0;
        for (auto [lo, hi] : stress_ranges(gel))
          s_max = std::max({s_max, std::abs(lo), std::abs(hi)});
        checks.absolute(std::string(name) + "max |sigma| / (kT/nu)", s_max / p.kT_nu(T), 0.0,
                        1e-10);
      }
      tolerance.check(checks, "free swelling: the temperature ramps");
    }

    // 2. Uniaxially constrained (Fig. 4.5b): lambda_par with phi_c = 0.3, chi on both sides of
    //    the stress-free chi_c = chi_free(phi_c)
    {
      const double phi_c = 0.3, lambda_par = std::cbrt(1 / phi_c);
      const double lambda_z = lambda_par * std::cbrt(p.phi0); // from the mesh state
      GelBox gel(comm, p, {2, 2, 2});
      gel.bcs->prescribe(z_max, 2, [&](double t, auto&)
                         { return t * (lambda_z - 1) * GelBox::L[2]; });
      gelx::NonlinearProblem problem(gel.u, gel.forms.residual, gel.forms.tangent,
                                     gel.bcs->bcs(), gel.margin);
      gelx::NewtonSolver newton(comm);
      // Apply the constraint at the initial temperature, then change chi at fixed lambda_par
      gelx::LoadStepper constrain(problem, newton, {}, [&](double t) { gel.bcs->update(t); });
      NewtonTolerance tolerance;
      constrain.run(tolerance.observer());
      const double chi_c = theory::chi_free(phi_c, p.n);
      // Counts of the states on each side of phi_c and of those with the sign of Eq. 4.11
      int below = 0, above = 0, negative_below = 0, positive_above = 0;
      for (double chi : {0.45, 0.52, 0.62, 0.7, 0.8})
      {
        const double T = p.temperature(chi);
        ramp_temperature(gel, problem, newton, T, tolerance);
        const double phi_exact = theory::phi_constrained(chi, lambda_par, p.n);
        auto s = gel.stretches();
        const double phi = p.phi0 / (s[0].first * s[1].first * s[2].first);
        const auto sigma = stress_ranges(gel);
        const double sigma3 = sigma[2].first / p.kT_nu(T);
        const double sigma3_exact = theory::sigma3(phi_exact, lambda_par, p.n);
        char name[128];
        std::snprintf(name, sizeof name, "constrained, chi = %.2f (chi_c = %.4f): ", chi, chi_c);
        checks.absolute(std::string(name) + "phi against Eq. 4.10", phi, phi_exact, 1e-6);
        checks.relative(std::string(name) + "lambda_z held", s[2].first, lambda_z, 1e-12);
        // sigma_3 in units of kT/nu: it is of order n = 1e-2 and the state is exact to the
        // Newton tolerance, so 1e-10 absolute is the same margin as above.
        checks.absolute(std::string(name) + "sigma3 / (kT/nu) against Eq. 4.11 (min over cells)",
                        sigma3, sigma3_exact, 1e-10);
        checks.absolute(std::string(name) + "sigma3 / (kT/nu) against Eq. 4.11 (max over cells)",
                        sigma[2].second / p.kT_nu(T), sigma3_exact, 1e-10);
        checks.absolute(std::string(name) + "transverse sigma_xx / (kT/nu)",
                        std::max(std::abs(sigma[0].first), std::abs(sigma[0].second)) / p.kT_nu(T),
                        0.0, 1e-10);
        if (phi < phi_c)
        {
          ++below;
          negative_below += sigma3 < 0;
        }
        else
        {
          ++above;
          positive_above += sigma3 > 0;
        }
        if (dolfinx::MPI::rank(comm) == 0)
          std::printf("      phi = %.8f  phi - phi_c = %+.4f  sigma3 nu/kT = %+.6e\n", phi,
                      phi - phi_c, sigma3);
      }
      tolerance.check(checks, "uniaxially constrained gel: the temperature ramps");
      // The sign change needs states on both sides: the chi values above straddle chi_c
      checks.require("states on both sides of phi_c: " + std::to_string(below) + " below, "
                         + std::to_string(above) + " above",
                     below > 0 && above > 0);
      checks.require("sigma3 < 0 for every phi < phi_c (" + std::to_string(negative_below) + " of "
                         + std::to_string(below) + ") and > 0 for every phi > phi_c ("
                         + std::to_string(positive_above) + " of " + std::to_string(above)
                         + "): the sign change at phi_c of Eq. 4.11",
                     negative_below == below && positive_above == above);
    }
    status = checks.finish();
  }
  PetscFinalize();
  return status;
}
