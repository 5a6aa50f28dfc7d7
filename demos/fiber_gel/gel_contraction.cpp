#include "gel_contraction.h"

#include <cmath>
#include <gelx/io/parameters.h>
#include <stdexcept>
#include <string>
#include <theory/flory_rehner.h>

namespace gelx::scenes
{

double GelContraction::phi_f() const { return phi_i / std::pow(alpha0, 3); }

std::pair<double, double> GelContraction::chi_line() const
{
  if (_given_chi)
    return *_given_chi;
  const double chi_i = theory::chi_free(phi_i, n), chi_f = theory::chi_free(phi_f(), n);
  const double chi_B = (chi_f - chi_i) / (T_f - T_i);
  return {chi_B, chi_i - chi_B * T_i};
}

void GelContraction::set_chi(double chi_A, double chi_B)
{
  const auto free_phi = [&](double T)
  {
    try
    {
      return theory::phi_free(chi_A + chi_B * T, n);
    }
    catch (const std::runtime_error&)
    {
      throw InputError("chi(T) = " + std::to_string(chi_A + chi_B * T) + " at T = "
                       + std::to_string(T) + " K: the free gel has no swollen state there");
    }
  };
  phi_i = free_phi(T_i);
  alpha0 = std::cbrt(phi_i / free_phi(T_f));
  _given_chi = {chi_B, chi_A};
}

double GelContraction::uniaxial_alpha_perp() const
{
  return theory::contract(n, alpha0, phi_i, 0.0).alpha_perp;
}

} // namespace gelx::scenes
