#include <gelx/solvers/arclength.h>

#include <gelx/common/timing.h>
#include <gelx/systems/mixed.h>
#include <gelx/io/parameters.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/systems/problem.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <sstream>

namespace gelx
{
namespace
{
double dot(Vec a, Vec b)
{
  PetscScalar d;
  GELX_PETSC(VecDot(a, b, &d));
  return d;
}

PetscErrorCode shell_mult(Mat A, Vec v, Vec y)
{
  void* ctx;
  MatShellGetContext(A, &ctx);
  try
  {
    static_cast<const ArcLengthSystem*>(ctx)->apply_tangent(v, y);
  }
  catch (...)
  {
    return PETSC_ERR_LIB;
  }
  return 0;
}

PetscErrorCode shell_apply(PC pc, Vec r, Vec z)
{
  void* ctx;
  PCShellGetContext(pc, &ctx);
  try
  {
    static_cast<const ArcLengthSystem*>(ctx)->apply_inverse(r, z);
  }
  catch (const ConvergenceError&) // K could not be solved: a failed linear solve, not an error
  {
    PCSetFailedReason(pc, PC_SUBPC_ERROR);
    VecSetInf(z);
  }
  catch (...)
  {
    return PETSC_ERR_LIB;
  }
  return 0;
}

/// The SNES defaults of a continuation's corrector, set before the solver reads its options.
const std::string& with_corrector_defaults(const std::string& prefix)
{
  set_default_option(prefix, "snes_max_it", "15");
  // Full corrector steps: the bordered residual mixes forces and the arc-length condition, so a
  // decrease test on its norm is no measure of progress (admissibility still halves steps)
  set_default_option(prefix, "snes_linesearch_type", "basic");
  // An inadmissible corrector iterate ends the attempt: the remedy is the shorter arc length
  // that a failed attempt leads to, while a halved bordered step leaves the arc-length
  // condition and keeps iterating (measured on the inflated shell: the two attempts that fail
  // took 14 and 15 iterations with halvings, 3 and 2 without, on the same path)
  set_default_option(prefix, "admissible_halvings", "0");
  return prefix;
}

/// How a continuation tracks the stability of its points (-PREFIX_stability).
enum class Stability
{
  none,
  eigenvalue, ///< the tangent's eigenvalue nearest zero (SLEPc, lowest_tangent_eigenpair)
  inertia     ///< the tangent's negative eigenvalues, from its LDL^T factors
};

Stability stability_test(const std::string& prefix)
{
  const std::string name
      = choice_option(prefix, "stability", "none", {"none", "eigenvalue", "inertia"});
  if (name == "eigenvalue")
    return Stability::eigenvalue;
  return name == "inertia" ? Stability::inertia : Stability::none;
}

/// The inertia is read from the factorisation of K the predictor makes: make it an LDL^T one.
const std::string& with_stability_defaults(const std::string& prefix)
{
  if (stability_test(prefix) == Stability::inertia)
  {
    // An iterative set would be overridden by the factorisation without a word
    const std::string solver = string_option(prefix, "linear_solver", "direct");
    if (solver != "direct")
      throw InputError("-" + prefix + "stability inertia reads the inertia of a factorisation: "
                       "it needs -" + prefix + "linear_solver direct, not " + solver
                       + " (or -" + prefix + "stability eigenvalue)");
    default_to_symmetric_factorisation(prefix);
  }
  return prefix;
}
} // namespace

// --- The bordered system ------------------------------------------------------------------

ArcLengthSystem::ArcLengthSystem(NonlinearSystem& inner, std::function<void(double)> set_load,
                                 const std::string& prefix)
    : _inner(inner), _set_load(std::move(set_load)),
      _comm(PetscObjectComm((PetscObject)inner.unknowns()))
{
  _last_rank = dolfinx::MPI::rank(_comm) == dolfinx::MPI::size(_comm) - 1;
  GELX_PETSC(VecGetLocalSize(inner.unknowns(), &_n));
  GELX_PETSC(VecCreateMPI(_comm, _n + (_last_rank ? 1 : 0), PETSC_DETERMINE, &_x));
  join(inner.unknowns(), 0.0, _x);
  _K = inner.create_matrix();
  _ksp = create_linear_solver(_comm, prefix);
  // K is the wrapped system's tangent, so a field split of it has that system's fields
  prepare_linear_solver(_ksp, inner);
  for (Vec* v : {&_g, &_x0, &_f, &_b, &_work, &_work2})
    *v = inner.create_vector();
}

ArcLengthSystem::~ArcLengthSystem()
{
  KSPDestroy(&_ksp);
  MatDestroy(&_K);
  for (Vec* v : {&_x, &_g, &_x0, &_f, &_b, &_work, &_work2})
    VecDestroy(v);
}

double ArcLengthSystem::split(Vec v, Vec x) const
{
  const PetscScalar* from;
  PetscScalar* to;
  GELX_PETSC(VecGetArrayRead(v, &from));
  GELX_PETSC(VecGetArray(x, &to));
  std::copy_n(from, _n, to);
  double lambda = _last_rank ? from[_n] : 0.0;
  GELX_PETSC(VecRestoreArray(x, &to));
  GELX_PETSC(VecRestoreArrayRead(v, &from));
  MPI_Bcast(&lambda, 1, MPI_DOUBLE, dolfinx::MPI::size(_comm) - 1, _comm);
  return lambda;
}

void ArcLengthSystem::join(Vec x, double lambda, Vec v) const
{
  const PetscScalar* from;
  PetscScalar* to;
  GELX_PETSC(VecGetArrayRead(x, &from));
  GELX_PETSC(VecGetArray(v, &to));
  std::copy_n(from, _n, to);
  if (_last_rank)
    to[_n] = lambda;
  GELX_PETSC(VecRestoreArray(v, &to));
  GELX_PETSC(VecRestoreArrayRead(x, &from));
}

void ArcLengthSystem::pack(Vec x, double lambda, Vec bordered) const { join(x, lambda, bordered); }

void ArcLengthSystem::set_constraint(Vec x0, double l0, double ds, double psi)
{
  GELX_PETSC(VecCopy(x0, _x0));
  _l0 = l0;
  _ds = ds;
  _psi = psi;
}

void ArcLengthSystem::unknowns_changed()
{
  _lambda = split(_x, _inner.unknowns());
  _inner.unknowns_changed();
  _set_load(_lambda);
}

void ArcLengthSystem::residual(Vec r)
{
  _inner.residual(_work);
  GELX_PETSC(VecWAXPY(_work2, -1.0, _x0, _inner.unknowns()));
  const double dl = _lambda - _l0;
  const double c = (dot(_work2, _work2) + _psi * _psi * dl * dl - _ds * _ds) / (2 * _ds);
  join(_work, c, r);
}

bool ArcLengthSystem::project(Vec x)
{
  const double lambda = split(x, _work);
  GELX_PETSC(VecAXPY(_work, -1.0, _x0)); // w = x - x0, then w - eta b on the sphere
  const double mu = lambda - _l0, psi2 = _psi * _psi;
  const double A = dot(_b, _b) + psi2, B = 2 * (psi2 * mu - dot(_work, _b)),
               C = dot(_work, _work) + psi2 * mu * mu - _ds * _ds;
  const double disc = B * B - 4 * A * C;
  if (!(A > 0) || !(disc >= 0))
    return false; // no point of the sphere along this line: the Newton step stands
  // The root of smaller magnitude, in the form without cancellation
  const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
  const double eta = q != 0 ? C / q : 0.0;
  GELX_PETSC(VecAXPBYPCZ(_work, 1.0, -eta, 1.0, _x0, _b)); // x0 + w - eta b
  join(_work, lambda + eta, x);
  return true;
}

void ArcLengthSystem::load_derivative(Vec f)
{
  const double h = 1e-4 * std::max(1.0, std::abs(_lambda));
  _set_load(_lambda + h);
  _inner.residual(f);
  _set_load(_lambda - h);
  _inner.residual(_work2);
  _set_load(_lambda);
  GELX_PETSC(VecAXPY(f, -1.0, _work2));
  GELX_PETSC(VecScale(f, 1.0 / (2 * h)));
}

void ArcLengthSystem::assemble_tangent() { _inner.tangent(_K); }

void ArcLengthSystem::solve_tangent(Vec b, Vec y)
{
  GELX_PETSC(KSPSetOperators(_ksp, _K, _K));
  GELX_PETSC(KSPSolve(_ksp, b, y));
  KSPConvergedReason reason;
  GELX_PETSC(KSPGetConvergedReason(_ksp, &reason));
  if (reason < 0)
    throw ConvergenceError(std::string("the tangent could not be solved: ")
                           + KSPConvergedReasons[reason]);
}

int ArcLengthSystem::tangent_negative_eigenvalues() const
{
  return factored_negative_eigenvalues(_ksp);
}

void ArcLengthSystem::tangent(Mat)
{
  GELX_PETSC(VecWAXPY(_g, -1.0, _x0, _inner.unknowns()));
  GELX_PETSC(VecScale(_g, 1.0 / _ds));
  _g_l = _psi * _psi * (_lambda - _l0) / _ds;
  load_derivative(_f);
  // K is factorised, and b = K^-1 f solved, at the first apply_inverse: inside the bordered
  // system's KSPSolve, which times it as solving, not inside the tangent's evaluation
  _inner.tangent(_K);
  _factorised = false;
}

void ArcLengthSystem::apply_tangent(Vec v, Vec y) const
{
  const double v_l = split(v, _work);
  GELX_PETSC(MatMult(_K, _work, _work2));
  GELX_PETSC(VecAXPY(_work2, v_l, _f));
  join(_work2, dot(_g, _work) + _g_l * v_l, y);
}

void ArcLengthSystem::apply_inverse(Vec r, Vec z) const
{
  const NestedSolves nested; // the bordered KSPSolve around this call times them
  const auto solve = [this](Vec rhs, Vec y)
  {
    GELX_PETSC(KSPSolve(_ksp, rhs, y));
    KSPConvergedReason reason;
    GELX_PETSC(KSPGetConvergedReason(_ksp, &reason));
    if (reason < 0)
      throw ConvergenceError("K^-1 failed");
  };
  if (!_factorised)
  {
    GELX_PETSC(KSPSetOperators(_ksp, _K, _K));
    solve(_f, _b);
    _factorised = true;
  }
  const double r_l = split(r, _work);
  solve(_work, _work2); // a = K^-1 r_x
  const double d_l = (r_l - dot(_g, _work2)) / (_g_l - dot(_g, _b));
  GELX_PETSC(VecAXPY(_work2, -d_l, _b));
  join(_work2, d_l, z);
}

Vec ArcLengthSystem::create_vector() const
{
  Vec v;
  GELX_PETSC(VecDuplicate(_x, &v));
  return v;
}

Mat ArcLengthSystem::create_matrix() const
{
  PetscInt local, global;
  GELX_PETSC(VecGetLocalSize(_x, &local));
  GELX_PETSC(VecGetSize(_x, &global));
  Mat A;
  GELX_PETSC(MatCreateShell(_comm, local, local, global, global,
                            const_cast<ArcLengthSystem*>(this), &A));
  GELX_PETSC(MatShellSetOperation(A, MATOP_MULT, (void (*)(void))shell_mult));
  return A;
}

void ArcLengthSystem::configure(SNES snes) const
{
  KSP ksp;
  PC pc;
  const char* prefix;
  GELX_PETSC(SNESGetOptionsPrefix(snes, &prefix));
  GELX_PETSC(SNESGetKSP(snes, &ksp));
  GELX_PETSC(KSPSetOptionsPrefix(ksp, (std::string(prefix ? prefix : "") + "bordered_").c_str()));
  GELX_PETSC(KSPSetType(ksp, KSPPREONLY));
  GELX_PETSC(KSPGetPC(ksp, &pc));
  GELX_PETSC(PCSetType(pc, PCSHELL));
  GELX_PETSC(PCShellSetContext(pc, const_cast<ArcLengthSystem*>(this)));
  GELX_PETSC(PCShellSetApply(pc, shell_apply));
}

// --- The path -----------------------------------------------------------------------------

ArcLength::ArcLength(MPI_Comm comm, NonlinearSystem& system,
                     std::function<void(double)> set_load, const std::string& prefix)
    : _comm(comm), _system(system),
      _bordered(system, std::move(set_load), with_stability_defaults(prefix)),
      _newton(comm, with_corrector_defaults(prefix)), _prefix(prefix),
      _load(system.create_vector())
{
  // The corrector's options are read now: read at its first solve, they would replace the
  // residual tolerance run() sets for that step (a restarted path's first step would then
  // converge to a tighter tolerance than the uninterrupted path's)
  _newton.bind(_bordered);
}

double ArcLength::tangent_direction(const PathState& state, double psi, Vec t)
{
  // K dx/ds + f dlambda/ds = 0: the direction (-K^-1 f, 1), scaled to unit length
  {
    const TimedAssembly assembly; // outside the corrector's SNES, whose events do not see it
    _bordered.load_derivative(_load.get());
    _bordered.assemble_tangent();
  }
  _bordered.solve_tangent(_load.get(), t);
  const double norm = std::sqrt(dot(t, t) + psi * psi);
  GELX_PETSC(VecScale(t, -1.0 / norm));
  double t_l = 1.0 / norm;
  // Keep going the way the path went: through a limit point lambda decreases
  if (state.direction && dot(t, state.direction.get()) + psi * psi * t_l * state.load_direction < 0)
  {
    GELX_PETSC(VecScale(t, -1.0));
    t_l = -t_l;
  }
  return t_l;
}

bool ArcLength::ahead_of(Vec x0, double l0, Vec t, double t_l, double psi)
{
  OwnedVec step(_system.create_vector());
  GELX_PETSC(VecWAXPY(step.get(), -1.0, x0, _system.unknowns()));
  return dot(step.get(), t) + psi * psi * (_bordered.load_factor() - l0) * t_l > 0;
}

double ArcLength::switch_branch(PathState& state)
{
  Vec bordered = _bordered.create_vector();
  _bordered.pack(_system.unknowns(), state.load, bordered);
  _bordered.set_state(bordered);
  VecDestroy(&bordered);
  _bordered.inner().tangent(_bordered.inner_tangent());
  const BucklingMode mode = lowest_tangent_eigenpair(_comm, _bordered.inner_tangent(),
                                                     _system.problem().u()->function_space());
  // The mode in the unknowns' layout
  Vec direction = _system.create_vector();
  PetscScalar* values;
  GELX_PETSC(VecGetArray(direction, &values));
  const auto& shape = mode.shape->x()->array();
  const auto& row_of = _system.unknown_of_problem_dof();
  for (std::size_t i = 0; i < row_of.size(); ++i)
    if (row_of[i] >= 0)
      values[row_of[i]] = shape[i];
  GELX_PETSC(VecRestoreArray(direction, &values));
  PetscReal norm;
  GELX_PETSC(VecNormalize(direction, &norm));
  state.direction.reset(direction);
  state.load_direction = 0;
  state.stability = mode.load_factor;
  _switch_pending = true;
  return mode.load_factor;
}

void ArcLength::run(PathState& state, int max_steps, const std::vector<StepObserver>& observers,
                    const std::function<bool(const StepRecord&)>& stop)
{
  // The bounds scale with the first step's size, also on a continued path (whose next step
  // size has moved away from it)
  const double ds_first = real_option(_prefix, "ds", _default_ds);
  const double ds_max = real_option(_prefix, "ds_max", 10 * ds_first);
  const double ds_min = real_option(_prefix, "ds_min", 1e-6 * ds_first);
  double ds = state.step_size > 0 ? state.step_size : ds_first;
  const double psi = real_option(_prefix, "psi", _default_psi);
  const int target_it = int_option(_prefix, "target_it", 5);
  const double rtol = real_option(_prefix, "rtol", 1e-9);
  const Stability stability = stability_test(_prefix);
  PetscReal atol;
  GELX_PETSC(SNESGetTolerances(_newton.snes(), &atol, nullptr, nullptr, nullptr, nullptr));
  const bool root = dolfinx::MPI::rank(_comm) == 0;

  if (state.step > 0)
  {
    StepRecord last;
    last.step = state.step;
    last.load = state.load;
    last.arc_length = state.arc_length;
    last.stability = state.stability;
    last.negative_eigenvalues = state.negative_eigenvalues;
    if (stop(last))
      return;
  }
  CompletedPoint point(_system); // the last point, restored after a failed attempt
  Vec x0 = point.unknowns();
  OwnedVec t(_system.create_vector());
  OwnedVec bordered(_bordered.create_vector()), last_point(_bordered.create_vector());
  // The predictor's direction at the current point, along the path's tangent or along the
  // crossing branch's mode; its solve factorises the tangent there, whose inertia is then
  // the point's stability at no extra cost
  double t_l = 0;
  auto predictor_direction = [&]
  {
    _bordered.pack(_system.unknowns(), state.load, bordered.get());
    _bordered.set_state(bordered.get());
    if (_switch_pending)
    {
      GELX_PETSC(VecCopy(state.direction.get(), t.get()));
      _bordered.load_derivative(_load.get());
      t_l = 0;
    }
    else
      t_l = tangent_direction(state, psi, t.get());
  };
  predictor_direction();
  while (state.step < max_steps)
  {
    const auto start = std::chrono::steady_clock::now();
    point.save();
    const double l0 = state.load;
    int cutbacks = 0;
    NewtonReport report;
    // |dR/dlambda| is the force scale of the residual test
    PetscReal f_norm;
    GELX_PETSC(VecNorm(_load.get(), NORM_2, &f_norm));
    GELX_PETSC(SNESSetTolerances(_newton.snes(), std::max<double>(atol, rtol * f_norm),
                                 PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
    while (true)
    {
      GELX_PETSC(VecWAXPY(_system.unknowns(), ds, t.get(), x0));
      _bordered.pack(_system.unknowns(), l0 + ds * t_l, bordered.get());
      _bordered.set_constraint(x0, l0, ds, psi);
      _bordered.pack(x0, l0, last_point.get());
      _bordered.set_state(bordered.get());
      report = _newton.correct(_bordered, last_point.get());
      // The arc-length sphere meets the path behind the last point as well as ahead of it, and
      // a corrector that wandered (next to a nearly singular tangent, where one Newton step
      // from a close start can throw the iterate far) can converge to the point behind: the
      // path would then retrace itself, with every later predictor oriented backwards. Only a
      // point ahead along the predictor's direction is a step; one behind is retried with a
      // shorter arc length.
      if (report.converged && !ahead_of(x0, l0, t.get(), t_l, psi))
      {
        report.converged = false;
        report.reason = "converged behind the last point";
      }
      if (report.converged)
        break;
      // Failed: back to the last point with half the arc length
      point.restore();
      _bordered.pack(x0, l0, bordered.get());
      _bordered.set_state(bordered.get());
      ds *= 0.5;
      ++cutbacks;
      ++state.cutbacks;
      if (root)
        std::printf("  arc-length step failed (%s): ds -> %.4g\n", report.reason.c_str(), ds);
      if (ds < ds_min)
      {
        std::ostringstream msg;
        msg << "arc-length step " << state.step + 1 << " failed at lambda = " << l0
            << " with the arc length below ds_min = " << ds_min << " (" << report.reason << ")";
        throw ConvergenceError(msg.str());
      }
    }
    const double lambda = _bordered.load_factor();
    // The step's direction (dx/ds, dlambda/ds) orients the next predictor
    if (!state.direction)
      state.direction.reset(_system.create_vector());
    GELX_PETSC(VecWAXPY(state.direction.get(), -1.0, x0, _system.unknowns()));
    GELX_PETSC(VecScale(state.direction.get(), 1.0 / ds));
    const double previous_load_direction = state.load_direction;
    state.load_direction = (lambda - l0) / ds;
    _switch_pending = false;

    StepRecord record;
    record.step = ++state.step;
    record.load = state.load = lambda;
    record.step_size = ds;
    record.arc_length = state.arc_length += ds;
    record.newton = report;
    record.cutbacks = cutbacks;
    record.limit_point = previous_load_direction * state.load_direction < 0;
    // A limit point between the two points is where the tangent's load component changes
    // sign: the tangent's determinant changes sign there too, so one eigenvalue crossing is
    // the limit point's and no bifurcation. (The secant's load direction, limit_point, can
    // lag a step behind: a point just past a maximum may still lie above the point before.)
    const double previous_t_l = t_l;
    predictor_direction();
    const bool limit_in_tangent = previous_t_l * t_l < 0;
    if (stability == Stability::eigenvalue)
    {
      const double previous = state.stability;
      state.stability = lowest_tangent_eigenpair(_comm, _bordered.inner_tangent(),
                                                 _system.problem().u()->function_space())
                            .load_factor;
      record.stability = state.stability;
      record.bifurcation = !limit_in_tangent && previous * state.stability < 0;
    }
    else if (stability == Stability::inertia)
    {
      const int previous = state.negative_eigenvalues;
      state.negative_eigenvalues = _bordered.tangent_negative_eigenvalues();
      record.negative_eigenvalues = state.negative_eigenvalues;
      const int crossings = std::abs(state.negative_eigenvalues - previous);
      record.bifurcation = previous >= 0 && crossings > (limit_in_tangent ? 1 : 0);
    }
    ds = std::min(ds_max, ds * std::clamp(std::sqrt(double(target_it)
                                                    / std::max(report.iterations, 1)),
                                          0.5, 2.0));
    state.step_size = ds;
    record.wall_time
        = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (const auto& observe : observers)
      observe(record, state);
    if (stop(record))
      return;
  }
}

std::pair<double, double> parabola_vertex(const double s[3], const double l[3])
{
  // lambda(s) = c0 + c1 s + c2 s^2 through the three points (divided differences)
  const double d01 = (l[1] - l[0]) / (s[1] - s[0]), d12 = (l[2] - l[1]) / (s[2] - s[1]);
  const double c2 = (d12 - d01) / (s[2] - s[0]);
  const double c1 = d01 - c2 * (s[0] + s[1]);
  const double c0 = l[0] - c1 * s[0] - c2 * s[0] * s[0];
  const double sv = -c1 / (2 * c2);
  return {sv, c0 + c1 * sv + c2 * sv * sv};
}

} // namespace gelx
