#include <gelx/solvers/deflation.h>
#include <gelx/solvers/buckling.h>
#include <gelx/io/parameters.h>
#include <gelx/common/petsc_utils.h>

#include <cmath>
#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <limits>

namespace gelx
{
namespace
{

/// The search's SNES defaults, set before the solver reads its options.
const std::string& with_search_defaults(const std::string& prefix)
{
  // Full steps: the deflated step is not a descent direction of |R| (it is scaled away from
  // the known solutions), so a decrease test on |R| would cut the steps that deflation makes
  set_default_option(prefix, "snes_linesearch_type", "basic");
  // A search that finds nothing ends by this limit: it is the cost of every failed search
  set_default_option(prefix, "snes_max_it", "50");
  return prefix;
}
} // namespace

DeflatedSystem::DeflatedSystem(NonlinearSystem& inner, const std::string& prefix)
    : SystemDecorator(inner), _power(real_option(prefix, "power", 2.0)),
      _shift(real_option(prefix, "shift", 1.0)), _work(inner.create_vector())
{
  PetscInt n;
  GELX_PETSC(VecGetSize(_work.get(), &n));
  _scale = 1 / std::sqrt(double(n));
  if (!(_power >= 1) || !(_shift >= 0))
    throw InputError("-" + prefix + "power must be >= 1 and -" + prefix
                                + "shift >= 0");
}

void DeflatedSystem::deflate(Vec solution) { _roots.push_back(copy_of(solution)); }

double DeflatedSystem::norm(Vec x) const
{
  PetscReal n;
  GELX_PETSC(VecNorm(x, NORM_2, &n));
  return _scale * n;
}

double DeflatedSystem::distance(Vec a, Vec b) const
{
  GELX_PETSC(VecWAXPY(_work.get(), -1.0, b, a));
  return norm(_work.get());
}

double DeflatedSystem::distance_to_nearest(Vec x) const
{
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& r : _roots)
    nearest = std::min(nearest, distance(x, r.get()));
  return nearest;
}

double DeflatedSystem::step_factor(Vec x, Vec y)
{
  // The step is -y (x <- x - y). With m_i = d_i^-p + shift, d_i = |x - r_i| = s |x - r_i|_2
  // (s = 1/sqrt(n)):
  //   grad(ln M) . dx = sum_i -p d_i^(-p-2) s^2 (x - r_i) . dx / m_i,  dx = -y
  double slope = 0;
  for (const auto& r : _roots)
  {
    GELX_PETSC(VecWAXPY(_work.get(), -1.0, r.get(), x));
    PetscScalar along;
    PetscReal d;
    GELX_PETSC(VecDot(_work.get(), y, &along));
    GELX_PETSC(VecNorm(_work.get(), NORM_2, &d));
    d *= _scale;
    const double m = std::pow(d, -_power) + _shift;
    slope += _power * std::pow(d, -_power - 2) * _scale * _scale * along / m;
  }
  return _inner.step_factor(x, y) / (1 - slope);
}

DeflationSolver::DeflationSolver(MPI_Comm comm, NonlinearSystem& system,
                                 const std::string& prefix)
    : _comm(comm), _system(system), _deflated(system, prefix),
      _newton(comm, with_search_defaults(prefix)), _prefix(prefix),
      _min_distance(real_option(prefix, "min_distance", 1e-6)),
      _max_solutions(int_option(prefix, "max_solutions", 20)), _K(system.create_matrix())
{
  _newton.bind(_deflated);
}

double DeflationSolver::distance(Vec a, Vec b) const
{
  return _deflated.distance(a, b);
}

std::unique_ptr<Equilibrium> DeflationSolver::solve(Vec guess)
{
  _deflated.set_state(guess);
  NewtonReport report = _newton.solve(_deflated);
  if (!report.converged)
    return nullptr;
  Vec x = _system.unknowns();
  const double nearest = _deflated.distance_to_nearest(x);
  if (nearest <= _min_distance * std::max(_deflated.norm(x), 1.0))
  {
    if (dolfinx::MPI::rank(_comm) == 0)
      std::printf("  deflation: converged %.3g from a known solution: not new\n", nearest);
    return nullptr;
  }
  auto found = std::make_unique<Equilibrium>();
  found->state = copy_of(x);
  found->newton = std::move(report);
  _system.tangent(_K);
  found->negative_eigenvalues = negative_eigenvalues(_comm, _K);
  _deflated.deflate(x);
  return found;
}

std::vector<Equilibrium> DeflationSolver::find(const std::vector<Vec>& guesses)
{
  std::vector<Equilibrium> found;
  for (Vec guess : guesses)
    while (int(_deflated.size()) < _max_solutions)
    {
      auto solution = solve(guess);
      if (!solution)
        break;
      found.push_back(std::move(*solution));
    }
  return found;
}

std::vector<Branch> deflated_continuation(
    DeflationSolver& solver, const std::vector<double>& loads,
    const std::function<void(double)>& set_load, Vec start,
    const std::function<std::vector<OwnedVec>(Vec)>& guesses_from,
    const std::function<void(const Branch&, const Equilibrium&)>& observe)
{
  const std::string search
      = choice_option(solver.prefix(), "search", "always", {"always", "at_bifurcations"});
  std::vector<Branch> branches;
  std::vector<std::size_t> alive; // branches with a point at the previous load
  for (double load : loads)
  {
    set_load(load);
    solver.clear();
    // The previous load's solutions: where the branches continue from and new ones start
    std::vector<OwnedVec> previous;
    std::vector<bool> search_from;
    for (std::size_t b : alive)
      previous.push_back(copy_of(branches[b].points.back().state.get()));
    if (alive.empty())
    {
      previous.push_back(copy_of(start));
      search_from.push_back(true);
    }

    std::vector<std::size_t> continued;
    for (std::size_t i = 0; i < alive.size(); ++i)
    {
      Branch& branch = branches[alive[i]];
      const int before = branch.points.back().negative_eigenvalues;
      auto point = solver.solve(previous[i].get());
      // New branches cross this one where its stability changes (or beyond its end)
      search_from.push_back(search == "always" || !point
                            || point->negative_eigenvalues != before);
      if (!point)
        continue;
      branch.loads.push_back(load);
      branch.points.push_back(std::move(*point));
      observe(branch, branch.points.back());
      continued.push_back(alive[i]);
    }
    for (std::size_t i = 0; i < previous.size(); ++i)
    {
      if (!search_from[i])
        continue;
      std::vector<OwnedVec> owned = guesses_from(previous[i].get());
      std::vector<Vec> guesses;
      for (const auto& g : owned)
        guesses.push_back(g.get());
      for (auto& point : solver.find(guesses))
      {
        branches.push_back({int(branches.size()), {load}, {}});
        branches.back().points.push_back(std::move(point));
        observe(branches.back(), branches.back().points.back());
        continued.push_back(branches.size() - 1);
      }
    }
    alive = continued;
  }
  return branches;
}

} // namespace gelx
