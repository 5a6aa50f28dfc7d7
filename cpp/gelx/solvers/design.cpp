#include <gelx/solvers/design.h>

#include <gelx/common/petsc_utils.h>
#include <gelx/solvers/homotopy.h>

#include <dolfinx/common/MPI.h>
#include <dolfinx/la/petsc.h>

namespace gelx
{

namespace
{
PetscErrorCode objective_and_gradient(Tao, Vec p, PetscReal* J, Vec gradient, void* context)
{
  auto& optimizer = *static_cast<DesignOptimizer*>(context);
  return guarded_callback(optimizer.callback_error,
                          [&] { *J = optimizer.evaluate(p, gradient); });
}

PetscErrorCode monitor(Tao, void* context)
{
  auto& optimizer = *static_cast<DesignOptimizer*>(context);
  return guarded_callback(optimizer.callback_error, [&] { optimizer.iterate_accepted(); });
}

/// A vector of parameters from their values (the same on every rank)
void set_parameters(Vec v, const std::vector<double>& values)
{
  PetscInt first, last;
  GELX_PETSC(VecGetOwnershipRange(v, &first, &last));
  for (PetscInt k = first; k < last; ++k)
    GELX_PETSC(VecSetValue(v, k, values.at(k), INSERT_VALUES));
  GELX_PETSC(VecAssemblyBegin(v));
  GELX_PETSC(VecAssemblyEnd(v));
}

/// All entries of a vector whose entries rank 0 owns, on every rank
std::vector<double> on_every_rank(Vec v, MPI_Comm comm)
{
  PetscInt n, local;
  GELX_PETSC(VecGetSize(v, &n));
  GELX_PETSC(VecGetLocalSize(v, &local));
  std::vector<double> values(n);
  const PetscScalar* array;
  GELX_PETSC(VecGetArrayRead(v, &array));
  std::copy_n(array, local, values.begin());
  GELX_PETSC(VecRestoreArrayRead(v, &array));
  MPI_Bcast(values.data(), n, MPI_DOUBLE, 0, comm);
  return values;
}
} // namespace

DesignOptimizer::DesignOptimizer(NonlinearSystem& system, NewtonSolver& newton,
                                 AdjointGradient& adjoint,
                                 std::shared_ptr<dolfinx::fem::Function<double>> design,
                                 int num_parameters,
                                 const std::function<int(const double*, int)>& parameter_of,
                                 const std::string& prefix)
    : _system(system), _newton(newton), _adjoint(adjoint), _design(std::move(design)),
      _prefix(prefix)
{
  const MPI_Comm comm = _design->function_space()->mesh()->comm();
  const bool root = dolfinx::MPI::rank(comm) == 0;
  const auto& dofmap = *_design->function_space()->dofmap();
  const int bs = dofmap.index_map_bs();
  const std::int32_t owned = dofmap.index_map->size_local() * bs;
  const std::int64_t first = dofmap.index_map->local_range()[0] * bs;

  // T: a 1 where parameter k sets design dof i
  GELX_PETSC(MatCreateAIJ(comm, owned, root ? num_parameters : 0, PETSC_DETERMINE,
                          num_parameters, 1, nullptr, 1, nullptr, &_T));
  _design_vec = dolfinx::la::petsc::create_vector_wrap(*_design->x());
  GELX_PETSC(VecDuplicate(_design_vec, &_fixed));
  GELX_PETSC(VecCopy(_design_vec, _fixed));
  const std::vector<double> X = _design->function_space()->tabulate_dof_coordinates(false);
  PetscScalar* fixed;
  GELX_PETSC(VecGetArray(_fixed, &fixed));
  for (std::int32_t i = 0; i < owned; ++i)
  {
    const int k = parameter_of(&X[3 * (i / bs)], i % bs);
    if (k < 0)
      continue;
    if (k >= num_parameters)
      throw std::invalid_argument("DesignOptimizer: parameter " + std::to_string(k)
                                  + " of a cell is not below the number of parameters, "
                                  + std::to_string(num_parameters));
    GELX_PETSC(MatSetValue(_T, first + i, k, 1.0, INSERT_VALUES));
    fixed[i] = 0;
  }
  GELX_PETSC(VecRestoreArray(_fixed, &fixed));
  GELX_PETSC(MatAssemblyBegin(_T, MAT_FINAL_ASSEMBLY));
  GELX_PETSC(MatAssemblyEnd(_T, MAT_FINAL_ASSEMBLY));

  // BLMVM's memory: TAO's 5 updates made the twin test (tests/design_twin.cpp, 10 parameters)
  // crawl, 200 iterations to J/J0 = 5e-9; 10, 20 and 40 took 111, 72 and 57 iterations to
  // |g| < 1e-8. Four per parameter, within [5, 100] (100 vectors of a per-cell design are
  // still small beside one factorisation).
  set_default_options(prefix, {{"tao_type", "blmvm"},
                               {"tao_max_it", "200"},
                               {"tao_blmvm_mat_lmvm_hist_size",
                                std::to_string(std::clamp(4 * num_parameters, 5, 100))}});
  GELX_PETSC(TaoCreate(comm, &_tao));
  GELX_PETSC(TaoSetOptionsPrefix(_tao, prefix.c_str()));
  GELX_PETSC(TaoSetObjectiveAndGradient(_tao, nullptr, objective_and_gradient, this));
  GELX_PETSC(TaoSetMonitor(_tao, monitor, this, nullptr));
  GELX_PETSC(MatCreateVecs(_T, &_lower, nullptr));
  GELX_PETSC(VecDuplicate(_lower, &_upper));
  GELX_PETSC(VecSet(_lower, PETSC_NINFINITY));
  GELX_PETSC(VecSet(_upper, PETSC_INFINITY));
}

DesignOptimizer::~DesignOptimizer()
{
  TaoDestroy(&_tao);
  MatDestroy(&_T);
  for (Vec* v : {&_fixed, &_design_vec, &_lower, &_upper})
    VecDestroy(v);
}

void DesignOptimizer::set_bounds(const std::vector<double>& lower,
                                 const std::vector<double>& upper)
{
  set_parameters(_lower, lower);
  set_parameters(_upper, upper);
}

void DesignOptimizer::set_design(Vec p)
{
  GELX_PETSC(VecCopy(p, _last_parameters.get()));
  GELX_PETSC(MatMultAdd(_T, p, _fixed, _design_vec));
  _design->x()->scatter_fwd();
}

void DesignOptimizer::solve_forward()
{
  NewtonReport report = _newton.solve(_system);
  ++_counts.forward_solves;
  _counts.newton_iterations += report.iterations;
  if (!report.converged)
    solve_forward_by_steps();
  GELX_PETSC(VecCopy(_system.unknowns(), _last_state.get()));
  GELX_PETSC(VecCopy(_design_vec, _last_design.get()));
}

void DesignOptimizer::solve_forward_by_steps()
{
  // Too large a change of the design for one Newton solve: from the last equilibrium along
  // s(t) = s_last + t (s_new - s_last), by load steps and, past a fold of that path (the shape
  // snaps), by arc length in t
  const OwnedVec target = copy_of(_design_vec);
  _system.set_state(_last_state.get());
  follow_homotopy(
      _system, _newton, {.secant_predictor = true},
      [&](double t)
      {
        GELX_PETSC(VecAXPBYPCZ(_design_vec, 1 - t, t, 0.0, _last_design.get(), target.get()));
        _design->x()->scatter_fwd();
      },
      [&](const StepRecord& step, PathState&)
      {
        ++_counts.forward_solves;
        _counts.newton_iterations += step.newton.iterations;
      },
      _prefix + "homotopy_");
}

double DesignOptimizer::evaluate(Vec p, Vec gradient)
{
  const double start = MPI_Wtime();
  set_design(p);
  solve_forward();
  const double solved = MPI_Wtime();
  const OwnedVec dJ_ds(_adjoint.create_design_vector());
  _adjoint.gradient(dJ_ds.get());
  ++_counts.adjoint_solves;
  GELX_PETSC(MatMultTranspose(_T, dJ_ds.get(), gradient));
  const double J = _adjoint.value();
  _counts.forward_time += solved - start;
  _counts.adjoint_time += MPI_Wtime() - solved;
  return J;
}

void DesignOptimizer::equilibrium_at(Vec p)
{
  PetscBool same;
  GELX_PETSC(VecEqual(p, _last_parameters.get(), &same));
  if (!same)
  {
    set_design(p);
    solve_forward();
  }
}

void DesignOptimizer::iterate_accepted()
{
  PetscInt iteration;
  PetscReal J, gradient_norm;
  TaoConvergedReason reason;
  GELX_PETSC(TaoGetSolutionStatus(_tao, &iteration, &J, &gradient_norm, nullptr, nullptr,
                                  &reason));
  Vec p;
  GELX_PETSC(TaoGetSolution(_tao, &p));
  equilibrium_at(p);
  DesignIterate iterate = _counts;
  iterate.iteration = iteration;
  iterate.objective = J;
  iterate.gradient_norm = gradient_norm;
  iterate.parameters = on_every_rank(p, _design->function_space()->mesh()->comm());
  iterate.wall_time = MPI_Wtime() - _start_time;
  if (_observe && *_observe)
    (*_observe)(iterate);
}

int DesignOptimizer::minimise(std::vector<double>& parameters,
                              const std::function<void(const DesignIterate&)>& observe)
{
  _observe = &observe;
  _start_time = MPI_Wtime();
  _last_state = copy_of(_system.unknowns());
  _last_design = copy_of(_design_vec);
  Vec p;
  GELX_PETSC(MatCreateVecs(_T, &p, nullptr));
  set_parameters(p, parameters);
  _last_parameters = copy_of(p);

  GELX_PETSC(TaoSetSolution(_tao, p));
  GELX_PETSC(TaoSetVariableBounds(_tao, _lower, _upper));
  GELX_PETSC(TaoSetFromOptions(_tao));
  solve_guarded(callback_error, [&] { return TaoSolve(_tao); });
  TaoConvergedReason reason;
  GELX_PETSC(TaoGetConvergedReason(_tao, &reason));
  parameters = on_every_rank(p, _design->function_space()->mesh()->comm());
  equilibrium_at(p);
  GELX_PETSC(VecDestroy(&p));
  _observe = nullptr;
  return reason;
}

} // namespace gelx
