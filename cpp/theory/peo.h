#pragma once
/// @file peo.h
/// phi-dependent chi (thesis section 4.3.3) and the PEO/water model of Dormidontova
/// (Macromolecules 35, 987 (2002); thesis appendix A, Eq. A.1-A.7).
///
/// Parameters. The thesis takes "all the parameters" from Dormidontova (2002) without listing
/// them, and the published values could not be retrieved when this module was written. None is
/// therefore given a default here: every field of PeoParameters is a required user input, to be
/// taken from the paper (and converted to the sign convention below).

#include "theory/amax_map.h"

#include <vector>

namespace gelx::theory
{

/// Eq. 4.20 made consistent with Eq. 4.3 and 4.6: chi_bar = chi - (1 - phi) dchi/dphi.
/// With F_mix = kT (V/nu)[(1-phi) ln(1-phi) + chi(phi) phi (1-phi)] the osmotic condition
/// (Eq. 4.6) contains d[chi (1-phi)]/dphi = -(chi - (1-phi) chi'), so chi_bar takes the place of
/// chi in Eq. 4.7 and 4.10. The thesis prints chi - phi dchi/dphi; its own Eq. A.7 agrees with
/// the (1 - phi) form (checked in tests/theory/test_peo.cpp), which is the one used here.
double chi_bar(double chi, double dchi_dphi, double phi);
/// Eq. 4.20 exactly as printed in the thesis, kept for comparison only.
double chi_bar_as_printed(double chi, double dchi_dphi, double phi);

/// Dormidontova's model in the notation of appendix A. Sign convention of Eq. A.5-A.6: a
/// hydrogen bond is favoured when its Delta f is positive, and
///   Delta f_p / kT = energy_p / T - entropy_p,   Delta f_w / kT = energy_w / T - entropy_w,
/// with energies in kelvin (energy / k) and entropies in units of k.
struct PeoParameters
{
  double chi_A;     ///< chi = chi_A + chi_B / T (Eq. A.2), dimensionless
  double chi_B;     ///< kelvin
  double v_over_vp; ///< v / v_p: water volume over PEO monomer volume
  double energy_p;  ///< PEO-water bond, kelvin
  double entropy_p; ///< PEO-water bond, units of k
  double energy_w;  ///< water-water bond, kelvin
  double entropy_w; ///< water-water bond, units of k
};

class PeoModel
{
public:
  explicit PeoModel(const PeoParameters& p) : _p(p) {}
  const PeoParameters& parameters() const { return _p; }

  /// Equilibrium hydrogen-bond fractions at (T, phi).
  struct Bonds
  {
    double p;  ///< fraction of PEO-water bonds
    double q;  ///< fraction of water-water association
    double q0; ///< q in pure water (phi = 0)
    double D;  ///< (1-phi)(1-q) - p phi v/v_p: free water acceptor sites, common to A.5-A.6
  };
  /// Solves Eq. A.5-A.6. Both read x/(2(1-x) D) = K_x, so for given D
  /// p = 2 K_p D/(1 + 2 K_p D), q = 2 K_w D/(1 + 2 K_w D), and D must satisfy
  /// D = (1-phi)(1-q(D)) - p(D) phi v/v_p: a strictly increasing equation in D on [0, 1-phi]
  /// whose root is unique; it is found by bracketed Newton. q0 has the closed form
  /// q0 = 4K_w / (1 + 4K_w + sqrt(1 + 8K_w)) (the smaller root of q0 = 2K_w (1-q0)^2).
  Bonds bonds(double T, double phi) const;

  /// Residuals of Eq. A.5 and A.6, written as x/(2(1-x)D) / K_x - 1.
  std::pair<double, double> residuals(double T, double phi, const Bonds& b) const;

  double chi(double T) const { return _p.chi_A + _p.chi_B / T; }
  double Kp(double T) const;
  double Kw(double T) const;

  /// Eq. A.7: chi_bar(T, phi) = chi + (2/phi)(p v/v_p - q)
  ///   + (2/phi^2)[q - q0 + ln(q / (q0 (1 - phi)))].
  double chi_bar(double T, double phi) const;

  /// Eq. A.3 at the equilibrium p, q: hydrogen-bond free energy per lattice site, units kT.
  double free_energy_hb(double T, double phi) const;

private:
  PeoParameters _p;
};

/// Temperatures in [T_lo, T_hi] at which a free PEO gel is in equilibrium at volume fraction
/// phi (Eq. 4.7 with chi -> chi_bar(T, phi)); all roots of a scan with `samples` points.
std::vector<double> peo_temperatures_free(const PeoModel& m, double phi, double n, double T_lo,
                                          double T_hi, int samples = 200);
/// Same for the uniaxially constrained gel (Eq. 4.10 with chi -> chi_bar).
std::vector<double> peo_temperatures_constrained(const PeoModel& m, double phi,
                                                 double lambda_par, double n, double T_lo,
                                                 double T_hi, int samples = 200);
/// Volume fractions of the constrained PEO gel at temperature T (all roots on (0, 1)).
std::vector<double> peo_phi_constrained(const PeoModel& m, double T, double lambda_par,
                                        double n, int samples = 200);

/// A_max map for the PEO gel (section 4.3.3): per row, T_i and T_f are the (unique) equilibrium
/// temperatures of the free gel at phi_i and phi_f = phi_i/alpha0^3; per grid point the
/// constrained gel with lambda_par = (1+eps) phi_i^-1/3 is solved at T_i and T_f. Non-unique
/// roots give NaN and are counted.
AmaxMap peo_amax_map(const PeoModel& m, double n, double alpha0,
                     const std::vector<double>& phi_i, const std::vector<double>& eps,
                     double T_lo, double T_hi);

} // namespace gelx::theory
