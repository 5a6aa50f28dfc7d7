#pragma once
/// @file amax_map.h
/// Maps of the largest contraction anisotropy A_max over the initial volume fraction phi_i of
/// the free gel and the longitudinal prestrain eps_par (thesis Fig. 4.2b and Fig. 4.3b).

#include <cstddef>
#include <string>
#include <vector>

namespace gelx::theory
{

/// A_max on a (phi_i, eps_par) grid; row-major, index i * eps.size() + j. Entries that are
/// undefined (phi_f >= 1, or Eq. 4.10 not uniquely invertible) hold NaN and are counted.
struct AmaxMap
{
  double n = 0, alpha0 = 0;
  std::vector<double> phi_i, eps;
  std::vector<double> A, phi_prime_i, phi_prime_f;
  std::vector<double> T_i, T_f; ///< per row; only filled for the PEO model (temperatures, K)
  int undefined = 0;            ///< grid points with phi_f = phi_i/alpha0^3 >= 1 (or no T)
  int non_unique = 0;           ///< grid points where a root was not unique

  /// A map over the grid with every entry undefined (NaN), to be filled.
  AmaxMap(double n, double alpha0, const std::vector<double>& phi_i,
          const std::vector<double>& eps);

  double at(std::size_t i, std::size_t j) const { return A[i * eps.size() + j]; }

  /// Location of the largest finite A over the whole map, or over the column nearest eps0.
  struct Peak
  {
    double A = 0, phi_i = 0, eps = 0, phi_prime_i = 0, phi_prime_f = 0;
  };
  Peak peak() const;
  Peak peak_at_eps(double eps0) const;
};

/// n+1 ... uniformly spaced values from a to b inclusive (m >= 2 points).
std::vector<double> linspace(double a, double b, int m);

/// A_max for a gel with phi-independent chi (section 4.3.2): per grid point see
/// gelx::theory::contract. Rows are swept in eps with the previous roots as warm starts, and
/// the monotonicity certificate lambda_monotone_bound avoids root scans wherever it applies.
AmaxMap amax_map(double n, double alpha0, const std::vector<double>& phi_i,
                 const std::vector<double>& eps);

/// Long-format CSV: phi_i, eps_par, A_max, phi_prime_i, phi_prime_f (NaN written as "nan").
void write_csv(const AmaxMap& map, const std::string& path);

} // namespace gelx::theory
