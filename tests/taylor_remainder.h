#pragma once
/// @file taylor_remainder.h
/// Taylor test of the tangent of any gelx::NonlinearSystem.
///
/// At a state u and a direction du, the remainder
///   e(eps) = |R(u + eps du) - R(u) - eps K(u) du|
/// is O(eps^2) when K is the derivative of R, so halving eps divides it by 4; with a wrong
/// tangent it keeps a first-order part (K - dR/du) du eps that eventually dominates, and the
/// ratio falls to 2. Newton's method then converges linearly, which no other check notices.
///
/// Which eps are judged: the sequence starts at the first admissible eps0 / 2^k and runs 30
/// halvings; the round-off floor of e is measured at an eps 2^15 times smaller still, and the
/// asserted ratios are those of the three smallest halvings whose remainders exceed 100 times
/// that floor. There the round-off moves a ratio by less than ~1.5%, and the terms above second
/// order are negligible (e/|eps K du| ~ 1e-7..1e-6 in tests/taylor.cpp), so an exact tangent
/// gives 4 well within [3.5, 4.5], while a tangent error of relative size tau adds
/// tau |eps K du| to e and takes the ratio below 3.5 once tau exceeds ~1/6 of e/|eps K du|.
/// The floor is measured rather than fixed (e.g. stopping at e = 1e-8 |eps K du|) because it
/// depends on the system (1e-16 to 1e-14 absolute in tests/taylor.cpp), and the sequence is not
/// stopped by e/|eps K du| because a wrong tangent never takes it below tau.

#include "support.h"

#include <functional>
#include <gelx/systems/problem.h>
#include <petscmat.h>
#include <petscvec.h>
#include <string>
#include <vector>

namespace gelx::test
{

/// One step of the Taylor test.
struct TaylorPoint
{
  double eps;
  double remainder; ///< e(eps)
  double linear;    ///< |eps K du|, the size of the first-order term
  /// e(eps) / |eps K du|: about c eps (c the curvature along du) for an exact tangent, the
  /// relative error of K du for a wrong one, the round-off of R over |eps K du| for a linear R
  double relative() const { return remainder / linear; }
};

struct TaylorOptions
{
  /// First step tried; halved while u + eps du is inadmissible (e.g. J <= phi0 of a gel)
  double eps0 = 1.0;
  /// Halvings after the first admissible eps. 30 take an exact tangent's remainder (x 1/4 each)
  /// down to the round-off floor from any start, and a wrong tangent's (x 1/2 once its
  /// first-order part dominates) far into the range where it does.
  int halvings = 30;
  /// A point is above the round-off floor when its remainder exceeds the round-off of R by this
  /// factor: the round-off then moves a ratio of two such remainders by at most ~1.5%.
  double floor_margin = 100;
  /// Called after the residual at every perturbed state, with its eps (e.g. to check that a
  /// contact active set has not changed)
  std::function<void(double eps)> at_perturbed_state;
};

/// The sequence eps_k = eps_start / 2^k and its remainders.
struct TaylorResult
{
  std::vector<TaylorPoint> points;
  int skipped = 0; ///< halvings of eps0 before u + eps du was admissible
  /// The round-off floor of e: e(eps) at eps = eps_start / 2^(halvings + 15), where the
  /// second-order term (~4^-45 of its value at eps_start) is far below the round-off of
  /// R(u + eps du) - R(u) and of representing u + eps du
  double round_off = 0;
  double floor_margin = 0;
  /// e(eps_k) / e(eps_{k+1}): 4 for an exact tangent, 2 for a wrong one
  std::vector<double> ratios() const;
  /// Index of the smallest eps whose remainder exceeds floor_margin * round_off (-1: none)
  int last_above_floor() const;
  /// The ratios of the three smallest halvings above the floor (fewer if there are fewer)
  std::vector<double> asserted_ratios() const;
  /// One line per point: eps, e, e / |eps K du|, ratio, and whether it is asserted
  std::string table() const;
};

/// Runs the Taylor test at the system's current unknowns along `direction` (a vector of the
/// system's layout) and leaves the unknowns, residual state included, as they were. Collective.
TaylorResult taylor_remainders(NonlinearSystem& system, Vec direction,
                               const TaylorOptions& options = {});

/// Global indices of the owned rows that prescribe a value at the current unknowns
/// (NonlinearSystem::prescribed_rows: Dirichlet dofs, prescribed macro unknowns, nodes in
/// contact), whose equation is u_i = const and whose tangent row is the identity. Collective.
std::vector<PetscInt> identity_rows(NonlinearSystem& system);

/// A direction in the system's layout with entries in [-1, 1] that depend on the global row
/// index only (reproducible, the same on every rank count for the same numbering), zero in the
/// rows `fixed`. The caller owns the vector. Collective.
Vec random_direction(NonlinearSystem& system, const std::vector<PetscInt>& fixed);

/// Require second order: at least three halvings above the floor, and the ratios of the three
/// smallest in [3.5, 4.5]. Prints the table on rank 0.
void check_second_order(Checks& checks, MPI_Comm comm, const std::string& name,
                        const TaylorResult& result);

/// Require first order, for negative controls (a deliberately wrong tangent): at least three
/// halvings above the floor, and the ratios of the three smallest in [1.5, 2.5]. Prints the
/// table on rank 0.
void check_first_order(Checks& checks, MPI_Comm comm, const std::string& name,
                       const TaylorResult& result);

/// Require a linear residual: the relative remainder at round-off at every point. Prints the
/// table on rank 0.
void check_linear(Checks& checks, MPI_Comm comm, const std::string& name,
                  const TaylorResult& result);

} // namespace gelx::test
