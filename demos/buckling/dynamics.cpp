// gelx scene: buckling in time, by damped quasi-static dynamics (gelx::DampedDynamics) or
// with inertia (gelx::InertialDynamics: implicit generalised-alpha or explicit central
// differences)
//
// Sample runs:
//   build/demos/buckling/gelx-buckling-dynamics --output /tmp/column
//   build/demos/buckling/gelx-buckling-dynamics --output /tmp/fast -dynamics_loading_time 1e3
//       -dynamics_hold_time 0               (20 times faster: flagged "not quasi-static")
//   build/demos/buckling/gelx-buckling-dynamics --method inertia --output /tmp/inertial
//       --checkpoint_every 10               (then --restart /tmp/inertial continues it)
//   mpirun -np 2 build/demos/buckling/gelx-buckling-dynamics --output /tmp/column
//       -dynamics_ts_monitor -dynamics_snes_converged_reason
//
// The column of the buckling scene (main.cpp), with mode 1 seeded as an imperfection, is
// loaded past its first critical load by the smooth-step ramp (a dead load clamped-free, a
// prescribed shortening clamped-clamped) and held, following in time with PETSc TS either
// the first-order viscous flow c M u' + R(u; t) = 0 (--method dynamics, options -dynamics_)
// or the equation of motion M u'' + C u' + R(u; t) = 0 with a light Rayleigh damping
// (--method inertia, options -inertial_; --method explicit, options -explicit_, with mass
// scaling). steps.csv has, per accepted step, the energies
// (strain, kinetic, dissipated; with inertia the supports' work and the balance residual),
// their ratios KE/SE and ED/SE (ABAQUS' ALLKE/ALLSE, ALLSD/ALLIE), the deflection and the axial
// force with the elastica's load at that deflection; summary.json says whether the run was
// quasi-static (the ratios within their bounds, -PREFIX_dissipation_bound and
// -PREFIX_kinetic_bound). The run checkpoints every --checkpoint_every steps and continues
// exactly with --restart. The verifications are tests/damped_dynamics.cpp,
// tests/inertial_dynamics.cpp and tests/explicit_dynamics.cpp.

#include "euler_column.h"

#include <gelx/solvers/dynamics.h>
#include <gelx/solvers/central_difference.h>
#include <gelx/solvers/inertia.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/io/program.h>

namespace
{
struct Loading
{
  double imperfection = 0.01; ///< amplitude of the seeded mode 1, over tx
  double load = 10;           ///< final load factor in Euler loads (traction or shortening)
  /// "dynamics" (first-order flow), "inertia" (equation of motion, TSALPHA2) or "explicit"
  /// (the same equation by central differences)
  std::string method = "dynamics";
  /// Time between field outputs; 0: every accepted step (explicit: every loading time / 200,
  /// as its steps are many and short)
  double output_every = 0;
};
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters
  // Clamped-clamped by default: under a prescribed shortening the buckled column settles
  // fast and the default load, 10 Euler loads of shortening, reaches d/L = 0.11 (a dead load
  // clamped-free needs --load near 1: 1.03 Euler loads already bend it to d/L = 0.3)
  gelx::scenes::ColumnParameters p;
  p.ends = "clamped-clamped";
  Loading loading;
  gelx::Parameters prm;
  p.bind(prm);
  prm.bind("material", "rho", p.rho, "mass density", gelx::Parameters::positive);
  prm.bind("analysis", "imperfection", loading.imperfection,
           "amplitude of the seeded mode 1, over tx", gelx::Parameters::positive);
  prm.bind("analysis", "load", loading.load,
           "final load factor in Euler loads (a dead load clamped-free, a shortening "
           "clamped-clamped)",
           gelx::Parameters::positive);
  prm.bind("analysis", "method", loading.method,
           "path: dynamics (first-order viscous flow), inertia (equation of motion, implicit) "
           "or explicit (equation of motion, central differences)",
           gelx::Parameters::one_of({"dynamics", "inertia", "explicit"}));
  prm.bind("analysis", "output_every", loading.output_every,
           "time between field outputs (0: every step; explicit: loading time / 200)",
           gelx::Parameters::non_negative);

  return gelx::run_program(argc, argv, "gelx-buckling-dynamics", prm, [&](gelx::Run& run)
  {
    p.check();

    // 2. The imperfect column: the linear buckling load and mode 1 seeded into the geometry
    gelx::scenes::EulerColumn column(run.comm(), p);
    gelx::ResultsWriter& results = run.results(column.mesh().mesh);
    const auto modes = column.buckling_modes(1);
    const double P_cr = modes[0].load_factor * column.euler_load();
    gelx::seed_imperfection(*column.mesh().mesh, modes, {loading.imperfection * p.tx});
    run.summary = {{"euler_load", column.euler_load()},
                   {"critical_load", P_cr},
                   {"imperfection_amplitude", loading.imperfection * p.tx}};


    // 3. Time scales for the default column at rho = 1 (tests/damped_dynamics.cpp explains
    //    them): its first bending period is 540, the loading time 37 of them. The flow's
    //    damping dissipates 0.2 % of the strain energy; with inertia a Rayleigh mass damping
    //    a = 1.2e-3 damps the first bending mode at 5 % of critical (a / (2 omega_1)), so
    //    that the column settles in the hold of 7 periods, and rho_inf = 0.8 removes what
    //    the steps do not resolve (the axial modes). Explicit: the same damping; its stable
    //    step (0.047 unscaled, measured) would take 6e5 steps, so the lumped masses are
    //    scaled to a step of 1 (ABAQUS' fixed mass scaling; the added mass is in the
    //    summary; its effect on the answer: README)
    const bool inertia = loading.method != "dynamics";
    const std::string prefix = loading.method == "dynamics" ? "dynamics_"
                               : loading.method == "inertia" ? "inertial_"
                                                             : "explicit_";
    gelx::set_default_options(prefix, {{"loading_time", "2e4"},
                                       {"hold_time", "4e3"},
                                       {"ts_rtol", "1e-3"},
                                       {"ts_atol", "1e-3"}});
    if (loading.method == "inertia")
      gelx::set_default_options(prefix, {{"rayleigh_mass", "1.2e-3"}, {"ts_alpha_radius", "0.8"}});
    else if (loading.method == "explicit")
      gelx::set_default_options(prefix, {{"ts_type", gelx::TSCENTRALDIFFERENCE},
                                         {"rayleigh_mass", "1.2e-3"},
                                         {"mass_scaling_step", "1"}});
    else
      gelx::set_default_option(prefix, "damping", "1e-3");
    auto strain_energy = [&] { return column.strain_energy(); };
    auto apply_load = [&](double a) { column.set_load_factor(a * loading.load); };

    // 4. The run: a row of steps.csv per accepted step, the fields at each
    gelx::FieldSet fields;
    fields.add("displacement", column.displacement());
    fields.add("cauchy_stress", column.stress());
    fields.add("energy_density", column.energy_density());
    double d = 0; // the last step's deflection / L
    const double output_every
        = loading.output_every > 0 || loading.method != "explicit"
              ? loading.output_every
              : gelx::real_option(prefix, "loading_time", 0) / 200;
    double next_output = 0;
    gelx::ProgressLine progress(
        run.comm(), {.quantity = [&] { return gelx::quantity_text("deflection/L", d); }});
    auto record = [&](const gelx::DynamicsRecord& r, const gelx::DynamicsSummary& so_far,
                      double end_time)
    {
      d = column.lateral_deflection();
      const double P = column.axial_force();
      nlohmann::json row = r.to_json();
      row.update({{"deflection_over_L", d},
                  {"axial_force_over_critical", P / P_cr},
                  {"elastica_load_over_critical", column.elastica_load_ratio(d)}});
      results.append_step(row);
      if (r.time >= next_output * (1 - 1e-12) || r.time >= end_time * (1 - 1e-12))
      {
        results.write_fields(r.time, fields.update());
        next_output = r.time + output_every;
      }
      run.summary["dynamics"] = so_far.to_json();
      progress.print(r.step, r.time, r.time / end_time);
    };
    gelx::DynamicsSummary summary;
    // The checkpoint after a step holds the integrator's state (with inertia velocity,
    // acceleration and the previous step; the flow's TSBDF history), so that --restart
    // continues the run as if never stopped
    const gelx::PathState start = run.start_path(column.problem());
    const gelx::StepObserver checkpoints = run.checkpoints();
    auto follow = [&](auto& dynamics)
    {
      return dynamics.run(
          {[&](const gelx::DynamicsRecord& r)
           {
             record(r, dynamics.summary(), dynamics.end_time());
             gelx::PathState state;
             dynamics.save(state);
             checkpoints(r.step, state);
           }},
          start.step > 0 ? &start : nullptr);
    };
    if (inertia)
    {
      gelx::InertialDynamics dynamics(run.comm(), column.problem(), *column.mass_form(),
                                      strain_energy, apply_load, prefix);
      summary = follow(dynamics);
    }
    else
    {
      gelx::DampedDynamics dynamics(run.comm(), column.problem(), *column.mass_form(),
                                    strain_energy, apply_load, prefix);
      summary = follow(dynamics);
    }
    run.summary["dynamics"] = summary.to_json();
    run.summary.update({{"deflection_over_L", column.lateral_deflection()},
                        {"axial_force_over_critical", column.axial_force() / P_cr}});
  });
}
