#include "theory/peo.h"

#include "theory/flory_rehner.h"
#include "theory/roots.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gelx::theory
{

double chi_bar(double chi, double dchi_dphi, double phi) { return chi - (1.0 - phi) * dchi_dphi; }

double chi_bar_as_printed(double chi, double dchi_dphi, double phi)
{
  return chi - phi * dchi_dphi;
}

double PeoModel::Kp(double T) const { return std::exp(_p.energy_p / T - _p.entropy_p); }
double PeoModel::Kw(double T) const { return std::exp(_p.energy_w / T - _p.entropy_w); }

PeoModel::Bonds PeoModel::bonds(double T, double phi) const
{
  const double kp = Kp(T), kw = Kw(T), r = _p.v_over_vp;
  Bonds b{};
  b.q0 = 4.0 * kw / (1.0 + 4.0 * kw + std::sqrt(1.0 + 8.0 * kw));
  auto g = [&](double D)
  {
    const double up = 1.0 + 2.0 * kp * D, uw = 1.0 + 2.0 * kw * D;
    return std::pair{D - (1.0 - phi) / uw + phi * r * 2.0 * kp * D / up,
                     1.0 + (1.0 - phi) * 2.0 * kw / (uw * uw) + phi * r * 2.0 * kp / (up * up)};
  };
  // g(0) = -(1-phi) < 0 and g(1-phi) > 0: [0, 1-phi] brackets the unique root.
  const double hi = 1.0 - phi;
  b.D = safeguarded_newton(g, 0.0, hi, 0.5 * hi, 1e-16 * hi);
  b.p = 2.0 * kp * b.D / (1.0 + 2.0 * kp * b.D);
  b.q = 2.0 * kw * b.D / (1.0 + 2.0 * kw * b.D);
  return b;
}

std::pair<double, double> PeoModel::residuals(double T, double phi, const Bonds& b) const
{
  const double r = _p.v_over_vp;
  const double D = (1.0 - phi) * (1.0 - b.q) - b.p * phi * r; // as printed in A.5-A.6
  return {b.p / (2.0 * (1.0 - b.p) * D) / Kp(T) - 1.0,
          b.q / (2.0 * (1.0 - b.q) * D) / Kw(T) - 1.0};
}

double PeoModel::chi_bar(double T, double phi) const
{
  const Bonds b = bonds(T, phi);
  const double r = _p.v_over_vp;
  return chi(T) + 2.0 / phi * (b.p * r - b.q)
         + 2.0 / (phi * phi) * (b.q - b.q0 + std::log(b.q / (b.q0 * (1.0 - phi))));
}

double PeoModel::free_energy_hb(double T, double phi) const
{
  const Bonds b = bonds(T, phi);
  const double r = _p.v_over_vp, dp = _p.energy_p / T - _p.entropy_p,
               dw = _p.energy_w / T - _p.entropy_w;
  auto xlx = [](double x) { return x > 0.0 ? x * std::log(x) : 0.0; };
  const double s = 1.0 - phi;
  const double bound = b.q + b.p * phi / s * r; // water acceptor sites in use
  double F = 2.0 * phi * r * (xlx(b.p) + xlx(1.0 - b.p) - b.p * dp);
  F += 2.0 * s * (xlx(b.q) + xlx(1.0 - b.q) - b.q * dw);
  F += 2.0 * s * xlx(1.0 - bound);
  F -= 2.0 * s * bound * (std::log(2.0 * s) - 1.0);
  // Pure-water reference, Eq. A.3 last line (ln(2/e) = ln 2 - 1).
  F -= 2.0 * s
       * (xlx(b.q0) - b.q0 * dw + 2.0 * xlx(1.0 - b.q0) - b.q0 * (std::log(2.0) - 1.0));
  return F;
}

namespace
{
ValueAndSlope slope_by_difference(std::function<double(double)> f)
{
  // The scans and Newton steps only need a usable slope; a central difference is enough and
  // avoids differentiating the bond equilibrium analytically.
  return [f](double x)
  {
    const double h = 1e-7 * std::max(std::abs(x), 1e-3);
    return std::pair{f(x), (f(x + h) - f(x - h)) / (2.0 * h)};
  };
}
} // namespace

std::vector<double> peo_temperatures_free(const PeoModel& m, double phi, double n, double T_lo,
                                          double T_hi, int samples)
{
  const double target = chi_free(phi, n);
  auto g = slope_by_difference([&](double T) { return m.chi_bar(T, phi) - target; });
  return all_roots(g, T_lo, T_hi, samples, Spacing::uniform, 1e-10 * T_hi);
}

std::vector<double> peo_temperatures_constrained(const PeoModel& m, double phi,
                                                 double lambda_par, double n, double T_lo,
                                                 double T_hi, int samples)
{
  const double target = chi_constrained(phi, lambda_par, n);
  auto g = slope_by_difference([&](double T) { return m.chi_bar(T, phi) - target; });
  return all_roots(g, T_lo, T_hi, samples, Spacing::uniform, 1e-10 * T_hi);
}

std::vector<double> peo_phi_constrained(const PeoModel& m, double T, double lambda_par,
                                        double n, int samples)
{
  auto g = slope_by_difference([&](double phi)
                               { return m.chi_bar(T, phi) - chi_constrained(phi, lambda_par, n); });
  // Logit spacing but kept away from phi ~ 1e-16 where A.7 cancels badly: the scan covers
  // (1e-6, 1 - 1e-12), far beyond any physical gel.
  return all_roots(g, 1e-6, 1.0 - 1e-12, samples, Spacing::logit, 1e-14);
}

AmaxMap peo_amax_map(const PeoModel& model, double n, double a0,
                     const std::vector<double>& phi_i, const std::vector<double>& eps,
                     double T_lo, double T_hi)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  AmaxMap m(n, a0, phi_i, eps);
  const std::size_t ne = eps.size();
  m.T_i.assign(phi_i.size(), nan);
  m.T_f = m.T_i;
  for (std::size_t i = 0; i < phi_i.size(); ++i)
  {
    const double pi = phi_i[i], pf = pi / (a0 * a0 * a0);
    if (!(pf < 1.0))
    {
      m.undefined += ne;
      continue;
    }
    const auto Ti = peo_temperatures_free(model, pi, n, T_lo, T_hi);
    const auto Tf = peo_temperatures_free(model, pf, n, T_lo, T_hi);
    if (Ti.size() != 1 || Tf.size() != 1)
    {
      (Ti.size() > 1 || Tf.size() > 1 ? m.non_unique : m.undefined) += ne;
      continue;
    }
    m.T_i[i] = Ti[0];
    m.T_f[i] = Tf[0];
    for (std::size_t j = 0; j < ne; ++j)
    {
      const double lambda = (1.0 + eps[j]) / std::cbrt(pi);
      const auto ri = peo_phi_constrained(model, Ti[0], lambda, n);
      const auto rf = peo_phi_constrained(model, Tf[0], lambda, n);
      const std::size_t k = i * ne + j;
      if (ri.size() != 1 || rf.size() != 1)
      {
        (ri.size() > 1 || rf.size() > 1 ? m.non_unique : m.undefined) += 1;
        continue;
      }
      m.phi_prime_i[k] = ri[0];
      m.phi_prime_f[k] = rf[0];
      m.A[k] = std::sqrt(rf[0] / ri[0]);
    }
  }
  return m;
}

} // namespace gelx::theory
