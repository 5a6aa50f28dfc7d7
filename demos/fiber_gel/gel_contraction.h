#pragma once
/// @file gel_contraction.h
/// The temperature programme of the fiber-reinforced gel (thesis section 4.4.2): chi(T) and the
/// free gel's states it joins, shared by the fiber_gel cell at equilibrium and the fiber_film
/// in time.

#include <optional>
#include <utility>

namespace gelx::scenes
{

/// The gel and its contraction, after thesis section 4.4.2 steps (1)-(5): the free gel
/// contracts isotropically by alpha0 from phi_i at T_i to phi_f = phi_i / alpha0^3 at T_f,
/// which fixes chi_i = chi(phi_i) and chi_f = chi(phi_f) by Eq. 4.7 and the line
/// chi = chi_A + chi_B T through (T_i, chi_i) and (T_f, chi_f). Or the other way round: chi(T)
/// given (set_chi), phi_i and alpha0 are the free gel's states at T_i and T_f.
struct GelContraction
{
  double n = 0.01;     ///< N nu / V_m
  double phi_i = 0.3;  ///< polymer volume fraction of the stress-free reference state at T_i
  double alpha0 = 0.8; ///< contraction ratio of the free gel from T_i to T_f (Eq. 4.13)
  double T_i = 298;    ///< initial temperature (K)
  double T_f = 363;    ///< final temperature (K)

  /// Eq. 4.13 inverted: the free gel's volume fraction at T_f.
  double phi_f() const;
  /// chi_B (1/K) and chi_A of chi = chi_A + chi_B T: given (set_chi), or steps (1)-(2).
  std::pair<double, double> chi_line() const;
  /// Take chi(T) = chi_A + chi_B T as given, and phi_i and alpha0 from it: the free gel's volume
  /// fractions at T_i and T_f (Eq. 4.7 inverted). Throws InputError where chi(T) has no
  /// free-swelling state. Call after n, T_i and T_f are set.
  void set_chi(double chi_A, double chi_B);
  /// The limit of a fiber of no thickness through the cell (L = l, D/d -> infinity): the
  /// transverse contraction ratio of the uniaxially constrained gel without prestrain (Eq. 4.14,
  /// phi_i = phi'_i = phi_c), from the theory library.
  double uniaxial_alpha_perp() const;

private:
  std::optional<std::pair<double, double>> _given_chi; ///< {chi_B, chi_A}, when set_chi gave it
};

} // namespace gelx::scenes
