#include "theory/amax_map.h"

#include "theory/flory_rehner.h"
#include "theory/roots.h"
#include <gelx/io/units.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace gelx::theory
{

std::vector<double> linspace(double a, double b, int m)
{
  if (m < 2)
    return {a};
  std::vector<double> v(m);
  for (int k = 0; k < m; ++k)
    v[k] = a + (b - a) * k / (m - 1.0);
  return v;
}

AmaxMap::Peak AmaxMap::peak() const
{
  Peak p;
  p.A = -INFINITY;
  for (std::size_t i = 0; i < phi_i.size(); ++i)
    for (std::size_t j = 0; j < eps.size(); ++j)
    {
      const std::size_t k = i * eps.size() + j;
      if (std::isfinite(A[k]) && A[k] > p.A)
        p = {A[k], phi_i[i], eps[j], phi_prime_i[k], phi_prime_f[k]};
    }
  return p;
}

AmaxMap::Peak AmaxMap::peak_at_eps(double eps0) const
{
  std::size_t jb = 0;
  for (std::size_t j = 1; j < eps.size(); ++j)
    if (std::abs(eps[j] - eps0) < std::abs(eps[jb] - eps0))
      jb = j;
  Peak p;
  p.A = -INFINITY;
  for (std::size_t i = 0; i < phi_i.size(); ++i)
  {
    const std::size_t k = i * eps.size() + jb;
    if (std::isfinite(A[k]) && A[k] > p.A)
      p = {A[k], phi_i[i], eps[jb], phi_prime_i[k], phi_prime_f[k]};
  }
  return p;
}

AmaxMap::AmaxMap(double n_, double alpha0_, const std::vector<double>& phi_i_,
                 const std::vector<double>& eps_)
    : n(n_), alpha0(alpha0_), phi_i(phi_i_), eps(eps_),
      A(phi_i_.size() * eps_.size(), std::numeric_limits<double>::quiet_NaN()),
      phi_prime_i(A), phi_prime_f(A)
{
}

AmaxMap amax_map(double n, double a0, const std::vector<double>& phi_i,
                 const std::vector<double>& eps)
{
  AmaxMap m(n, a0, phi_i, eps);
  const std::size_t ne = eps.size();
  const double a3 = a0 * a0 * a0;
  for (std::size_t i = 0; i < phi_i.size(); ++i)
  {
    const double pi = phi_i[i], pf = pi / a3;
    if (!(pi > 0.0 && pf < 1.0))
    {
      m.undefined += ne;
      continue;
    }
    // Closed forms: the free gel needs no root finding at all.
    const double chi_i = chi_free(pi, n), chi_f = chi_free(pf, n);
    const double stretch_i = 1.0 / std::cbrt(pi);
    double guess_i = -1.0, guess_f = -1.0; // warm starts along the row
    for (std::size_t j = 0; j < ne; ++j)
    {
      const double lambda = (1.0 + eps[j]) * stretch_i;
      const std::size_t k = i * ne + j;
      try
      {
        if (guess_i < 0.0)
          guess_i = std::min(1.0 / (lambda * lambda * lambda), 0.99);
        const double ppi = phi_constrained(chi_i, lambda, n, guess_i);
        const double ppf = phi_constrained(chi_f, lambda, n, guess_f > 0.0 ? guess_f : ppi);
        guess_i = ppi;
        guess_f = ppf;
        m.phi_prime_i[k] = ppi;
        m.phi_prime_f[k] = ppf;
        m.A[k] = std::sqrt(ppf / ppi); // Eq. 4.16 with alpha_par = 1
      }
      catch (const NonUniqueRoot&)
      {
        ++m.non_unique;
      }
    }
  }
  return m;
}

void write_csv(const AmaxMap& m, const std::string& path)
{
  std::ofstream f(path);
  if (!f)
    throw std::runtime_error("cannot write " + path);
  f.precision(12);
  const bool peo = !m.T_i.empty();
  std::vector<std::string> columns = {"phi_i", "eps_par", "A_max", "phi_prime_i", "phi_prime_f"};
  if (peo)
    columns.insert(columns.end(), {"T_i", "T_f"});
  f << gelx::units_line(columns, gelx::millimetre);
  for (std::size_t c = 0; c < columns.size(); ++c)
    f << (c ? "," : "") << columns[c];
  f << "\n";
  for (std::size_t i = 0; i < m.phi_i.size(); ++i)
    for (std::size_t j = 0; j < m.eps.size(); ++j)
    {
      const std::size_t k = i * m.eps.size() + j;
      f << m.phi_i[i] << "," << m.eps[j] << "," << m.A[k] << "," << m.phi_prime_i[k] << ","
        << m.phi_prime_f[k];
      if (peo)
        f << "," << m.T_i[i] << "," << m.T_f[i];
      f << "\n";
    }
}

} // namespace gelx::theory
