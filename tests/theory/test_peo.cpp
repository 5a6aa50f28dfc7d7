// The Dormidontova PEO model of thesis appendix A (Eq. A.3-A.7) and the phi-dependent chi_bar
// of Eq. 4.20. The parameter sets below are NOT Dormidontova's values (those are required user
// inputs of the scene): they only exercise identities that must hold for any parameters.

#include "check.h"
#include "theory/amax_map.h"
#include "theory/peo.h"

#include <algorithm>
#include <cmath>

using namespace gelx::theory;

int main()
{
  const PeoParameters sets[] = {
      // chi_A, chi_B, v/v_p, E_p, S_p, E_w, S_w  (arbitrary test values, see above)
      {0.0, 0.0, 0.5, 1500.0, 4.0, 1200.0, 3.0},
      {0.2, 50.0, 0.4, 2500.0, 6.0, 2000.0, 5.0},
      {-0.1, 100.0, 1.0, 800.0, 1.0, 1800.0, 4.5},
  };
  double worst_res = 0.0, worst_a7 = 0.0, worst_q0 = 0.0, largest_printed = 0.0;
  for (const auto& s : sets)
  {
    const PeoModel m(s);
    for (double T : linspace(260.0, 400.0, 15))
    {
      // 1. p, q satisfy Eq. A.5-A.6 (relative residuals; the D-equation is solved to 1e-16
      //    of its range, so 1e-10 leaves room for the 1/D amplification when D is small).
      for (double phi : linspace(0.0, 0.95, 39))
      {
        const auto b = m.bonds(T, phi);
        const auto [r5, r6] = m.residuals(T, phi, b);
        worst_res = std::max({worst_res, std::abs(r5), std::abs(r6)});
      }
      // q0 from the closed form equals the phi = 0 solution of A.6.
      worst_q0 = std::max(worst_q0, std::abs(m.bonds(T, 0.0).q - m.bonds(T, 0.0).q0));
      // 2. Eq. A.7 against thermodynamics: with g(phi) = F_HB at equilibrium (Eq. A.3), the
      //    osmotic condition needs (g - phi g')/phi^2, and with chi_eff = chi + g/(phi(1-phi))
      //    that is chi_bar = chi_eff - (1-phi) chi_eff'. Central differences with h = 1e-4
      //    have truncation error ~h^2 |g'''| ~ 1e-8 and rounding ~1e-16/h; tolerance 1e-6.
      for (double phi : linspace(0.05, 0.8, 16))
      {
        const double h = 1e-4;
        auto chi_eff = [&](double x) { return m.chi(T) + m.free_energy_hb(T, x) / (x * (1 - x)); };
        const double d = (chi_eff(phi + h) - chi_eff(phi - h)) / (2 * h);
        const double a7 = m.chi_bar(T, phi);
        worst_a7 = std::max(worst_a7, std::abs(chi_bar(chi_eff(phi), d, phi) - a7));
        largest_printed = std::max(largest_printed, std::abs(chi_bar_as_printed(chi_eff(phi), d, phi) - a7));
      }
    }
  }
  check::near("Eq. A.5-A.6 relative residuals, worst", worst_res, 0.0, 1e-10);
  check::near("q0 closed form vs A.6 at phi = 0, worst", worst_q0, 0.0, 1e-14);
  check::near("Eq. A.7 = chi_eff - (1-phi) dchi_eff/dphi, worst", worst_a7, 0.0, 1e-6);
  std::printf("     largest |Eq. 4.20 as printed (chi - phi chi') - Eq. A.7| = %.3e\n", largest_printed);
  check::that("Eq. 4.20 as printed does not reproduce Eq. A.7 (documented discrepancy)",
              largest_printed > 1e-3);

  // 3. Closed forms the solver of Eq. A.5-A.6 does not use (sections 1-3 check it against its
  //    own equations). Without PEO-water bonds (K_p = e^-30 ~ 1e-13: p = 0 to 1e-12),
  //    D = (1-phi)(1-q) and Eq. A.6 is the quadratic q = a (1-q)^2, a = 2 K_w (1-phi), whose
  //    root in [0, 1) is q = 2a / (2a + 1 + sqrt(4a + 1)); chi_bar then follows from Eq. A.7
  //    with p = 0. Tolerance 1e-11: the bracketed Newton solves D to ~1e-16 of its range,
  //    and Eq. A.7's 2/phi^2 amplifies that (and the O(K_p) left of p) by at most 800 at
  //    phi = 0.05 (measured 3.4e-13; a q0 off by 1e-6 relative fails it). Without any bonds (K_p = K_w = e^-30) the gel is Flory-Huggins':
  //    chi_bar = chi(T), the bonds' terms being O(K_w / phi^2) < 1e-10
  {
    const PeoParameters no_peo_bonds{0.1, 60.0, 0.5, 0.0, 30.0, 1800.0, 4.0};
    const PeoModel water_only(no_peo_bonds);
    double worst_q = 0.0, worst_chi = 0.0;
    for (double T : linspace(270.0, 370.0, 6))
      for (double phi : linspace(0.05, 0.9, 18))
      {
        const double a = 2 * water_only.Kw(T) * (1 - phi), a0 = 2 * water_only.Kw(T);
        const double q = 2 * a / (2 * a + 1 + std::sqrt(4 * a + 1));
        const double q0 = 2 * a0 / (2 * a0 + 1 + std::sqrt(4 * a0 + 1));
        const auto b = water_only.bonds(T, phi);
        worst_q = std::max({worst_q, std::abs(b.q - q), std::abs(b.p)});
        const double chi_bar_closed = water_only.chi(T) - 2 * q / phi
                                      + 2 / (phi * phi) * (q - q0 + std::log(q / (q0 * (1 - phi))));
        worst_chi = std::max(worst_chi, std::abs(water_only.chi_bar(T, phi) - chi_bar_closed));
      }
    check::near("no PEO-water bonds: p = 0 and q against the quadratic's root, worst", worst_q,
                0.0, 1e-12);
    check::near("no PEO-water bonds: chi_bar against Eq. A.7 with the closed-form q, worst",
                worst_chi, 0.0, 1e-11);
    const PeoModel no_bonds({0.1, 60.0, 0.5, 0.0, 30.0, 0.0, 30.0});
    double worst_fh = 0.0;
    for (double T : linspace(270.0, 370.0, 6))
      for (double phi : linspace(0.05, 0.9, 18))
        worst_fh = std::max(worst_fh, std::abs(no_bonds.chi_bar(T, phi) - no_bonds.chi(T)));
    check::near("no hydrogen bonds: chi_bar = chi(T) (Flory-Huggins), worst", worst_fh, 0.0,
                1e-10);
  }

  // 4. A free-gel equilibrium temperature really satisfies Eq. 4.7 with chi -> chi_bar.
  const PeoModel m(sets[1]);
  const auto T = peo_temperatures_free(m, 0.2, 0.002, 200.0, 600.0);
  std::printf("     free-gel equilibrium temperatures at phi = 0.2 (test set 2):");
  for (double t : T)
    std::printf(" %.6f", t);
  std::printf("\n");
  check::that("a free-gel equilibrium temperature exists in [200, 600] K", !T.empty());
  if (!T.empty()) // reported as a failure above
    check::near("chi_bar(T, 0.2) - chi_free(0.2) at that T", m.chi_bar(T[0], 0.2),
                0.5 * 0.002 * (1 / 0.2 - 2 * std::pow(0.2, -5.0 / 3.0)) - std::log1p(-0.2) / 0.04 - 5.0,
                1e-8);
  return check::result();
}
