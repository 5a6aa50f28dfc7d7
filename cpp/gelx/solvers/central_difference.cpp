#include <gelx/solvers/central_difference.h>
#include <gelx/common/petsc_utils.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <petsc/private/tsimpl.h>
#include <slepceps.h>
#include <stdexcept>

namespace gelx
{
namespace
{
/// The TS type's data (ts->data)
struct CentralDifference
{
  Vec mass = nullptr, damping = nullptr; ///< diagonals of M and C (referenced)
  PrescribedMotion prescribe;
  Vec X0 = nullptr, V0 = nullptr, A0 = nullptr, A1 = nullptr, F = nullptr, zero = nullptr;
  Vec divisor = nullptr; ///< M + dt/2 C
  bool acceleration_known = false;
};

CentralDifference& data_of(TS ts) { return *static_cast<CentralDifference*>(ts->data); }

/// a = -F / (M + dt/2 C); in the prescribed rows F = u - g = 0 (u is on g), so a = 0 there
/// until prescribe() writes their acceleration
PetscErrorCode solve_acceleration(TS ts, double t, double dt, Vec u, Vec v_half, Vec a)
{
  CentralDifference& cd = data_of(ts);
  PetscCall(VecCopy(cd.mass, cd.divisor));
  if (cd.damping)
    PetscCall(VecAXPY(cd.divisor, 0.5 * dt, cd.damping));
  PetscCall(TSComputeI2Function(ts, t, u, v_half, cd.zero, cd.F));
  PetscCall(VecPointwiseDivide(a, cd.F, cd.divisor));
  PetscCall(VecScale(a, -1.0));
  return 0;
}

PetscErrorCode step(TS ts)
{
  CentralDifference& cd = data_of(ts);
  Vec u = ts->vec_sol, v = ts->vec_dot;
  const double t = ts->ptime;
  const double dt = std::min(ts->time_step, ts->max_time - t);
  PetscCall(TSPreStage(ts, t));
  if (!cd.acceleration_known)
  {
    // The run's start: a_0 from the equation of motion at (u_0, v_0), with the damping force
    // at v_0 itself: M a_0 = -(C v_0 + R(u_0))
    PetscCall(VecCopy(cd.mass, cd.divisor));
    PetscCall(TSComputeI2Function(ts, t, u, v, cd.zero, cd.F));
    PetscCall(VecPointwiseDivide(cd.A1, cd.F, cd.divisor));
    PetscCall(VecScale(cd.A1, -1.0));
    PetscCall(cd.prescribe(t, u, v, cd.A1));
    cd.acceleration_known = true;
  }
  PetscCall(VecCopy(u, cd.X0));
  PetscCall(VecCopy(v, cd.V0));
  PetscCall(VecCopy(cd.A1, cd.A0));
  // v_n+1/2 = v_n + dt/2 a_n into v, u_n+1 = u_n + dt v_n+1/2, and the prescribed rows on
  // their motion at t_n+1 before the forces are evaluated (C is diagonal: the free rows'
  // damping force sees the free rows' v_n+1/2 only)
  PetscCall(VecAXPY(v, 0.5 * dt, cd.A0));
  PetscCall(VecAXPY(u, dt, v));
  PetscCall(cd.prescribe(t + dt, u, v, cd.A1));
  PetscCall(solve_acceleration(ts, t + dt, dt, u, v, cd.A1));
  // v_n+1 = v_n+1/2 + dt/2 a_n+1, and the prescribed rows' own velocity and acceleration
  PetscCall(VecAXPY(v, 0.5 * dt, cd.A1));
  PetscCall(cd.prescribe(t + dt, u, v, cd.A1));
  PetscCall(TSPostStage(ts, t + dt, 0, &u));
  ts->ptime += dt;
  ts->time_step = dt;
  return 0;
}

PetscErrorCode setup(TS ts)
{
  CentralDifference& cd = data_of(ts);
  PetscCheck(cd.mass && cd.prescribe, PetscObjectComm(reinterpret_cast<PetscObject>(ts)),
             PETSC_ERR_ORDER, "call central_difference_set_mass before TSSetUp");
  PetscCheck(ts->vec_dot, PetscObjectComm(reinterpret_cast<PetscObject>(ts)), PETSC_ERR_ORDER,
             "set the velocity with TS2SetSolution");
  for (Vec* w : {&cd.X0, &cd.V0, &cd.A0, &cd.A1, &cd.F, &cd.zero, &cd.divisor})
    if (!*w)
      PetscCall(VecDuplicate(ts->vec_sol, w));
  PetscCall(VecSet(cd.zero, 0.0));
  PetscCall(VecSet(cd.A1, 0.0));
  // TSSolve's checks want an adaptor (none: the owner sets the step)
  PetscCall(TSGetAdapt(ts, &ts->adapt));
  return 0;
}

PetscErrorCode reset(TS ts)
{
  CentralDifference& cd = data_of(ts);
  for (Vec* w : {&cd.X0, &cd.V0, &cd.A0, &cd.A1, &cd.F, &cd.zero, &cd.divisor})
    PetscCall(VecDestroy(w));
  cd.acceleration_known = false;
  return 0;
}

PetscErrorCode destroy(TS ts)
{
  PetscCall(reset(ts));
  CentralDifference* cd = &data_of(ts);
  PetscCall(VecDestroy(&cd->mass));
  PetscCall(VecDestroy(&cd->damping));
  delete cd;
  ts->data = nullptr;
  return 0;
}

PetscErrorCode set_from_options(TS, PetscOptionItems*) { return 0; }

PetscErrorCode view(TS ts, PetscViewer viewer)
{
  PetscBool ascii;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(viewer), PETSCVIEWERASCII,
                                   &ascii));
  if (ascii)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  explicit central differences (gelx), %s\n",
                                     data_of(ts).damping ? "with damping" : "undamped"));
  return 0;
}

PetscErrorCode create(TS ts)
{
  ts->data = new CentralDifference;
  ts->ops->setup = setup;
  ts->ops->step = step;
  ts->ops->reset = reset;
  ts->ops->destroy = destroy;
  ts->ops->setfromoptions = set_from_options;
  ts->ops->view = view;
  ts->default_adapt_type = TSADAPTNONE;
  ts->usessnes = PETSC_FALSE;
  return 0;
}

/// The local rows of `prescribed` as a mask over n rows
std::vector<char> mask_of(const std::vector<PetscInt>& prescribed, PetscInt n)
{
  std::vector<char> mask(n, 0);
  for (PetscInt r : prescribed)
    mask[r] = 1;
  return mask;
}

/// sum_j |K_ij| for each local row
std::vector<double> absolute_row_sums(Mat K)
{
  PetscInt first, last;
  GELX_PETSC(MatGetOwnershipRange(K, &first, &last));
  std::vector<double> sums(last - first, 0.0);
  for (PetscInt row = first; row < last; ++row)
  {
    PetscInt n;
    const PetscScalar* values;
    GELX_PETSC(MatGetRow(K, row, &n, nullptr, &values));
    for (PetscInt k = 0; k < n; ++k)
      sums[row - first] += std::abs(values[k]);
    GELX_PETSC(MatRestoreRow(K, row, &n, nullptr, &values));
  }
  return sums;
}
} // namespace

void register_central_difference()
{
  static bool registered = false;
  if (!registered)
    GELX_PETSC(TSRegister(TSCENTRALDIFFERENCE, create));
  registered = true;
}

void central_difference_set_mass(TS ts, Vec mass, Vec damping, PrescribedMotion prescribe)
{
  PetscBool is_cd;
  GELX_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ts), TSCENTRALDIFFERENCE,
                                    &is_cd));
  if (!is_cd)
    throw std::invalid_argument("central_difference_set_mass: TS is not of type "
                                + std::string(TSCENTRALDIFFERENCE));
  CentralDifference& cd = data_of(ts);
  GELX_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(mass)));
  GELX_PETSC(VecDestroy(&cd.mass));
  cd.mass = mass;
  if (damping)
    GELX_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(damping)));
  GELX_PETSC(VecDestroy(&cd.damping));
  cd.damping = damping;
  cd.prescribe = std::move(prescribe);
}

CentralDifferenceState central_difference_state(TS ts)
{
  PetscBool is_cd;
  GELX_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ts), TSCENTRALDIFFERENCE,
                                    &is_cd));
  if (!is_cd || !data_of(ts).A1)
    throw std::invalid_argument("central_difference_state: no set-up TS of type "
                                + std::string(TSCENTRALDIFFERENCE));
  CentralDifference& cd = data_of(ts);
  return {cd.X0, cd.V0, cd.A0, cd.A1, &cd.acceleration_known};
}

Mat lumped_mass(Mat M, const std::vector<PetscInt>& prescribed, const std::string& lumping,
                std::string& method)
{
  if (lumping != "row_sum" && lumping != "diagonal" && lumping != "auto")
    throw std::invalid_argument("lumping must be row_sum, diagonal or auto, not " + lumping);
  Vec sums, diagonal;
  GELX_PETSC(MatCreateVecs(M, &sums, &diagonal));
  GELX_PETSC(MatGetRowSum(M, sums));
  GELX_PETSC(MatGetDiagonal(M, diagonal));
  const PetscScalar* s;
  PetscInt n;
  GELX_PETSC(VecGetLocalSize(sums, &n));
  const std::vector<char> fixed = mask_of(prescribed, n);
  GELX_PETSC(VecGetArrayRead(sums, &s));
  int nonpositive = 0;
  for (PetscInt i = 0; i < n; ++i)
    nonpositive += !fixed[i] && !(s[i] > 0);
  GELX_PETSC(VecRestoreArrayRead(sums, &s));
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(M));
  MPI_Allreduce(MPI_IN_PLACE, &nonpositive, 1, MPI_INT, MPI_SUM, comm);
  if (lumping == "row_sum" && nonpositive > 0)
    throw std::invalid_argument(
        "the row-sum lumped mass has " + std::to_string(nonpositive)
        + " non-positive entries (P2 tetrahedra: the vertices'); use the diagonal lumping");
  method = lumping == "auto" ? (nonpositive > 0 ? "diagonal" : "row_sum") : lumping;
  if (method == "diagonal")
  {
    // Per component (unknowns interleaved by the block size): M's diagonal scaled so that its
    // sum over the free rows is the row sums' sum there, the total mass; the prescribed rows
    // keep their row sums
    PetscInt bs;
    GELX_PETSC(MatGetBlockSize(M, &bs));
    std::vector<double> total(2 * bs, 0.0);
    PetscScalar *r, *d;
    GELX_PETSC(VecGetArray(sums, &r));
    GELX_PETSC(VecGetArray(diagonal, &d));
    for (PetscInt i = 0; i < n; ++i)
      if (!fixed[i])
      {
        total[i % bs] += r[i];
        total[bs + i % bs] += d[i];
      }
    MPI_Allreduce(MPI_IN_PLACE, total.data(), int(total.size()), MPI_DOUBLE, MPI_SUM, comm);
    for (PetscInt i = 0; i < n; ++i)
      if (!fixed[i])
        r[i] = d[i] * total[i % bs] / total[bs + i % bs];
    GELX_PETSC(VecRestoreArray(diagonal, &d));
    GELX_PETSC(VecRestoreArray(sums, &r));
  }
  // Only the diagonal is stored: a product with M's pattern of zeros cost as much as one with
  // the consistent mass (0.5 ms of an explicit step's 6 ms on 15 Q2 slabs of the bistrip)
  PetscInt local_rows, local_columns, rows, columns, bs;
  GELX_PETSC(MatGetLocalSize(M, &local_rows, &local_columns));
  GELX_PETSC(MatGetSize(M, &rows, &columns));
  GELX_PETSC(MatGetBlockSize(M, &bs));
  Mat lumped;
  GELX_PETSC(MatCreate(comm, &lumped));
  GELX_PETSC(MatSetSizes(lumped, local_rows, local_columns, rows, columns));
  GELX_PETSC(MatSetBlockSize(lumped, bs));
  GELX_PETSC(MatSetType(lumped, MATAIJ));
  GELX_PETSC(MatSeqAIJSetPreallocation(lumped, 1, nullptr));
  GELX_PETSC(MatMPIAIJSetPreallocation(lumped, 1, nullptr, 0, nullptr));
  GELX_PETSC(MatDiagonalSet(lumped, sums, INSERT_VALUES));
  VecDestroy(&sums);
  VecDestroy(&diagonal);
  return lumped;
}

double gershgorin_bound(Mat K, Vec m, const std::vector<PetscInt>& prescribed)
{
  // Gershgorin on the symmetric M^-1/2 K M^-1/2 (the same spectrum as M^-1 K): its row sums
  // sum_j |K_ij| / sqrt(m_i m_j) weigh a light node's stiff neighbours by their own masses,
  // which on P2 tetrahedra (light vertices, heavy edges) is tighter than max_i sum_j |K_ij| / m_i
  Vec d;
  GELX_PETSC(VecDuplicate(m, &d));
  GELX_PETSC(VecCopy(m, d));
  GELX_PETSC(VecSqrtAbs(d));
  GELX_PETSC(VecReciprocal(d));
  Mat A;
  GELX_PETSC(MatDuplicate(K, MAT_COPY_VALUES, &A));
  GELX_PETSC(MatDiagonalScale(A, d, d));
  const std::vector<double> symmetric = absolute_row_sums(A);
  MatDestroy(&A);
  VecDestroy(&d);
  // and on M^-1 K itself: the smaller of two upper bounds is one (and this one is what
  // scale_mass_for_step sets)
  const std::vector<double> sums = absolute_row_sums(K);
  const std::vector<char> fixed = mask_of(prescribed, PetscInt(sums.size()));
  const PetscScalar* mass;
  GELX_PETSC(VecGetArrayRead(m, &mass));
  std::array<double, 2> bounds{0, 0};
  for (std::size_t i = 0; i < sums.size(); ++i)
    if (!fixed[i])
    {
      bounds[0] = std::max(bounds[0], symmetric[i]);
      bounds[1] = std::max(bounds[1], sums[i] / mass[i]);
    }
  GELX_PETSC(VecRestoreArrayRead(m, &mass));
  MPI_Allreduce(MPI_IN_PLACE, bounds.data(), 2, MPI_DOUBLE, MPI_MAX,
                PetscObjectComm(reinterpret_cast<PetscObject>(K)));
  return std::min(bounds[0], bounds[1]);
}

double largest_stiffness_eigenvalue(MPI_Comm comm, Mat K, Vec m,
                                    const std::vector<PetscInt>& prescribed,
                                    const std::string& prefix, double tol)
{
  // A = D K D, D = M^-1/2 in the free rows and 0 in the prescribed ones: A's spectrum is
  // M^-1 K's on the free rows, and zeros
  Vec d;
  GELX_PETSC(VecDuplicate(m, &d));
  GELX_PETSC(VecCopy(m, d));
  GELX_PETSC(VecSqrtAbs(d));
  GELX_PETSC(VecReciprocal(d));
  PetscScalar* values;
  GELX_PETSC(VecGetArray(d, &values));
  for (PetscInt r : prescribed)
    values[r] = 0;
  GELX_PETSC(VecRestoreArray(d, &values));
  Mat A;
  GELX_PETSC(MatDuplicate(K, MAT_COPY_VALUES, &A));
  GELX_PETSC(MatDiagonalScale(A, d, d));
  EPS eps;
  GELX_PETSC(EPSCreate(comm, &eps));
  GELX_PETSC(EPSSetOptionsPrefix(eps, prefix.c_str()));
  GELX_PETSC(EPSSetOperators(eps, A, nullptr));
  GELX_PETSC(EPSSetProblemType(eps, EPS_HEP));
  GELX_PETSC(EPSSetWhichEigenpairs(eps, EPS_LARGEST_REAL));
  GELX_PETSC(EPSSetTolerances(eps, tol, 1000));
  GELX_PETSC(EPSSetFromOptions(eps));
  GELX_PETSC(EPSSolve(eps));
  PetscInt converged;
  GELX_PETSC(EPSGetConverged(eps, &converged));
  PetscScalar lambda = NAN;
  if (converged > 0)
    GELX_PETSC(EPSGetEigenpair(eps, 0, &lambda, nullptr, nullptr, nullptr));
  EPSDestroy(&eps);
  MatDestroy(&A);
  VecDestroy(&d);
  if (converged < 1)
    throw std::runtime_error("the largest eigenvalue of M^-1 K did not converge");
  return lambda;
}

double scale_mass_for_step(Mat K, Vec m, const std::vector<PetscInt>& prescribed, double dt,
                           double fraction)
{
  const std::vector<double> sums = absolute_row_sums(K);
  const std::vector<char> fixed = mask_of(prescribed, PetscInt(sums.size()));
  const double factor = std::pow(dt / (2 * fraction), 2);
  PetscScalar* mass;
  GELX_PETSC(VecGetArray(m, &mass));
  double added = 0;
  for (std::size_t i = 0; i < sums.size(); ++i)
    if (!fixed[i] && mass[i] < factor * sums[i])
    {
      added += factor * sums[i] - mass[i];
      mass[i] = factor * sums[i];
    }
  GELX_PETSC(VecRestoreArray(m, &mass));
  MPI_Allreduce(MPI_IN_PLACE, &added, 1, MPI_DOUBLE, MPI_SUM,
                PetscObjectComm(reinterpret_cast<PetscObject>(K)));
  return added;
}

} // namespace gelx
