#include "taylor_remainder.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <gelx/common/petsc_utils.h>

namespace gelx::test
{

std::vector<double> TaylorResult::ratios() const
{
  std::vector<double> r;
  for (std::size_t k = 0; k + 1 < points.size(); ++k)
    r.push_back(points[k].remainder / points[k + 1].remainder);
  return r;
}

int TaylorResult::last_above_floor() const
{
  int k = -1;
  while (k + 1 < int(points.size()) && points[k + 1].remainder > floor_margin * round_off)
    ++k;
  return k;
}

std::vector<double> TaylorResult::asserted_ratios() const
{
  const std::vector<double> r = ratios();
  const int last = last_above_floor(); // ratio k uses points k and k + 1
  std::vector<double> asserted;
  for (int k = std::max(0, last - 3); k < last; ++k)
    asserted.push_back(r[k]);
  return asserted;
}

std::string TaylorResult::table() const
{
  const std::vector<double> r = ratios();
  const int last = last_above_floor();
  std::string text;
  char line[160];
  std::snprintf(line, sizeof line,
                "    %-10s %-10s %-13s %s   (round-off floor of e: %.2e, %d halvings of eps0 "
                "to an admissible state)\n",
                "eps", "e(eps)", "e/|eps K du|", "e(eps)/e(eps/2)", round_off, skipped);
  text += line;
  for (std::size_t k = 0; k < points.size(); ++k)
  {
    const TaylorPoint& p = points[k];
    std::snprintf(line, sizeof line, "    %.3e  %.3e  %.3e", p.eps, p.remainder, p.relative());
    text += line;
    if (k < r.size())
    {
      const int position = int(k) - (last - 3);
      std::snprintf(line, sizeof line, "     %.4f%s", r[k],
                    int(k) < last && position >= 0 ? "   <- asserted" : "");
      text += line;
    }
    text += int(k) == last ? "   (last point above the floor)\n" : "\n";
  }
  return text;
}

namespace
{
/// |R(x0 + eps du) - R0 - eps K du| and |eps K du|, or NaN when x0 + eps du is inadmissible.
/// Leaves the system's unknowns at x0 + eps du.
TaylorPoint remainder_at(NonlinearSystem& system, Vec x0, Vec du, Vec R0, Vec Kdu, double eps,
                         Vec work, const TaylorOptions& options)
{
  Vec x = system.unknowns();
  GELX_PETSC(VecWAXPY(x, eps, du, x0));
  system.unknowns_changed();
  TaylorPoint p{eps, NAN, NAN};
  if (!system.admissible())
    return p;
  system.residual(work);
  if (options.at_perturbed_state)
    options.at_perturbed_state(eps);
  GELX_PETSC(VecAXPY(work, -1.0, R0));
  GELX_PETSC(VecAXPY(work, -eps, Kdu));
  GELX_PETSC(VecNorm(work, NORM_2, &p.remainder));
  GELX_PETSC(VecNorm(Kdu, NORM_2, &p.linear));
  p.linear *= eps;
  return p;
}

/// splitmix64: a well-mixed 64-bit hash, mapped to [-1, 1]
double hash_to_unit(std::uint64_t i)
{
  std::uint64_t z = i + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return 2.0 * double(z >> 11) / double(1ULL << 53) - 1.0;
}
} // namespace

TaylorResult taylor_remainders(NonlinearSystem& system, Vec direction, const TaylorOptions& options)
{
  // The reference state: its unknowns, residual (first, as it may update state the tangent
  // reads, e.g. a contact active set) and the tangent's action on the direction
  Vec x = system.unknowns(), x0, R0 = system.create_vector(), Kdu = system.create_vector(),
      work = system.create_vector();
  GELX_PETSC(VecDuplicate(x, &x0));
  GELX_PETSC(VecCopy(x, x0));
  system.residual(R0);
  Mat K = system.create_matrix();
  system.tangent(K);
  GELX_PETSC(MatMult(K, direction, Kdu));
  MatDestroy(&K);

  TaylorResult result;
  result.floor_margin = options.floor_margin;
  auto at = [&](double eps)
  { return remainder_at(system, x0, direction, R0, Kdu, eps, work, options); };
  double eps = options.eps0;
  TaylorPoint p = at(eps);
  while (std::isnan(p.remainder) && result.skipped < 60)
  {
    eps /= 2;
    ++result.skipped;
    p = at(eps);
  }
  if (!std::isnan(p.remainder))
  {
    result.points.push_back(p);
    for (int k = 1; k <= options.halvings; ++k)
      result.points.push_back(at(eps / std::ldexp(1.0, k)));
    result.round_off = at(eps / std::ldexp(1.0, options.halvings + 15)).remainder;
  }

  // Back to the reference state; the residual once more re-evaluates there whatever the
  // system updates in residual()
  GELX_PETSC(VecCopy(x0, x));
  system.unknowns_changed();
  system.residual(work);
  VecDestroy(&x0);
  VecDestroy(&R0);
  VecDestroy(&Kdu);
  VecDestroy(&work);
  return result;
}

std::vector<PetscInt> identity_rows(NonlinearSystem& system)
{
  Vec r = system.create_vector();
  system.residual(r); // the state the rows depend on (e.g. the active set)
  PetscInt first;
  GELX_PETSC(VecGetOwnershipRange(r, &first, nullptr));
  VecDestroy(&r);
  std::vector<PetscInt> rows = system.prescribed_rows();
  for (PetscInt& row : rows)
    row += first;
  return rows;
}

Vec random_direction(NonlinearSystem& system, const std::vector<PetscInt>& fixed)
{
  Vec du = system.create_vector();
  PetscInt first, last;
  GELX_PETSC(VecGetOwnershipRange(du, &first, &last));
  PetscScalar* values;
  GELX_PETSC(VecGetArray(du, &values));
  for (PetscInt row = first; row < last; ++row)
    values[row - first] = hash_to_unit(row);
  for (PetscInt row : fixed)
    if (row >= first && row < last)
      values[row - first] = 0;
  GELX_PETSC(VecRestoreArray(du, &values));
  return du;
}

namespace
{
void print_table(MPI_Comm comm, const std::string& name, const TaylorResult& result)
{
  if (dolfinx::MPI::rank(comm) == 0)
    std::printf("%s: Taylor remainders\n%s", name.c_str(), result.table().c_str());
}
} // namespace

void check_second_order(Checks& checks, MPI_Comm comm, const std::string& name,
                        const TaylorResult& result)
{
  print_table(comm, name, result);
  const std::vector<double> ratios = result.asserted_ratios();
  checks.require(name + ": " + std::to_string(result.last_above_floor())
                     + " halvings above the round-off floor (at least 3)",
                 ratios.size() == 3);
  if (ratios.size() != 3)
    return;
  // 4 +- 0.5: the floor margin keeps round-off below ~1.5% of a ratio, and at these eps the
  // third-order term is negligible (e/|eps K du| ~ 1e-7..1e-6). A tangent error of relative
  // size tau in K du adds tau |eps K du| to e and gives 4 (tau + r) / (2 tau + r), r the exact
  // e/|eps K du|: below 3.5 once tau > r/6 at the smallest asserted eps.
  const TaylorPoint& smallest = result.points[result.last_above_floor()];
  char sensitivity[96];
  std::snprintf(sensitivity, sizeof sensitivity,
                " (fails for a tangent error above ~%.1e of |K du|)", smallest.relative() / 6);
  for (std::size_t i = 0; i < ratios.size(); ++i)
    checks.absolute(name + ": e(eps)/e(eps/2), smallest halvings above the floor #"
                        + std::to_string(i + 1) + (i == 2 ? sensitivity : ""),
                    ratios[i], 4.0, 0.5);
}

void check_first_order(Checks& checks, MPI_Comm comm, const std::string& name,
                       const TaylorResult& result)
{
  print_table(comm, name, result);
  const std::vector<double> ratios = result.asserted_ratios();
  checks.require(name + ": " + std::to_string(result.last_above_floor())
                     + " halvings above the round-off floor (at least 3)",
                 ratios.size() == 3);
  // 2 +- 0.5: the first-order part of a wrong tangent dominates e at the smallest eps, where
  // the ratio tends to 2; the band is disjoint from the [3.5, 4.5] of an exact tangent
  for (std::size_t i = 0; i < ratios.size(); ++i)
    checks.absolute(name + ": e(eps)/e(eps/2) of a wrong tangent, smallest halvings #"
                        + std::to_string(i + 1),
                    ratios[i], 2.0, 0.5);
}

void check_linear(Checks& checks, MPI_Comm comm, const std::string& name,
                  const TaylorResult& result)
{
  print_table(comm, name, result);
  checks.require(name + ": an admissible state to start from", !result.points.empty());
  if (result.points.empty())
    return;
  // At the largest eps, where |eps K du| is largest: a linear R leaves only the round-off of
  // assembling R and K du, ~1e-16 times the terms summed into an entry (measured 1e-16 to
  // 1e-15); a nonlinear one leaves e/|eps K du| ~ c eps, 6e-2 for the neo-Hookean state of
  // tests/taylor.cpp at its first admissible eps, and a tangent error tau leaves tau
  checks.absolute(name + ": e/|eps K du| at eps = " + std::to_string(result.points[0].eps)
                      + " (linear residual: round-off)",
                  result.points[0].relative(), 0.0, 1e-12);
}

} // namespace gelx::test
