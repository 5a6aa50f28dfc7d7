#pragma once
/// @file central_difference.h
/// Explicit central differences, the scheme of ABAQUS/Explicit, as a PETSc TS type, with the
/// lumped mass and the stable-step estimates it needs.

#include <functional>
#include <mpi.h>
#include <petscts.h>
#include <string>
#include <vector>

namespace gelx
{

/// The TS type of explicit central differences (velocity Verlet with a damping term):
///     v_n+1/2 = v_n + dt/2 a_n,   u_n+1 = u_n + dt v_n+1/2,
///     (M + dt/2 C) a_n+1 = -F(t_n+1, u_n+1, v_n+1/2, 0),   v_n+1 = v_n+1/2 + dt/2 a_n+1,
/// with F(t, u, v, a) = M a + C v + R(u; t) the TS's I2Function (TSSetI2Function), M and C
/// diagonal (a lumped mass, mass-proportional damping: given by central_difference_set_mass),
/// which makes every step explicit: one residual evaluation, no solve. Second-order, exact
/// for the damping term's C v at the step's end, and stable while dt <= 2 / omega_max, omega_max^2
/// the largest eigenvalue of M^-1 K. The rows TS's owner prescribes (supports moved in time)
/// take their displacement, velocity and acceleration from the `prescribe` callback at the
/// step's end, so that they are exact whatever the step.
///
/// Why gelx's own TS type: PETSc 3.18 has no explicit scheme for M u'' + C u' + R(u) = 0.
/// TSBASICSYMPLECTIC's velocity Verlet integrates q' = f(p), p' = g(q) with a momentum
/// right-hand side of the positions alone, so no velocity-dependent (damping) force, and no
/// prescribed motions but through f; the explicit Runge-Kutta methods are not symplectic and
/// need several residual evaluations per step. As a TS type it keeps what TS gives every
/// integrator: TSSolve's loop, monitors, pre- and post-step hooks, -ts_max_time and
/// -ts_max_steps through the options database. The step size is TS's (TSSetTimeStep); the
/// type clips it to the final time. The state (u in the solution, v in TS2SetSolution's
/// velocity, the acceleration here) is TS's, readable through central_difference_state.
inline constexpr const char* TSCENTRALDIFFERENCE = "gelx_central_difference";

/// Registers TSCENTRALDIFFERENCE with TS (once; later calls do nothing).
void register_central_difference();

/// The motion of the prescribed rows at time t: writes their displacement, velocity and
/// acceleration into u, v and a (vectors of the solution's layout), leaving the other rows.
/// Returns a PETSc error code (it is called from within TSSolve).
using PrescribedMotion = std::function<PetscErrorCode(double t, Vec u, Vec v, Vec a)>;

/// The diagonals of M and C (C may be null: no damping) and the prescribed motion of a TS of
/// type TSCENTRALDIFFERENCE, after TSSetType. The vectors are referenced, not copied.
void central_difference_set_mass(TS ts, Vec mass, Vec damping, PrescribedMotion prescribe);

/// The state a TSCENTRALDIFFERENCE keeps besides u and v: the previous step's u, v and a, and
/// the acceleration at the current state. `acceleration_known` false: the next step first
/// computes a_n from the equation of motion (the start of a run); a restart writes the
/// acceleration and sets it true.
struct CentralDifferenceState
{
  Vec previous_unknowns, previous_velocity, previous_acceleration, acceleration;
  bool* acceleration_known;
};
/// The state of `ts` (of type TSCENTRALDIFFERENCE, set up): throws otherwise.
CentralDifferenceState central_difference_state(TS ts);

/// The lumped mass of the consistent mass M (assembled, square): a matrix of M's layout that
/// stores only its diagonal (it adds to a tangent with SUBSET_NONZERO_PATTERN), either the
/// row sums (`row_sum`: positive on Q1 and Q2 hexahedra and P1 tetrahedra; on P2 tetrahedra
/// the vertex rows sum to a negative mass, -1/20 of each element's), or M's diagonal scaled to
/// keep the total mass per unknown component (`diagonal`, HRZ's scaling applied to the whole
/// mesh at once: positive on every element), or `auto`: the row sums where they are all
/// positive, the diagonal otherwise. `method` returns the one used. The prescribed rows
/// (local indices) keep M's row sums, whatever their sign: they carry no equation of motion.
/// Collective.
Mat lumped_mass(Mat M, const std::vector<PetscInt>& prescribed, const std::string& lumping,
                std::string& method);

/// An upper bound of the largest eigenvalue of M^-1 K over the free rows, M = diag(m): the
/// smaller of Gershgorin's bounds max_i sum_j |K_ij| / m_i and, on the similar symmetric
/// M^-1/2 K M^-1/2, max_i sum_j |K_ij| / sqrt(m_i m_j), over the rows i not in `prescribed`
/// (local indices). Never below the largest eigenvalue, so that 2 / sqrt of it is never above
/// the critical step; a few times above it (the test measures by how much). A copy of K and
/// two passes over it. Collective.
double gershgorin_bound(Mat K, Vec m, const std::vector<PetscInt>& prescribed);

/// The largest eigenvalue of M^-1 K over the free rows (prescribed rows and columns removed),
/// M = diag(m), K symmetric: SLEPc's Krylov-Schur on M^-1/2 K M^-1/2 to a relative
/// tolerance `tol` (options -PREFIX_eps_*). Collective.
double largest_stiffness_eigenvalue(MPI_Comm comm, Mat K, Vec m,
                                    const std::vector<PetscInt>& prescribed,
                                    const std::string& prefix, double tol = 1e-10);

/// Mass scaling for a target step: m_i raised to sum_j |K_ij| (dt / (2 fraction))^2 where it
/// is below, over the free rows, so that Gershgorin's step fraction * 2 / sqrt(bound) is at
/// least dt. Returns the mass added (the sum over unknowns, as m's). Collective.
double scale_mass_for_step(Mat K, Vec m, const std::vector<PetscInt>& prescribed, double dt,
                           double fraction);

} // namespace gelx
