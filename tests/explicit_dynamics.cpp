// Verification: explicit central differences (gelx::InertialDynamics with
// -PREFIX_ts_type gelx_central_difference, the scheme of ABAQUS/Explicit).
//
// The buckling scene's column, short (L = 6 tx, ty = 1.5 tx, P2 tetrahedra on 2 x 3 x 8
// boxes), as a cantilever (clamped at z = 0) or shortened between clamped ends. Checked:
//  1. the lumped mass on P2 tetrahedra: the row sums are negative at the vertices (so
//     `row_sum` is refused), `auto` takes the scaled diagonal, positive, whose sum per
//     component is the body's mass rho tx ty L;
//  2. the stable step on the linear law: Gershgorin's bound of the largest eigenvalue of
//     M^-1 K is never below SLEPc's converged value (the runs' step never above the critical
//     one); from a random velocity, 1.1 x the critical step diverges (the energy grows by
//     more than 1e6) and 0.9 x does not (the energy stays below the closed-form bound
//     E0 / (1 - (0.9)^2) of velocity Verlet's modified energy);
//  3. explicit against implicit on a nonlinear problem (the neo-Hookean cantilever released
//     with a large velocity in its first bending mode, a quarter period): the tip equals
//     TSALPHA2's with the same lumped mass within the two schemes' time-discretisation
//     errors (each estimated from a halved step); the control, TSALPHA2 with the consistent
//     mass, differs by more;
//  4. mass scaling to twice the stable step: half the steps, the mass added reported;
//  5. restart (with mass scaling and Rayleigh mass damping): continued from a checkpoint, the
//     run ends equal to the uninterrupted one (1e-10); continued with the unscaled mass it
//     differs;
//  6. a moving support: the clamped-clamped column (linear law) shortened by the smooth step
//     over 10 axial periods: the energy balance W = SE + KE + ED, and the axial force at the
//     end against the static solution's (the quasi-static limit).
//
// Usage: test_explicit_dynamics [PETSc options]

#include "euler_column.h"
#include "support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <dolfinx/la/petsc.h>
#include <gelx/solvers/buckling.h>
#include <gelx/solvers/central_difference.h>
#include <gelx/io/checkpoint.h>
#include <gelx/solvers/inertia.h>
#include <gelx/solvers/newton.h>
#include <gelx/common/petsc_utils.h>
#include <random>
#include <string>
#include <vector>

namespace
{
using gelx::scenes::ColumnParameters;
using gelx::scenes::EulerColumn;

std::string real(double v)
{
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

/// What a run gives back
struct Run
{
  std::vector<double> energy; ///< SE + KE at t = 0 and every step
  double tip = 0;             ///< the tip's x deflection over L at the end
  int steps = 0;
  gelx::DynamicsSummary summary;
  gelx::OwnedVec u, v;
  bool diverged = false; ///< stopped by an inadmissible state
};

/// How a run is made
struct RunOptions
{
  double end_time = 0;
  Vec velocity = nullptr; ///< the initial velocity
  int save_at = 0;        ///< checkpoint after this step ...
  gelx::Checkpoints* checkpoints = nullptr;
  const gelx::PathState* resume = nullptr;
};

/// The column from rest at u = 0 (or from `resume`) with the integrator of options `prefix`
/// (central differences unless the prefix sets its ts_type) to `end_time`
Run run(EulerColumn& column, const std::string& prefix, const RunOptions& o)
{
  gelx::NonlinearProblem& problem = column.problem();
  gelx::set_default_option(prefix, "ts_type", gelx::TSCENTRALDIFFERENCE);
  gelx::set_default_option(prefix, "loading_time", real(o.end_time));
  gelx::set_default_option(prefix, "ts_max_steps", "1000000");
  gelx::set_default_option(prefix, "snes_rtol", "1e-10");
  gelx::set_default_option(prefix, "snes_atol", "1e-13");
  if (!o.resume)
  {
    VecSet(problem.unknowns(), 0.0);
    problem.unknowns_changed();
  }
  gelx::InertialDynamics dynamics(column.mesh().mesh->comm(), problem, *column.mass_form(),
                                  [&] { return column.strain_energy(); }, [](double) {},
                                  prefix);
  if (o.velocity)
    dynamics.set_initial_velocity(o.velocity);
  Run r;
  gelx::OwnedVec work(problem.create_vector());
  if (!o.resume)
    r.energy.push_back(column.strain_energy()
                       + (o.velocity
                              ? 0.5 * gelx::quadratic_form(dynamics.mass(), o.velocity, work.get())
                              : 0.0));
  try
  {
    r.summary = dynamics.run({[&](const gelx::DynamicsRecord& record)
                              {
                                r.energy.push_back(record.strain_energy
                                                   + record.kinetic_energy);
                                r.steps = record.step.step;
                                if (record.step.step == o.save_at && o.checkpoints)
                                {
                                  gelx::PathState state;
                                  dynamics.save(state);
                                  o.checkpoints->write(problem, state, {});
                                }
                              }},
                             o.resume);
  }
  catch (const gelx::ConvergenceError&)
  {
    r.diverged = true;
  }
  r.tip = column.tip_deflection()[0];
  r.u.reset(problem.create_vector());
  VecCopy(problem.unknowns(), r.u.get());
  r.v.reset(problem.create_vector());
  VecCopy(dynamics.velocity(), r.v.get());
  return r;
}

/// |a - b| / |b|
double relative_difference(Vec a, Vec b)
{
  Vec d;
  VecDuplicate(a, &d);
  VecWAXPY(d, -1.0, b, a);
  double nd, nb;
  VecNorm(d, NORM_2, &nd);
  VecNorm(b, NORM_2, &nb);
  VecDestroy(&d);
  return nd / nb;
}
} // namespace

int main(int argc, char* argv[])
{
  return gelx::test::run_checks(argc, argv, [](MPI_Comm comm, gelx::test::Checks& checks)
  {
    char text[256];
    ColumnParameters p;
    p.L = 6;
    p.cells = {2, 3, 8};
    p.law = "linear_elastic";
    EulerColumn linear(comm, p);
    gelx::NonlinearProblem& problem = linear.problem();
    const std::vector<PetscInt> prescribed = problem.prescribed_rows();

    // 1. The lumped mass on P2 tetrahedra
    Mat M = gelx::assemble_system_mass(problem, *linear.mass_form(), "test");
    std::string method;
    bool refused = false;
    try
    {
      Mat row_sum = gelx::lumped_mass(M, prescribed, "row_sum", method);
      MatDestroy(&row_sum);
    }
    catch (const std::invalid_argument&)
    {
      refused = true;
    }
    checks.require("P2 tetrahedra: the row-sum lumped mass has non-positive entries "
                   "(refused)",
                   refused);
    Mat lumped = gelx::lumped_mass(M, {}, "auto", method);
    Vec m;
    MatCreateVecs(lumped, &m, nullptr);
    MatGetDiagonal(lumped, m);
    PetscReal smallest, total;
    VecMin(m, nullptr, &smallest);
    VecSum(m, &total);
    checks.require("auto lumping on P2 tetrahedra: " + method, method == "diagonal");
    std::snprintf(text, sizeof text, "lumped masses positive (smallest %.3e)", smallest);
    checks.require(text, smallest > 0);
    checks.relative("lumped mass per component against rho tx ty L", total / 3,
                    p.rho * p.tx * p.ty * p.L, 1e-12);
    MatDestroy(&lumped);
    MatDestroy(&M);

    // 2. The stable step (linear law: K constant). The lumped mass with the prescribed rows
    //    as the integrator makes it
    M = gelx::assemble_system_mass(problem, *linear.mass_form(), "test");
    lumped = gelx::lumped_mass(M, prescribed, "auto", method);
    MatGetDiagonal(lumped, m);
    Mat K = problem.create_matrix();
    VecSet(problem.unknowns(), 0.0);
    problem.unknowns_changed();
    problem.tangent(K);
    const double lambda = gelx::largest_stiffness_eigenvalue(comm, K, m, prescribed, "test_");
    const double bound = gelx::gershgorin_bound(K, m, prescribed);
    const double critical = 2 / std::sqrt(lambda);
    std::snprintf(text, sizeof text,
                  "Gershgorin's bound %.5e >= the largest eigenvalue of M^-1 K %.5e (ratio "
                  "%.3f)",
                  bound, lambda, bound / lambda);
    checks.require(text, bound >= lambda * (1 - 1e-10));
    MatDestroy(&K);
    MatDestroy(&lumped);
    MatDestroy(&M);
    //    A random velocity (every mode excited), seeded identically on every rank count
    gelx::OwnedVec v0(problem.create_vector());
    {
      PetscInt first, last;
      VecGetOwnershipRange(v0.get(), &first, &last);
      std::mt19937_64 random(7);
      std::uniform_real_distribution<double> uniform(-1, 1);
      PetscInt size;
      VecGetSize(v0.get(), &size);
      std::vector<double> values(size);
      for (double& x : values)
        x = 1e-6 * uniform(random);
      PetscScalar* v;
      VecGetArray(v0.get(), &v);
      for (PetscInt i = first; i < last; ++i)
        v[i - first] = values[i];
      VecRestoreArray(v0.get(), &v);
      VecGetArray(v0.get(), &v);
      for (PetscInt r : prescribed)
        v[r] = 0;
      VecRestoreArray(v0.get(), &v);
    }
    for (const double fraction : {1.1, 0.9})
    {
      const std::string prefix = fraction > 1 ? "above_" : "below_";
      gelx::set_default_option(prefix, "dt", real(fraction * critical));
      const Run r = run(linear, prefix, {200 * fraction * critical, v0.get()});
      double largest = 0;
      for (double e : r.energy)
        largest = std::max(largest, std::isfinite(e) ? e : INFINITY);
      const double growth = largest / r.energy[0];
      if (fraction > 1)
      {
        std::snprintf(text, sizeof text,
                      "1.1 x the critical step %.4e: the energy grows by %.3e > 1e6 in %d "
                      "steps",
                      critical, growth, r.steps);
        checks.require(text, r.diverged || growth > 1e6);
      }
      else
      {
        const double verlet = 1 / (1 - fraction * fraction);
        std::snprintf(text, sizeof text,
                      "0.9 x the critical step: the energy stays below E0 / (1 - 0.81) = %.3f "
                      "E0 (largest %.4f E0) over %d steps",
                      verlet, growth, r.steps);
        checks.require(text, !r.diverged && r.steps == 200 && growth <= verlet * (1 + 1e-9));
      }
    }
    //    The runs' own step (Gershgorin, fraction 0.9) never above the critical one
    {
      const Run r = run(linear, "estimated_", {20 * critical, v0.get()});
      const double dt = r.summary.integrator.at("smallest_stable_step");
      std::snprintf(text, sizeof text,
                    "the runs' stable-step estimate %.4e <= the critical step %.4e (%.3f of it)",
                    dt, critical, dt / critical);
      checks.require(text, dt <= critical);
    }

    // 3. Explicit against implicit, nonlinear: the neo-Hookean cantilever released in its
    //    first bending mode with a tip velocity giving a tip amplitude of about 0.2 L (the
    //    mode from the consistent mass; any large initial velocity would do), to a quarter
    //    of its period
    p.law = "neo_hookean";
    EulerColumn column(comm, p);
    auto modes = gelx::vibration_modes(comm, column.problem(), *column.mass_form(), 1);
    const double omega = std::sqrt(modes[0].load_factor);
    const double end_time = 0.25 * 2 * M_PI / omega;
    gelx::OwnedVec v_mode(dolfinx::la::petsc::create_vector_wrap(*modes[0].shape->x()));
    gelx::OwnedVec kick(column.problem().create_vector());
    VecCopy(v_mode.get(), kick.get());
    VecScale(kick.get(), 0.2 * p.L * omega);
    const Run explicit_run = run(column, "explicit_", {end_time, kick.get()});
    gelx::set_default_option("explicit_half_", "stable_step_fraction", "0.45");
    const Run explicit_half = run(column, "explicit_half_", {end_time, kick.get()});
    const double explicit_error = std::abs(explicit_run.tip - explicit_half.tip) / 3;
    const int n = 100;
    double implicit_tip[2], implicit_error = 0, consistent_tip = 0;
    for (int k = 0; k < 2; ++k)
    {
      const std::string prefix = "implicit_" + std::to_string(k) + "_";
      gelx::set_default_option(prefix, "ts_type", "alpha2");
      gelx::set_default_option(prefix, "mass", "lumped");
      gelx::set_default_option(prefix, "ts_adapt_type", "none");
      gelx::set_default_option(prefix, "dt", real(end_time / (n << k)));
      implicit_tip[k] = run(column, prefix, {end_time, kick.get()}).tip;
    }
    implicit_error = std::abs(implicit_tip[0] - implicit_tip[1]) / 3;
    gelx::set_default_option("consistent_", "ts_type", "alpha2");
    gelx::set_default_option("consistent_", "ts_adapt_type", "none");
    gelx::set_default_option("consistent_", "dt", real(end_time / (2 * n)));
    consistent_tip = run(column, "consistent_", {end_time, kick.get()}).tip;
    const double difference = std::abs(explicit_half.tip - implicit_tip[1]);
    const double allowed = 2 * (explicit_error + implicit_error);
    std::snprintf(text, sizeof text,
                  "explicit (%d steps) against TSALPHA2 (%d steps), lumped mass: tip %.8f "
                  "against %.8f, |difference| %.3e <= 2 (explicit error %.2e + implicit error "
                  "%.2e)",
                  explicit_half.steps, 2 * n, explicit_half.tip, implicit_tip[1], difference,
                  explicit_error, implicit_error);
    checks.require(text, difference <= allowed);
    const double control = std::abs(explicit_half.tip - consistent_tip);
    std::snprintf(text, sizeof text,
                  "control: TSALPHA2 with the consistent mass differs by %.3e > that bound %.3e",
                  control, allowed);
    checks.require(text, control > allowed);

    // 4. Mass scaling to twice the runs' stable step: half the steps, and mass added
    {
      const double dt = explicit_run.summary.integrator.at("smallest_stable_step");
      gelx::set_default_option("scaled_", "mass_scaling_step", real(2 * dt));
      const Run scaled = run(column, "scaled_", {end_time, kick.get()});
      const double added = scaled.summary.integrator.at("added_mass_ratio");
      std::snprintf(text, sizeof text,
                    "mass scaling to 2 dt: %d steps against %d (<= 0.55 of them), mass added "
                    "%.3e of the body's",
                    scaled.steps, explicit_run.steps, added);
      checks.require(text, scaled.steps <= 0.55 * explicit_run.steps && added > 0);
    }

    // 5. Restart, with mass scaling and Rayleigh mass damping
    {
      const std::string folder
          = "explicit_dynamics_checkpoints_np" + std::to_string(dolfinx::MPI::size(comm));
      gelx::Checkpoints checkpoints(comm, folder);
      checkpoints.clear();
      const double dt = explicit_run.summary.integrator.at("smallest_stable_step");
      gelx::set_default_option("restart_", "mass_scaling_step", real(1.5 * dt));
      gelx::set_default_option("restart_", "rayleigh_mass", real(0.05 * omega));
      gelx::set_default_option("restart_", "stable_step_every", "7");
      const Run whole = run(column, "restart_", {end_time, kick.get(), 40, &checkpoints});
      const auto newest = gelx::Checkpoints::newest(folder);
      gelx::PathState state = gelx::Checkpoints::read(comm, newest, column.problem());
      const Run continued = run(column, "restart_", {end_time, kick.get(), 0, nullptr, &state});
      checks.absolute("restart: final u against the uninterrupted run's",
                      relative_difference(continued.u.get(), whole.u.get()), 0, 1e-10);
      checks.absolute("restart: final v against the uninterrupted run's",
                      relative_difference(continued.v.get(), whole.v.get()), 0, 1e-10);
      // The control: continued with the lumped mass without its scaling
      state = gelx::Checkpoints::read(comm, newest, column.problem());
      Mat Mc = gelx::assemble_system_mass(column.problem(), *column.mass_form(), "test");
      Mat Ml = gelx::lumped_mass(Mc, column.problem().prescribed_rows(), "auto", method);
      MatGetDiagonal(Ml, state.vectors.at("lumped_mass").get());
      MatDestroy(&Ml);
      MatDestroy(&Mc);
      const Run unscaled = run(column, "restart_", {end_time, kick.get(), 0, nullptr, &state});
      const double off = relative_difference(unscaled.u.get(), whole.u.get());
      std::snprintf(text, sizeof text,
                    "control: continued with the unscaled mass, it differs by %.2e > 1e-6", off);
      checks.require(text, off > 1e-6);
      checkpoints.clear();
    }

    // 6. A moving support: the clamped-clamped column (linear law) shortened by the smooth
    //    step to 0.5 Euler loads over 10 axial periods (2 L sqrt(rho / E)), light mass
    //    damping, then held for 2 periods
    {
      ColumnParameters q = p;
      q.law = "linear_elastic";
      q.ends = "clamped-clamped";
      EulerColumn moved(comm, q);
      const double axial_period = 2 * q.L * std::sqrt(q.rho / moved.youngs_modulus());
      const double T = 10 * axial_period, lambda = 0.5;
      gelx::set_default_option("moving_", "ts_type", gelx::TSCENTRALDIFFERENCE);
      gelx::set_default_option("moving_", "loading_time", real(T));
      gelx::set_default_option("moving_", "hold_time", real(2 * axial_period));
      gelx::set_default_option("moving_", "ts_max_steps", "1000000");
      gelx::set_default_option("moving_", "rayleigh_mass", real(0.1 / axial_period));
      gelx::InertialDynamics dynamics(comm, moved.problem(), *moved.mass_form(),
                                      [&] { return moved.strain_energy(); },
                                      [&](double a) { moved.set_load_factor(a * lambda); },
                                      "moving_");
      const gelx::DynamicsSummary s = dynamics.run({});
      std::snprintf(text, sizeof text,
                    "moving support, %d steps: balance W - dSE - dKE - ED = %.3e of W = %.5e "
                    "(ED %.3e)",
                    s.steps, s.balance_residual / s.external_work, s.external_work,
                    s.dissipated_energy);
      // Central differences' energy error is O(dt^2) and oscillates with the axial
      // vibration; measured 2.8e-9 of W. The bound 1e-7 leaves a factor 36
      checks.absolute(text, s.balance_residual / s.external_work, 0, 1e-7);
      const double P_dynamic = moved.axial_force();
      gelx::NewtonSolver newton(comm, "moving_static_");
      checks.require("moving support: the static solution converges",
                     newton.solve(moved.problem()).converged);
      // The smooth step leaves an axial vibration of order 60 / (omega T)^3 = 2.4e-4 of the
      // travel (omega T = 2 pi 10); measured 1.1e-4
      checks.relative("moving support: axial force at the hold's end against the static "
                      "solution's",
                      P_dynamic, moved.axial_force(), 1e-3);
    }
    VecDestroy(&m);
  });
}
