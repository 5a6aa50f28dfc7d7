// gelx scene: buckling, by damped quasi-static dynamics (gelx::DampedDynamics)
//
// Sample runs:
//   build/demos/buckling/gelx-buckling-dynamics --output /tmp/column
//   build/demos/buckling/gelx-buckling-dynamics --output /tmp/fast -dynamics_loading_time 1e3
//       -dynamics_hold_time 0               (20 times faster: flagged "not quasi-static")
//   mpirun -np 2 build/demos/buckling/gelx-buckling-dynamics --output /tmp/column
//       -dynamics_ts_monitor -dynamics_snes_converged_reason
//
// The column of the buckling scene (main.cpp), with mode 1 seeded as an imperfection, is
// loaded past its first critical load by the smooth-step ramp (a dead load clamped-free, a
// prescribed shortening clamped-clamped) and held, following c M u' + R(u; t) = 0 in time with
// PETSc TS. steps.csv has, per accepted step, the energies (strain, kinetic, dissipated), their
// ratios KE/SE and ED/SE (ABAQUS' ALLKE/ALLSE, ALLSD/ALLIE), the deflection and the axial
// force with the elastica's load at that deflection; summary.json says whether the run was
// quasi-static (both ratios within their bounds, -dynamics_dissipation_bound and
// -dynamics_kinetic_bound). The verification is tests/damped_dynamics.cpp.

#include "euler_column.h"

#include <gelx/dynamics.h>
#include <gelx/petsc_utils.h>
#include <gelx/program.h>

namespace
{
struct Loading
{
  double imperfection = 0.01; ///< amplitude of the seeded mode 1, over tx
  double load = 10;           ///< final load factor in Euler loads (traction or shortening)
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

    // 3. Time scales for the default column (tests/damped_dynamics.cpp explains them): a
    //    loading time of 37 periods of its first bending vibration at rho = 1, a damping
    //    that dissipates 0.2 % of the strain energy
    gelx::set_default_option("dynamics_", "loading_time", "2e4");
    gelx::set_default_option("dynamics_", "hold_time", "4e3");
    gelx::set_default_option("dynamics_", "damping", "1e-3");
    gelx::set_default_option("dynamics_", "ts_rtol", "1e-3");
    gelx::set_default_option("dynamics_", "ts_atol", "1e-3");
    gelx::DampedDynamics dynamics(
        run.comm(), column.problem(), *column.mass_form(),
        [&] { return column.strain_energy(); },
        [&](double a) { column.set_load_factor(a * loading.load); });

    // 4. The run: a row of steps.csv per accepted step, the fields at each
    gelx::FieldSet fields;
    fields.add("displacement", column.displacement());
    fields.add("cauchy_stress", column.stress());
    fields.add("energy_density", column.energy_density());
    double d = 0; // the last step's deflection / L
    gelx::ProgressLine progress(
        run.comm(), {.quantity = [&] { return gelx::quantity_text("deflection/L", d); }});
    const gelx::DynamicsSummary summary = dynamics.run(
        {[&](const gelx::DynamicsRecord& r)
         {
           d = column.lateral_deflection();
           const double P = column.axial_force();
           nlohmann::json row = r.to_json();
           row.update({{"deflection_over_L", d},
                       {"axial_force_over_critical", P / P_cr},
                       {"elastica_load_over_critical", column.elastica_load_ratio(d)}});
           results.append_step(row);
           results.write_fields(r.time, fields.update());
           run.summary["dynamics"] = dynamics.summary().to_json();
           progress.print(r.step, r.time, r.time / dynamics.end_time());
         }});
    run.summary["dynamics"] = summary.to_json();
    run.summary.update({{"deflection_over_L", column.lateral_deflection()},
                        {"axial_force_over_critical", column.axial_force() / P_cr}});
  });
}
