#include <gelx/solvers/homotopy.h>

#include <gelx/common/petsc_utils.h>
#include <gelx/solvers/arclength.h>

#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <sstream>

namespace gelx
{

void follow_homotopy(NonlinearSystem& system, NewtonSolver& newton, LoadSteppingOptions options,
                     const std::function<void(double)>& apply_load, const StepObserver& observe,
                     const std::string& prefix)
{
  OwnedVec start = copy_of(system.unknowns());
  const std::vector<StepObserver> observers
      = observe ? std::vector<StepObserver>{observe} : std::vector<StepObserver>{};
  PathState steps;
  try
  {
    LoadStepper(system, newton, options, apply_load).run(steps, observers);
    return;
  }
  catch (const ConvergenceError& failed)
  {
    if (steps.step == 0)
      throw;
    if (dolfinx::MPI::rank(PetscObjectComm((PetscObject)newton.snes())) == 0)
      std::printf("  %s; by arc length from t = %.6g\n", failed.what(), steps.load);
  }

  // The state holds the last completed load step. Arc length in t from there, on the scale
  // of the way the load steps came.
  PetscReal moved;
  // start becomes x(t) - x(0): it is not needed after this
  GELX_PETSC(VecAYPX(start.get(), -1.0, system.unknowns()));
  GELX_PETSC(VecNorm(start.get(), NORM_2, &moved));
  OwnedVec before = copy_of(system.unknowns());
  double before_load = steps.load;
  const double psi = moved / steps.load;
  const MPI_Comm comm = PetscObjectComm((PetscObject)newton.snes());
  ArcLength continuation(comm, system, apply_load, prefix);
  continuation.set_default_scale(0.02 * psi, psi);
  PathState path;
  path.load = steps.load;
  StepRecord last;
  continuation.run(
      path, int_option(prefix, "max_steps", 200),
      {[&](const StepRecord& record, PathState& state)
       {
         if (observe)
           observe(record, state);
         last = record;
         if (record.load < 1)
         {
           GELX_PETSC(VecCopy(system.unknowns(), before.get()));
           before_load = record.load;
         }
       }},
      [](const StepRecord& record) { return record.load >= 1; });
  if (last.load < 1)
  {
    std::ostringstream msg;
    msg << "the homotopy's path did not reach t = 1 in " << path.step
        << " arc-length steps from t = " << steps.load << " (it reached t = " << last.load
        << "; more: -" << prefix << "max_steps)";
    throw ConvergenceError(msg.str());
  }

  // Land at t = 1 from the chord between the points around it
  GELX_PETSC(VecAXPBY(before.get(), (1 - before_load) / (last.load - before_load),
                      (last.load - 1) / (last.load - before_load), system.unknowns()));
  apply_load(1);
  system.set_state(before.get());
  StepRecord landing;
  landing.step = path.step + 1;
  landing.load = 1;
  landing.newton = newton.solve(system);
  if (!landing.newton.converged)
    throw ConvergenceError("the homotopy's path passed t = 1, but Newton at t = 1 from it failed ("
                           + landing.newton.reason + ")");
  if (observe)
    observe(landing, path);
}

} // namespace gelx
