// Verification: second-order dynamics with inertia (gelx::InertialDynamics, PETSc TSALPHA2).
//
// The slender column of the buckling scene as a cantilever (L = 30 tx, ty = 1.5 tx, clamped at
// z = 0, free at z = L, compressible neo-Hookean, G = 1, nu = 0.3, rho = 1, P2 tetrahedra on
// 2 x 3 x 40 boxes), set vibrating in its first bending mode (about the thin direction x) by
// an initial velocity, unloaded. The mode and its frequency omega_h come from the discrete
// problem K phi = omega^2 M phi (SLEPc); the closed forms are computed here. Checked:
//  1. the first bending period against Euler-Bernoulli's 2 pi / (1.8751^2 sqrt(EI/(rho A L^4)))
//     within 1 % (the bound), measured from the tip's zero crossings over ten periods
//     of a small-amplitude run with rho_inf = 1 (no numerical dissipation) at 40 steps per
//     period; and against the trapezoidal rule's own period for omega_h (the period
//     elongation T_h omega_h dt / (2 atan(omega_h dt / 2))), within 1e-4;
//  2. with rho_inf = 1 and no damping, the small-amplitude vibration's energy SE + KE kept
//     over those ten periods (the trapezoidal rule conserves a linear system's energy
//     exactly; what remains is the law's nonlinearity at this amplitude and the Newton
//     tolerance);
//  3. a large-amplitude (nonlinear) vibration's energy error after one period falling as
//     dt^2 over three step sizes;
//  4. with rho_inf = 0.5 at omega_h dt = 1, the energy's decay per step against the spectral
//     radius of generalised-alpha's amplification matrix for omega_h dt (computed here) and
//     the modal equation's generalised-alpha solution;
//  5. Rayleigh mass damping a M: the energy against the damped oscillator's and its
//     generalised-alpha solution, and the balance W = SE + KE + ED;
//  6. restart: a run checkpointed at step 25 and continued in a new integrator from the
//     checkpoint ends equal to the uninterrupted run (u, v to 1e-10 of their size); the same
//     restart without its acceleration differs;
//  7. fixed steps come back after a stage that failed;
//  8. a moving support: the clamped-clamped column (linear law) shortened by the smooth step
//     to half its Euler load over 20 periods of its first axial vibration: every step ends
//     with the moved end where it is prescribed, and the axial force at the ramp's end is
//     the static solution's (the quasi-static limit).
//
// Usage: test_inertial_dynamics [PETSc options]

#include "euler_column.h"
#include "support.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <dolfinx/la/petsc.h>
#include <dolfinx/common/MPI.h>
#include <gelx/solvers/buckling.h>
#include <gelx/io/checkpoint.h>
#include <gelx/solvers/inertia.h>
#include <gelx/solvers/newton.h>
#include <gelx/common/petsc_utils.h>
#include <string>
#include <vector>

namespace
{
using gelx::scenes::ColumnParameters;
using gelx::scenes::EulerColumn;

/// The spectral radius of generalised-alpha for u'' + omega^2 u = 0 at omega dt = w, with
/// PETSc's parameters for rho_inf (TSAlpha2SetRadius): the growth of |A^k x|^(1/k) of the
/// amplification matrix A of (u, dt v, dt^2 a) over many steps.
double generalised_alpha_radius(double rho_inf, double w)
{
  const double am = (2 - rho_inf) / (1 + rho_inf), af = 1 / (1 + rho_inf);
  const double gamma = 0.5 + am - af, beta = 0.25 * std::pow(1 + am - af, 2);
  // One step from x = (u, dt v, dt^2 a): with a1 unknown, u1 = u + dt v + (1/2 - beta) dt^2 a
  // + beta dt^2 a1, and (1 - am) a + am a1 + w^2 / dt^2 ((1 - af) u + af u1) = 0
  auto step = [&](std::array<double, 3> x)
  {
    const double w2 = w * w;
    const double a1
        = -((1 - am) * x[2] + w2 * (x[0] + af * (x[1] + (0.5 - beta) * x[2])))
          / (am + w2 * af * beta);
    const double u1 = x[0] + x[1] + (0.5 - beta) * x[2] + beta * a1;
    const double v1 = x[1] + (1 - gamma) * x[2] + gamma * a1;
    return std::array<double, 3>{u1, v1, a1};
  };
  std::array<double, 3> x{1, 0.3, -0.2};
  double log_growth = 0;
  const int n = 4000;
  for (int k = 0; k < n; ++k)
  {
    x = step(x);
    const double norm = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (k >= n / 2)
      log_growth += std::log(norm);
    for (double& c : x)
      c /= norm;
  }
  return std::exp(log_growth / (n - n / 2));
}

/// The energy ratio E_n / E_0 of the damped oscillator q'' + c q' + omega^2 q = 0, q(0) = 0,
/// q'(0) = 1, after n steps of dt of generalised-alpha with PETSc's parameters for rho_inf,
/// started from the consistent acceleration -c: the modal equation of the cantilever's run
double generalised_alpha_oscillator(double rho_inf, double omega, double c, double dt, int n)
{
  const double am = (2 - rho_inf) / (1 + rho_inf), af = 1 / (1 + rho_inf);
  const double gamma = 0.5 + am - af, beta = 0.25 * std::pow(1 + am - af, 2);
  const double w2 = omega * omega;
  double q = 0, v = 1, a = -c;
  for (int k = 0; k < n; ++k)
  {
    // (1 - am) a + am a1 + c ((1 - af) v + af v1) + w2 ((1 - af) q + af q1) = 0, a1 unknown
    const double q_known = q + dt * v + dt * dt * (0.5 - beta) * a;
    const double v_known = v + dt * (1 - gamma) * a;
    const double a1 = -((1 - am) * a + c * ((1 - af) * v + af * v_known)
                        + w2 * ((1 - af) * q + af * q_known))
                      / (am + c * af * dt * gamma + w2 * af * dt * dt * beta);
    q = q_known + dt * dt * beta * a1;
    v = v_known + dt * gamma * a1;
    a = a1;
  }
  return v * v + w2 * q * q;
}

struct Sample
{
  double t, tip, energy, work, dissipated, balance;
};

/// A run's samples at every step (the first at t = 0) and its final state
struct Vibration
{
  std::vector<Sample> samples;
  std::vector<double> steps; ///< the step sizes taken
  gelx::OwnedVec u, v;
};

/// The cantilever and its first bending mode
struct Cantilever
{
  ColumnParameters p;
  std::unique_ptr<EulerColumn> column;
  double omega = 0; ///< omega_h of the discrete problem
  std::shared_ptr<dolfinx::fem::Function<double>> mode;
  double period() const { return 2 * M_PI / omega; }
};

Cantilever cantilever(MPI_Comm comm, std::array<int, 3> cells,
                      const std::string& law = "neo_hookean")
{
  Cantilever c;
  c.p.cells = cells;
  c.p.law = law;
  c.column = std::make_unique<EulerColumn>(comm, c.p);
  auto modes = gelx::vibration_modes(comm, c.column->problem(), *c.column->mass_form(), 1);
  c.omega = std::sqrt(modes[0].load_factor);
  c.mode = modes[0].shape;
  return c;
}

std::string real(double v)
{
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

/// A system that declares one state inadmissible, the `at`-th it is asked about (as if
/// det F <= 0 there), and is otherwise `inner`: the stage fails and TS retries it smaller
class InadmissibleOnce : public gelx::SystemDecorator
{
public:
  InadmissibleOnce(gelx::NonlinearSystem& inner, int at) : SystemDecorator(inner), _at(at) {}
  bool admissible() const override { return ++_asked != _at && _inner.admissible(); }

private:
  int _at;
  mutable int _asked = 0;
};

/// What a run does besides vibrating
struct RunOptions
{
  int save_at = 0;                           ///< checkpoint the state after this step ...
  gelx::Checkpoints* checkpoints = nullptr;  ///< ... here
  const gelx::PathState* resume = nullptr;   ///< continue from this state
  int inadmissible_at = 0; ///< declare the state of this residual evaluation inadmissible
};

/// Run the cantilever from rest in the undeformed state with the initial velocity
/// `amplitude` omega_h phi (phi the mode, largest component 1: the tip's amplitude is about
/// `amplitude`) for `steps` steps of `dt`, options prefix `prefix` (fixed steps unless the
/// prefix's options say otherwise).
Vibration vibrate(Cantilever& c, double amplitude, int steps, double dt, const std::string& prefix,
                  const RunOptions& o = {})
{
  EulerColumn& column = *c.column;
  gelx::NonlinearProblem& problem = column.problem();
  gelx::set_default_option(prefix, "loading_time", real(steps * dt));
  gelx::set_default_option(prefix, "dt", real(dt));
  gelx::set_default_option(prefix, "ts_adapt_type", "none");
  // Newton to near round-off, which the energy checks rest on: |R| <= 1e-10 |R0| or 1e-13
  // (the small-amplitude run's residual falls from 5e-8 to a floor of 1.3e-15, measured), or
  // a step below 1e-14 of the state
  gelx::set_default_option(prefix, "snes_rtol", "1e-10");
  gelx::set_default_option(prefix, "snes_atol", "1e-13");
  gelx::set_default_option(prefix, "snes_stol", "1e-14");
  if (!o.resume)
  {
    VecSet(problem.unknowns(), 0.0);
    problem.unknowns_changed();
  }
  InadmissibleOnce system(problem, o.inadmissible_at);
  gelx::InertialDynamics dynamics(column.mesh().mesh->comm(), system, *column.mass_form(),
                                  [&] { return column.strain_energy(); }, [](double) {},
                                  prefix);
  gelx::OwnedVec mode(dolfinx::la::petsc::create_vector_wrap(*c.mode->x()));
  gelx::OwnedVec v0(problem.create_vector());
  VecCopy(mode.get(), v0.get());
  VecScale(v0.get(), amplitude * c.omega);
  dynamics.set_initial_velocity(v0.get());
  Vibration run;
  if (!o.resume)
  {
    gelx::OwnedVec work(problem.create_vector());
    run.samples.push_back({0, 0,
                           column.strain_energy()
                               + 0.5 * gelx::quadratic_form(dynamics.mass(), v0.get(), work.get()),
                           0, 0, 0});
  }
  dynamics.run({[&](const gelx::DynamicsRecord& r)
                {
                  run.steps.push_back(r.step.step_size);
                  run.samples.push_back({r.time, column.tip_deflection()[0] * c.p.L,
                                         r.strain_energy + r.kinetic_energy, r.external_work,
                                         r.dissipated_energy, r.balance_residual});
                  if (r.step.step == o.save_at && o.checkpoints)
                  {
                    gelx::PathState state;
                    dynamics.save(state);
                    o.checkpoints->write(system, state, {});
                  }
                }},
               o.resume);
  run.u.reset(problem.create_vector());
  VecCopy(problem.unknowns(), run.u.get());
  run.v.reset(problem.create_vector());
  VecCopy(dynamics.velocity(), run.v.get());
  return run;
}

/// |a - b| / |b|
double relative_difference(Vec a, Vec b)
{
  gelx::OwnedVec d;
  Vec diff;
  VecDuplicate(a, &diff);
  d.reset(diff);
  VecWAXPY(diff, -1.0, b, a);
  double nd, nb;
  VecNorm(diff, NORM_2, &nd);
  VecNorm(b, NORM_2, &nb);
  return nd / nb;
}

/// The largest |E - E0| / E0 over the samples
double energy_drift(const std::vector<Sample>& s)
{
  double drift = 0;
  for (const Sample& x : s)
    drift = std::max(drift, std::abs(x.energy - s[0].energy) / s[0].energy);
  return drift;
}

/// The mean period of the upward zero crossings of the tip (linear interpolation)
double measured_period(const std::vector<Sample>& s)
{
  std::vector<double> crossings;
  for (std::size_t k = 1; k < s.size(); ++k)
    if (s[k - 1].tip < 0 && s[k].tip >= 0)
      crossings.push_back(s[k - 1].t
                          + (s[k].t - s[k - 1].t) * (-s[k - 1].tip) / (s[k].tip - s[k - 1].tip));
  if (crossings.size() < 2)
    return NAN;
  return (crossings.back() - crossings.front()) / (crossings.size() - 1);
}
} // namespace

int main(int argc, char* argv[])
{
  return gelx::test::run_checks(argc, argv, [](MPI_Comm comm, gelx::test::Checks& checks)
  {
    // The buckling scene's mesh for the period; a coarser one (1 x 1 x 20 boxes) for the
    // checks of the integrator, which hold on any mesh with its own omega_h
    Cantilever c = cantilever(comm, {2, 3, 40});
    const double E = 2 * c.p.G * (1 + c.p.nu), I = c.p.ty * std::pow(c.p.tx, 3) / 12;
    const double A = c.p.tx * c.p.ty;
    const double omega_eb
        = std::pow(1.875104068711961, 2) * std::sqrt(E * I / (c.p.rho * A * std::pow(c.p.L, 4)));
    const double T_eb = 2 * M_PI / omega_eb, T_h = c.period();

    // 1. The period (small amplitude: the tip moves 1e-3 tx, strains ~ 1e-6), rho_inf = 1
    //    (PETSc's default), 40 steps per period, three periods. 1 % against Euler-Bernoulli:
    //    shear and rotary inertia change omega by ~ (r/L)^2 (1 + E/(kappa G)) = 4e-4 here, the
    //    mesh by less (P2); 1e-4 against the trapezoidal rule's period of omega_h: the zero
    //    crossings' linear interpolation (sin is straight at zero to O(dt^3))
    const int per_period = 40;
    const Vibration small = vibrate(c, 1e-3, 3 * per_period, T_h / per_period, "period_");
    const double T_run = measured_period(small.samples);
    checks.relative("first bending period against Euler-Bernoulli's", T_run, T_eb, 0.01);
    const double w = c.omega * T_h / per_period;
    checks.relative("period against the trapezoidal rule's for omega_h", T_run,
                    T_h * w / (2 * std::atan(w / 2)), 1e-4);

    Cantilever coarse = cantilever(comm, {1, 1, 20});
    const double T_coarse = coarse.period();
    Cantilever linear = cantilever(comm, {1, 1, 20}, "linear_elastic");
    const double T_linear = linear.period();

    // 2. The linear vibration's energy over ten periods, rho_inf = 1: conserved to
    //    the linear solves' round-off: 400 steps of LU solves with relative errors ~ cond eps
    //    (measured 4.6e-9; on the neo-Hookean law at this amplitude its stored energy alone is
    //    evaluated to 5e-5 only, as I1 J^-2/3 - 3 ~ 1e-12 cancels)
    const double drift = energy_drift(
        vibrate(linear, 1e-3, 10 * per_period, T_linear / per_period, "linear_").samples);
    char text[160];
    std::snprintf(text, sizeof text,
                  "rho_inf = 1, linear law: SE + KE kept over ten periods to %.2e <= 2e-8", drift);
    checks.require(text, drift <= 2e-8);

    // 3. A large-amplitude vibration (tip amplitude 0.2 L, neo-Hookean): its energy error
    //    over one period at 20, 40 and 80 steps per period falls at least as dt^2: ratios of
    //    at least 3.4 per halving (a first-order integrator gives 2). Measured 15.7 and 15.4:
    //    dt^4, faster than the trapezoidal rule's general dt^2, as the per-step errors of a
    //    symmetric oscillation cancel over its period
    std::vector<double> errors;
    for (int n : {20, 40, 80})
      errors.push_back(energy_drift(
          vibrate(coarse, 0.2 * coarse.p.L, n, T_coarse / n, "nonlinear_" + std::to_string(n) + "_").samples));
    for (std::size_t k = 0; k + 1 < errors.size(); ++k)
    {
      std::snprintf(text, sizeof text,
                    "large amplitude: energy error %.3e / %.3e at halved dt = %.2f >= 3.4",
                    errors[k], errors[k + 1], errors[k] / errors[k + 1]);
      checks.require(text, errors[k] / errors[k + 1] >= 3.4);
    }

    // 4. rho_inf = 0.5 at omega_h dt = 1: the energy of the mode decays per step as the
    //    square of the amplification's spectral radius (1e-3: measured over steps 50 to 250,
    //    so that the start's other roots have died out and the energy's oscillation within a
    //    period, a few % of it, spreads over 200 steps; measured 1.2e-4), and equals the
    //    modal equation's generalised-alpha solution (1e-6, as in 5.)
    gelx::set_default_option("decay_", "ts_alpha_radius", "0.5");
    const Vibration decaying = vibrate(linear, 1e-3, 250, 1 / linear.omega, "decay_");
    const double rho = generalised_alpha_radius(0.5, 1.0);
    const double measured_rho
        = std::pow(decaying.samples[250].energy / decaying.samples[50].energy, 1.0 / 400);
    checks.relative("rho_inf = 0.5, omega dt = 1: decay per step against the spectral radius",
                    measured_rho, rho, 1e-3);
    checks.relative("rho_inf = 0.5: energy after 250 steps against the oscillator's "
                    "generalised-alpha solution",
                    decaying.samples[250].energy / decaying.samples[0].energy,
                    generalised_alpha_oscillator(0.5, linear.omega, 0, 1 / linear.omega, 250),
                    1e-6);
    checks.require("rho_inf = 0.5: spectral radius " + std::to_string(rho) + " < 0.999",
                   rho < 0.999);

    // 5. Rayleigh mass damping a = 0.02 omega_h over five periods: E(t) / E0 against the damped
    //    oscillator's, the continuous one within 1 % (generalised-alpha's error in the decay,
    //    measured 5.2e-3 at 40 steps per period) and its generalised-alpha solution (both
    //    computed here) within 1e-6: the mode is the modal equation's, exactly, on a linear
    //    law; and the balance: with the supports at rest, the energy lost is the viscous
    //    dissipation integrated from the velocities
    const double a = 0.02 * linear.omega;
    gelx::set_default_option("damped_", "rayleigh_mass", real(a));
    const Vibration damped = vibrate(linear, 1e-3, 5 * per_period, T_linear / per_period, "damped_");
    {
      const double zeta = a / (2 * linear.omega), wd = linear.omega * std::sqrt(1 - zeta * zeta);
      const double t = damped.samples.back().t;
      // x = e^(-zeta w t) sin(wd t) / wd for x(0) = 0, x'(0) = 1
      const double x = std::exp(-zeta * linear.omega * t) * std::sin(wd * t) / wd;
      const double xdot = std::exp(-zeta * linear.omega * t)
                          * (std::cos(wd * t) - zeta * linear.omega / wd * std::sin(wd * t));
      const double exact = xdot * xdot + linear.omega * linear.omega * x * x;
      const double ratio = damped.samples.back().energy / damped.samples[0].energy;
      checks.relative("Rayleigh a = 0.02 omega: energy after five periods against the damped "
                      "oscillator's",
                      ratio, exact, 0.01);
      checks.relative("Rayleigh a = 0.02 omega: against the oscillator's generalised-alpha "
                      "solution",
                      ratio,
                      generalised_alpha_oscillator(1.0, linear.omega, a, T_linear / per_period,
                                                   5 * per_period),
                      1e-6);
      const Sample& end = damped.samples.back();
      std::snprintf(text, sizeof text,
                    "Rayleigh damping: balance residual / E0 (energy lost %.4e, ED %.4e)",
                    damped.samples[0].energy - end.energy, end.dissipated);
      checks.absolute(text, end.balance / damped.samples[0].energy, 0.0, 1e-8);
    }

    // 6. Restart, with adaptive steps (TSALPHA2's error estimate uses the previous step) and
    //    rho_inf = 0.8 (with 1, the trapezoidal rule's u and v do not depend on the
    //    acceleration, which the control below needs): a large-amplitude run of 1.375
    //    periods (u and v both far from zero at its end) checkpointed at step 25 and
    //    continued from the checkpoint in a new integrator ends equal to the uninterrupted
    //    run (at 1 rank to the bit; at 2, MPI's reduction order moves the last digits)
    const std::string folder
        = "inertial_dynamics_checkpoints_np" + std::to_string(dolfinx::MPI::size(comm));
    gelx::Checkpoints checkpoints(comm, folder);
    checkpoints.clear();
    gelx::set_default_option("restart_", "ts_adapt_type", "basic");
    gelx::set_default_option("restart_", "ts_alpha_radius", "0.8");
    gelx::set_default_option("restart_", "ts_rtol", "1e-4");
    gelx::set_default_option("restart_", "ts_atol", "1e-4");
    const int steps = 60;
    const Vibration whole = vibrate(coarse, 0.1 * coarse.p.L, steps, 1.375 * T_coarse / steps,
                                    "restart_", {25, &checkpoints});
    const auto checkpoint = gelx::Checkpoints::newest(folder);
    gelx::PathState state = gelx::Checkpoints::read(comm, checkpoint, coarse.column->problem());
    checks.require("checkpoint at step 25 with the velocity and acceleration",
                   state.step == 25 && state.vectors.count("velocity")
                       && state.vectors.count("acceleration"));
    const Vibration continued
        = vibrate(coarse, 0.1 * coarse.p.L, steps, 1.375 * T_coarse / steps, "restart_",
                  {0, nullptr, &state});
    checks.require("adaptive steps: " + std::to_string(whole.samples.size() - 1) + " steps",
                   whole.samples.size() > 2);
    checks.absolute("restarted run's final u against the uninterrupted run's",
                    relative_difference(continued.u.get(), whole.u.get()), 0, 1e-10);
    checks.absolute("restarted run's final v against the uninterrupted run's",
                    relative_difference(continued.v.get(), whole.v.get()), 0, 1e-10);
    // The control: the same restart with the acceleration lost ends elsewhere
    state = gelx::Checkpoints::read(comm, checkpoint, coarse.column->problem());
    VecSet(state.vectors.at("acceleration").get(), 0.0);
    const Vibration lost
        = vibrate(coarse, 0.1 * coarse.p.L, steps, 1.375 * T_coarse / steps, "restart_",
                  {0, nullptr, &state});
    const double off = relative_difference(lost.u.get(), whole.u.get());
    std::snprintf(text, sizeof text,
                  "control: the restart without its acceleration differs by %.2e > 1e-7", off);
    checks.require(text, off > 1e-7);
    checkpoints.clear();

    // 7. Fixed steps after a failed stage: the step TS cut (a quarter) comes back at once
    //    (PETSc's TSADAPTNONE would keep it to the end)
    const double dt = T_coarse / per_period;
    const Vibration cut = vibrate(coarse, 1e-3, 20, dt, "cut_", {0, nullptr, nullptr, 20});
    //    (the last step is short too: it ends the run at 20 dt)
    int short_steps = 0;
    for (std::size_t k = 0; k + 1 < cut.steps.size(); ++k)
      short_steps += cut.steps[k] < 0.99 * dt;
    std::snprintf(text, sizeof text,
                  "fixed steps: one cut step (%.3g of dt) among %zu, then dt again: %d short "
                  "before the last",
                  *std::min_element(cut.steps.begin(), cut.steps.end()) / dt, cut.steps.size(),
                  short_steps);
    checks.require(text, short_steps == 1 && cut.samples.back().t > (20 - 1e-9) * dt);

    // 8. A moving support: the clamped-clamped column (linear law, 1 x 1 x 20 boxes, straight)
    //    shortened by the smooth step to 0.5 Euler loads over T = 20 periods of its first axial
    //    vibration (2 L sqrt(rho / E)), 100 fixed steps, rho_inf = 1 (no dissipation to hide
    //    an error), then held for 10 steps.
    //    a. Every step ends on the prescribed shortening g(t_n): the moved end's rows of
    //       u - g(t_n) within 1e-12 of the end's travel (the stage's amplitude is the step's
    //       alpha_f-weighted one; at A(t_n + alpha_f dt), the amplitude at the stage time,
    //       the ends are off by up to g'' dt^2 / 4 ~ 1.4e-4 of the travel, measured 7.2e-5;
    //       measured here 1.0e-15).
    //    b. The quasi-static limit: at the end of the hold the axial force is the static
    //       solution's at that shortening (solved here) within 1e-3: the smooth step leaves a
    //       residual axial vibration of order 60 / (omega T)^3 ~ 3e-5 of the travel, and
    //       bending is not excited by a straight column's shortening below its critical load
    //       (measured 7.0e-6)
    {
      ColumnParameters q;
      q.cells = {1, 1, 20};
      q.law = "linear_elastic";
      q.ends = "clamped-clamped";
      EulerColumn moved(comm, q);
      gelx::NonlinearProblem& problem = moved.problem();
      const double axial_period = 2 * q.L * std::sqrt(q.rho / moved.youngs_modulus());
      const double T = 20 * axial_period, lambda = 0.5;
      const int ramp_steps = 100, hold_steps = 10;
      gelx::set_default_option("moving_", "loading_time", real(T));
      gelx::set_default_option("moving_", "hold_time", real(hold_steps * T / ramp_steps));
      gelx::set_default_option("moving_", "dt", real(T / ramp_steps));
      gelx::set_default_option("moving_", "ts_adapt_type", "none");
      gelx::set_default_option("moving_", "snes_rtol", "1e-10");
      gelx::set_default_option("moving_", "snes_atol", "1e-13");
      gelx::InertialDynamics dynamics(comm, problem, *moved.mass_form(),
                                      [&] { return moved.strain_energy(); },
                                      [&](double a) { moved.set_load_factor(a * lambda); },
                                      "moving_");
      // The prescribed rows' u - g at the step's own time (the observers see the loads at
      // A(t_n)), over the end's travel g(T)
      const std::vector<PetscInt> prescribed = problem.prescribed_rows();
      gelx::OwnedVec r(problem.create_vector());
      auto largest_prescribed = [&](Vec x)
      {
        const PetscScalar* values;
        VecGetArrayRead(x, &values);
        double largest = 0;
        for (PetscInt i : prescribed)
          largest = std::max(largest, std::abs(values[i]));
        VecRestoreArrayRead(x, &values);
        MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, comm);
        return largest;
      };
      double off = 0;
      int steps = 0;
      dynamics.run({[&](const gelx::DynamicsRecord&)
                    {
                      problem.residual(r.get());
                      off = std::max(off, largest_prescribed(r.get()));
                      ++steps;
                    }});
      const double travel = largest_prescribed(problem.unknowns());
      const double P_dynamic = moved.axial_force();
      std::snprintf(text, sizeof text,
                    "moving support: the moved end's u - g at %d step ends <= %.2e of its "
                    "travel %.4g",
                    steps, off / travel, travel);
      checks.require(text, steps == ramp_steps + hold_steps && off <= 1e-12 * travel);
      gelx::NewtonSolver newton(comm, "moving_static_");
      checks.require("moving support: the static solution converges",
                     newton.solve(problem).converged);
      checks.relative("moving support: axial force at the hold's end against the static "
                      "solution's",
                      P_dynamic, moved.axial_force(), 1e-3);
    }
  });
}
