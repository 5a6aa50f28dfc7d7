#include "methods.h"

#include <gelx/solvers/arclength.h>
#include <gelx/solvers/central_difference.h>
#include <gelx/solvers/dynamics.h>
#include <gelx/solvers/inertia.h>
#include <gelx/solvers/newton.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/io/progress.h>
#include <cmath>
#include <utility>

namespace gelx::scenes
{
namespace
{
/// The solver defaults of each method, for the default strip (the user's options win). Time
/// in s with the density of rubber (rho = 1e-9 t/mm^3 in mm, MPa units); the bonded strip's
/// first free vibration has a period of 0.0206 s (SLEPc, 40 slabs; README).
void set_method_defaults(const std::string& method)
{
  if (method == "dynamics")
  {
    // The flow: c = 1/s relaxes the first bending mode within milliseconds, so a loading
    // time of 1 s is quasi-static wherever the path is stable
    set_default_options("dynamics_", {{"loading_time", "1"},
                                      {"hold_time", "0.05"},
                                      {"damping", "1"},
                                      {"ts_rtol", "1e-3"},
                                      {"ts_atol", "1e-3"}});
  }
  else if (method == "inertia")
  {
    // The equation of motion over the same loading time (50 periods of the first mode).
    // Fixed steps of 1 ms (20 per period): TSALPHA2's error estimate weighs the velocities'
    // error with the displacements' tolerances, and its adaptive steps fell to microseconds
    // at 28.5 cm, long before the strip buckles (measured). rho_inf = 0.5 and a Rayleigh mass
    // damping of 30/s (5 % of critical on the first mode, a / (2 omega_1)) take out what
    // the steps do not resolve and the energy the snap into helices releases: without them
    // (2 ms, rho_inf = 0.8) the run went through the first perversion and then diverged
    // (kinetic energy 1e153, measured)
    set_default_options("inertial_", {{"loading_time", "1"},
                                      {"hold_time", "0.05"},
                                      {"ts_adapt_type", "none"},
                                      {"dt", "1e-3"},
                                      {"ts_alpha_radius", "0.5"},
                                      {"rayleigh_mass", "30"}});
  }
  else if (method == "explicit")
  {
    // Central differences over the same loading time and damping, without mass scaling:
    // the default strip's stable-step estimate is 1.24e-6 s (through the layers' thickness),
    // 8e5 steps for the path, and scaling the mass to 4 times that step already adds 3.7
    // times the strip's mass (measured: README), which would change the dynamics studied
    set_default_options("explicit_", {{"ts_type", TSCENTRALDIFFERENCE},
                                      {"loading_time", "1"},
                                      {"hold_time", "0.05"},
                                      {"rayleigh_mass", "30"}});
  }
  else if (method == "arclength")
  {
    set_default_options("arclength_", {{"ds", "20"}, {"ds_max", "200"}});
  }
}

/// The end from its distance now to `to`, as a load of amplitude 0 to 1
std::function<void(double)> move_end(Bistrip& strip, double to)
{
  const double from = strip.end_distance();
  return [&strip, from, to](double amplitude)
  { strip.set_end_distance(from + amplitude * (to - from)); };
}
} // namespace

void follow_path(Run& run, Bistrip& strip, const BistripParameters& p, const BistripAnalysis& a,
                 PathRecord& record)
{
  NonlinearProblem& problem = strip.problem();
  set_method_defaults(a.method);
  const double travel = p.L - a.end_distance;
  // One progress line per step: the end distance, the end force
  const ProgressLine::Options progress_options{
      .load_name = "end distance",
      .load = [&](const StepRecord&) { return strip.end_distance(); },
      .quantity = [&] { return quantity_text("end force", record.end_force()); }};

  if (a.method == "arclength")
  {
    // Continuation in the end shortening: the Dirichlet values follow the load factor, and
    // ArcLength's dR/dlambda of the lifted residual carries them
    record.begin_leg(1);
    ArcLength continuation(run.comm(), problem,
                           [&](double shortening) { strip.set_end_distance(p.L - shortening); });
    PathState path;
    ProgressLine::Options arclength_progress = progress_options;
    arclength_progress.fraction = [&](const StepRecord& pt) { return pt.load / travel; };
    continuation.run(
        path, a.max_steps,
        {[&](const StepRecord& pt, PathState&)
         {
           record.step_done({{"step", pt.step},
                             {"arc_length", pt.arc_length},
                             {"newton_iterations", pt.newton.iterations},
                             {"cutbacks", pt.cutbacks},
                             {"wall_time", pt.wall_time}},
                            0.0, 0.0, pt.load >= travel);
         },
         ProgressLine(run.comm(), arclength_progress)},
        [&](const StepRecord& pt) { return pt.load >= travel; });
    run.summary["arclength_steps"] = path.step;
    if (strip.end_distance() > a.end_distance)
      throw ConvergenceError("arc-length stopped at end distance "
                             + std::to_string(strip.end_distance()) + " mm after "
                             + std::to_string(path.step) + " steps");
    return;
  }

  // In time: a leg drives `load` from 0 to 1 on the smooth step (options prefix `prefix`,
  // summary under `key`); `dissipated_before` is the energy damping dissipated on the legs
  // before it (each leg's TS counts from 0). Returns the dissipation up to its end.
  const bool inertia = a.method == "inertia" || a.method == "explicit";
  // The path checkpoints after its steps and continues from a checkpoint (--restart): the
  // integrator's state, and the record's in its scene state
  const PathState start = run.start_path(problem);
  const bool resuming = start.step > 0;
  // The integrator's state of the checkpoint, for the first leg driven (the one it is in)
  const PathState* resume = resuming ? &start : nullptr;
  const StepObserver checkpoints = run.checkpoints();
  // A step's checkpoint: the integrator's state, the record's, the dissipation before the leg
  auto checkpoint = [&](const StepRecord& step, PathState& state, double dissipated_before)
  {
    state.scene = record.state();
    state.scene["dissipated_before"] = dissipated_before;
    checkpoints(step, state);
  };
  // A leg's outputs besides its last: a moving end's every output_every of travel (the
  // record's), and `held_output(record, end_time)` for a leg with the end held, which has no
  // travel to output by
  using HeldOutput = std::function<bool(const DynamicsRecord&, double)>;
  auto drive = [&](std::function<void(double)> load, double dissipated_before,
                   const std::string& key, const std::string& prefix, bool inertia,
                   const HeldOutput& held_output = {})
  {
    ProgressLine progress(run.comm(), progress_options);
    auto observe = [&](const DynamicsRecord& r, const DynamicsSummary& so_far, double end_time)
    {
      // The flow's kinetic energy is a diagnostic of the regularised velocity, no term of
      // its balance; with inertia it is one
      record.step_done(r.to_json(), dissipated_before + r.dissipated_energy,
                       inertia ? r.kinetic_energy : 0.0,
                       (held_output && held_output(r, end_time)) || r.time >= end_time - 1e-12);
      run.summary[key] = so_far.to_json();
      StepRecord step = r.step; // numbered over the legs, as steps.csv is
      step.step = record.steps();
      progress.print(step, strip.end_distance(), r.time / end_time);
    };
    // Either integrator: observed, checkpointed after every step, resumed by the first leg
    auto follow = [&](auto& dynamics)
    {
      return dynamics.run(
          {[&](const DynamicsRecord& r)
           {
             observe(r, dynamics.summary(), dynamics.end_time());
             PathState state;
             dynamics.save(state);
             checkpoint(r.step, state, dissipated_before);
           }},
          std::exchange(resume, nullptr));
    };
    DynamicsSummary summary;
    if (inertia)
    {
      InertialDynamics dynamics(run.comm(), problem, *strip.mass_form(),
                                [&] { return strip.strain_energy(); }, load, prefix);
      summary = follow(dynamics);
    }
    else
    {
      DampedDynamics dynamics(run.comm(), problem, *strip.mass_form(),
                              [&] { return strip.strain_energy(); }, load, prefix);
      summary = follow(dynamics);
    }
    run.summary[key] = summary.to_json();
    return dissipated_before + summary.dissipated_energy;
  };

  // The leg a checkpoint is in (-1: a new path); the legs before it are done
  int resumed_leg = -1;
  double dissipated = 0;
  if (resuming)
  {
    record.restore(start.scene);
    resumed_leg = record.leg();
    dissipated = start.scene.at("dissipated_before");
  }
  const std::string prefix = a.method == "explicit" ? "explicit_"
                             : inertia               ? "inertial_"
                                                     : "dynamics_";
  const std::string key = a.method == "explicit" ? "explicit_dynamics"
                          : inertia              ? "inertial_dynamics"
                                                 : "dynamics";
  // With inertia a quench is the release itself: the strip bonded with all of A's
  // pre-compression and let go at L under the path's equation of motion (options
  // -bonding_inertial_ or -bonding_explicit_), so that the dynamics, not a gradient flow,
  // picks the wavelengths that grow
  const bool inertial_quench = inertia && a.bonding == "quench";
  const std::string bonding_prefix = inertial_quench ? "bonding_" + prefix : "bonding_dynamics_";
  const std::string bonding_key = inertial_quench ? "bonding_" + key : "bonding_dynamics";
  if (a.bonding != "instant" && resumed_leg <= 0)
  {
    // Leg 0, the end held at L: a ramp builds the prestretch up over 1 s, at the path's
    // damping. A quench leaves the bonded strip to buckle: under a fixed load the
    // first-order dynamics c M u' = -R(u) is a gradient flow whose trajectory does not
    // depend on c, only its time scale does (t / c), so c is chosen for the steps: the
    // fastest modes grow at ~1e8/s for c = 1 (stretch 0.4), at a few per second for
    // c = 1e8; 2000 s of it settle (Fig. 3.8a's pattern from the fastest-growing
    // wavelengths; measured at nz = 60: after 200 s, 16 perversions and still 6 negative
    // eigenvalues, from which the path at c = 1 needs microsecond steps). The balance of the
    // legs after it starts from where it ends (the prestretch's own work is not the end
    // force's)
    const bool quench = a.bonding == "quench";
    if (inertial_quench)
    {
      // The fastest modes grow at ~1e4/s under inertia (the square root of the flow's rate
      // at c = 1): central differences at their stable step, or TSALPHA2 at fixed steps of
      // 10 us, whose rho_inf = 0.5 damps the section's ringing they do not resolve (its
      // adaptive steps stayed at 1 us for it: 740 steps in the first minute at nz = 15,
      // measured); the path's damping
      if (a.method == "explicit")
        set_default_options("bonding_explicit_", {{"ts_type", TSCENTRALDIFFERENCE}});
      else
        set_default_options("bonding_inertial_", {{"dt", "1e-5"},
                                                  {"ts_adapt_type", "none"},
                                                  {"ts_alpha_radius", "0.5"}});
      set_default_options(bonding_prefix,
                          {{"loading_time", "0.05"}, {"hold_time", "0"}, {"rayleigh_mass", "30"}});
    }
    else
    {
      set_default_options(bonding_prefix, {{"loading_time", quench ? "2000" : "1"},
                                           {"hold_time", "0.05"},
                                           {"damping", quench ? "1e8" : "1"},
                                           {"ts_rtol", "1e-3"},
                                           {"ts_atol", "1e-3"}});
    }
    if (resumed_leg < 0)
      record.begin_leg(0);
    // The release's outputs: 50 at equal times (its explicit steps number 1e5; a step's
    // slot from its time and size, so that a restart keeps them)
    const HeldOutput fiftieths = [](const DynamicsRecord& r, double end_time)
    {
      const auto slot = [end_time](double t) { return std::floor(50 * t / end_time + 1e-9); };
      return slot(r.time) > slot(r.time - r.step.step_size);
    };
    drive([&](double s) { strip.set_prestretch_fraction(quench ? 1 : s); }, 0, bonding_key,
          bonding_prefix, inertial_quench, inertial_quench ? fiftieths : HeldOutput{});
  }
  // With the end distance at L, the bonding leg is the whole path
  const bool moves_in = a.end_distance < p.L;
  if (resumed_leg < 1 && moves_in)
  {
    if (inertia && !inertial_quench)
    {
      // The motion starts at rest from the bonded strip's static equilibrium at L: u = 0 is
      // none (A's prestretch pulls on the clamps and contracts the section), and released
      // from it the strip rang with 3.8 mJ of kinetic energy after the first 2 ms (measured)
      NewtonSolver bonded(run.comm(), "bonded_newton_");
      if (!bonded.solve(problem).converged)
        throw ConvergenceError("the bonded strip's equilibrium at L did not converge");
    }
    record.begin_leg(1);
  }
  // Each leg's end moves from where the leg starts: L, then end_distance
  if (record.leg() == 1 && moves_in)
  {
    strip.set_end_distance(p.L);
    dissipated = drive(move_end(strip, a.end_distance), dissipated, key, prefix, inertia);
  }
  if (a.return_distance > 0 && record.leg() <= 2)
  {
    if (record.leg() == 1)
      record.begin_leg(2);
    strip.set_end_distance(a.end_distance);
    dissipated = drive(move_end(strip, a.return_distance), dissipated, "return_" + key, prefix,
                       inertia);
  }
  if (a.settle_time > 0)
  {
    // Leg 3, the end held where the path left it: a gradient flow from the path's state
    // (the damped flow at c = 1/s relaxes a mode of M^-1 K eigenvalue lambda at the rate
    // lambda / c: the stiff ones at once, a slow perversion's sliding mode slowly), with no
    // load to ramp; the static Newton solve of --equilibria failed from such states at rest
    // (README "Rate study": a nearly singular tangent)
    if (record.leg() < 3)
      record.begin_leg(3);
    set_default_options("settle_dynamics_", {{"loading_time", std::to_string(a.settle_time)},
                                             {"hold_time", "0"},
                                             {"damping", "1"},
                                             {"ts_rtol", "1e-4"},
                                             {"ts_atol", "1e-4"}});
    drive([](double) {}, dissipated, "settle_dynamics", "settle_dynamics_", false,
          [](const DynamicsRecord& r, double) { return r.step.step % 10 == 0; });
  }
}

} // namespace gelx::scenes
