#pragma once
/// @file deflation.h
/// Distinct equilibria at one load, and branches of them over a range of loads, by deflation
/// (P. E. Farrell, A. Birkisson, S. W. Funke, SIAM J. Sci. Comput. 37 (2015) A2026; deflated
/// continuation: P. E. Farrell, C. H. L. Beentjes, A. Birkisson, arXiv:1603.00809).

#include <gelx/solvers/newton.h>
#include <gelx/solvers/path.h>
#include <functional>
#include <memory>
#include <mpi.h>
#include <string>
#include <vector>

namespace gelx
{

/// A system whose known solutions r_i are made unreachable: Newton's method on the deflated
/// residual G(x) = M(x) R(x) with the shifted deflation operator
///   M(x) = prod_i (|x - r_i|^-p + shift),
/// which is singular at every r_i (G does not vanish there for p >= 1) and tends to a constant
/// far from them (the shift keeps the iteration from running off to infinity, where M R -> 0
/// for shift 0). Newton's step for G is Newton's step dx for R scaled (the paper's Eq. 3.4):
///   dx_G = dx / (1 - grad(ln M) . dx),
/// so the system is R itself with this factor as its step_factor() hook: tangent, line
/// search and convergence test stay those of R, and at a new solution R = 0 as for G.
/// |.| is the root mean square of the unknowns, |x|_2 / sqrt(n): a displacement in length
/// units whatever the mesh size, so that the shift means the same on every mesh (with the
/// 2-norm, the distances of a column's states grow with the node count, and M stays near
/// the shift around every root: measured, deflation then did not repel at all).
/// Options (prefix `deflation_` by default): power p (2) and shift (1).
class DeflatedSystem : public SystemDecorator
{
public:
  explicit DeflatedSystem(NonlinearSystem& inner, const std::string& prefix = "deflation_");

  /// Deflate `solution` (copied) from now on.
  void deflate(Vec solution);
  /// Forget every deflated solution.
  void clear() { _roots.clear(); }
  std::size_t size() const { return _roots.size(); }
  /// |x| and |a - b| in the operator's norm.
  double norm(Vec x) const;
  double distance(Vec a, Vec b) const;
  /// The smallest distance |x - r_i| to a deflated solution (+inf without one).
  double distance_to_nearest(Vec x) const;

  double step_factor(Vec x, Vec y) override;

private:
  std::vector<OwnedVec> _roots;
  double _power, _shift;
  double _scale; ///< 1 / sqrt(n): the norm's weight
  OwnedVec _work;
};

/// One equilibrium found by deflation.
struct Equilibrium
{
  OwnedVec state;            ///< the unknowns
  NewtonReport newton;       ///< the solve that found it
  int negative_eigenvalues;  ///< of the tangent there (its inertia): 0 = stable
};

/// Finds distinct equilibria of a system at its current load by deflation: from each initial
/// guess, Newton's method (SNES with options prefix PREFIX: -PREFIX_snes_*, -PREFIX_ksp_*, ...;
/// -PREFIX_power, -PREFIX_shift for the operator) is restarted with every solution found so
/// far deflated, until it fails to converge (or -PREFIX_max_solutions are found).
///
/// A solution nearer than -PREFIX_min_distance (1e-6 |x|, relative) to a known one counts as
/// a failure, never as a new solution: the convergence test measures R, not the deflated
/// residual, so a solve could end beside a deflated root. The stability of each solution is
/// the inertia of its tangent (negative_eigenvalues, an LDL^T factorisation with options
/// prefix `inertia_`): it needs a symmetric tangent.
///
/// Newton's step keeps every symmetry the problem and the guess share (a straight column's
/// iterates stay straight): deflation cannot break a symmetry, so a guess must.
class DeflationSolver
{
public:
  DeflationSolver(MPI_Comm comm, NonlinearSystem& system,
                  const std::string& prefix = "deflation_");

  /// Forget every deflated solution (before a new load).
  void clear() { _deflated.clear(); }
  /// Deflate a solution found otherwise (the end of a path): solve() from it could not
  /// confirm it, since its residual is already at the level round-off keeps it at, and the
  /// relative tolerance asks for 1e-10 of that.
  void deflate(Vec solution) { _deflated.deflate(solution); }

  /// Solve from `guess` with the known solutions deflated; the converged state, if it is a new
  /// solution (then deflated from now on), or nothing.
  std::unique_ptr<Equilibrium> solve(Vec guess);
  /// Every new solution found from `guesses`, in the order found.
  std::vector<Equilibrium> find(const std::vector<Vec>& guesses);

  /// The distance |a - b| in the norm of the deflation operator.
  double distance(Vec a, Vec b) const;
  const std::string& prefix() const { return _prefix; }

private:
  MPI_Comm _comm;
  NonlinearSystem& _system;
  DeflatedSystem _deflated;
  NewtonSolver _newton;
  std::string _prefix;
  double _min_distance;
  int _max_solutions;
  Mat _K = nullptr;
};

/// A branch of a deflated continuation: its equilibria at consecutive loads.
struct Branch
{
  int id;                   ///< in the order the branches were found
  std::vector<double> loads; ///< from the load where it was found
  std::vector<Equilibrium> points;
};

/// Deflated continuation over the loads `loads` (Farrell, Beentjes & Birkisson): at each load,
/// every branch alive at the previous load is continued from its last solution, the
/// solutions found so far at this load deflated (so that two branches cannot land on the
/// same solution); then new branches are sought, with all solutions at this load deflated,
/// from the guesses `guesses_from(x)` makes of every solution x at the previous load (of
/// `start` at the first load): x itself and, where the problem has a symmetry that Newton's
/// step keeps, x perturbed out of it. A branch whose continuation fails ends there.
/// `set_load(lambda)` applies a load; `observe(branch, point)` sees every new point.
///
/// -PREFIX_search (the solver's prefix): `always` (the method as published: every search
/// costs at least one failed solve, -PREFIX_snes_max_it iterations, per guess and load) or
/// `at_bifurcations`: only from the solutions whose branch changed its number of negative
/// eigenvalues between the two loads (or ended), where stability theory says branches cross
/// (tests/column_deflation.cpp, whose bifurcations are all of this kind).
std::vector<Branch> deflated_continuation(
    DeflationSolver& solver, const std::vector<double>& loads,
    const std::function<void(double)>& set_load, Vec start,
    const std::function<std::vector<OwnedVec>(Vec)>& guesses_from,
    const std::function<void(const Branch&, const Equilibrium&)>& observe);

} // namespace gelx
