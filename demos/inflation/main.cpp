// gelx scene: inflation — a neo-Hookean spherical shell inflated through its pressure maximum
//
// Sample runs:
//   ./gelx run inflation
//   ./gelx run inflation --B 1.1 --h 0.08 -arclength_ds_max 10
//   ./gelx run inflation --np 2
//
// A thick shell (inner radius A, outer B) of the compressible neo-Hookean solid of Eq. 3.1 with
// K/G = 1000 is inflated by a follower pressure p = lambda G on its cavity. The pressure has a
// maximum: past it, load stepping cannot follow the path. Arc-length continuation
// (gelx::ArcLength) passes the limit point and traces the falling branch. The path is compared
// with the incompressible closed form p(la) (shell.h); the run also measures the cost of a
// continuation step against one Newton iteration of plain load stepping on the same problem.
// `--symmetry constraints` holds the three symmetry planes by multipoint constraints (a reduced
// space) instead of Dirichlet rollers: the same path, through composed solver layers.

#include "shell.h"

#include <gelx/solvers/arclength.h>
#include <gelx/solvers/load_stepping.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/systems/problem.h>
#include <gelx/io/program.h>

#include <cstdio>
#include <dolfinx/common/MPI.h>

namespace
{
/// How far the path is followed.
struct Continuation
{
  double descend_to = 0.8; ///< stop when the pressure has fallen to this fraction of its maximum
  /// stop when the shell has left the spherical shape by this much (InflatedShell::asphericity)
  double asphericity_max = 0.05;
  int max_steps = 200;     ///< largest number of arc-length steps
};

/// The inflation path so far, kept in the path's state (a restarted run continues it).
struct Curve
{
  std::vector<double> stretch, pressure;
  bool passed_maximum = false;
  int corrector_iterations = 0;
  double time = 0;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Curve, stretch, pressure, passed_maximum, corrector_iterations,
                                   time)
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters
  gelx::scenes::ShellParameters p;
  std::string mesh = "sphere_shell.geo"; // meshes/sphere_shell.geo
  Continuation c;
  gelx::Parameters prm;
  prm.bind("geometry", "A", p.A, "inner radius", gelx::Parameters::positive);
  prm.bind("geometry", "B", p.B, "outer radius (> A)", gelx::Parameters::positive);
  prm.bind("geometry", "h", p.h, "mesh size", gelx::Parameters::positive);
  prm.bind("geometry", "mesh", mesh, "gmsh geometry file (a path, or a file of meshes/)");
  prm.bind("geometry", "symmetry", p.symmetry,
           "rollers (Dirichlet) or constraints (multipoint) on the three symmetry planes",
           [](const std::string& v)
           { return v == "rollers" || v == "constraints" ? "" : "must be rollers or constraints"; });
  prm.bind("geometry", "domain", p.domain,
           "octant (three symmetry planes) or quarter (x, y >= 0: modes odd in z are free)",
           [](const std::string& v)
           { return v == "octant" || v == "quarter" ? "" : "must be octant or quarter"; });
  prm.bind("material", "G", p.G, "shear modulus", gelx::Parameters::positive);
  prm.bind("material", "K", p.K, "bulk modulus", gelx::Parameters::positive);
  prm.bind("material", "C01_over_C10", p.C01_over_C10,
           "Mooney-Rivlin C01/C10 (0: neo-Hookean); G = 2 (C10 + C01)",
           [](double v) { return v >= 0 ? "" : "must be non-negative"; });
  prm.bind("continuation", "descend_to", c.descend_to,
           "stop when the pressure has fallen to this fraction of its maximum",
           [](double v) { return v > 0 && v < 1 ? "" : "must be in (0, 1)"; });
  prm.bind("continuation", "asphericity_max", c.asphericity_max,
           "stop when (largest - smallest) / mean inner radius exceeds this (the shell has "
           "left the spherical shape)",
           gelx::Parameters::positive);
  prm.bind("continuation", "max_steps", c.max_steps, "largest number of arc-length steps",
           gelx::Parameters::at_least_one);

  return gelx::run_program(argc, argv, "gelx-inflation", prm, [&](gelx::Run& run)
  {
    if (p.B <= p.A)
      throw gelx::InputError("the outer radius B must exceed the inner radius A");

    // 2. The shell octant: mesh, forms, symmetry conditions
    gelx::scenes::InflatedShell shell(run.comm(), mesh, p);
    // The continuation, set up before any output (a bad solver option stops the run before its
    // folder exists). The arc length is measured in the 2-norm of the dof vector (~1.5e4
    // entries at h = 0.125): steps from 0.5 to 6 resolve the path with 2-5 corrector
    // iterations each (override with -arclength_ds ...)
    gelx::set_default_option("arclength_", "ds", "0.5");
    gelx::set_default_option("arclength_", "ds_max", "6");
    // Every point's stability from the inertia of the tangent the next predictor factorises
    // anyway: past the maximum one eigenvalue is negative (the limit point's); a thin sphere
    // then loses sphericity where another crosses zero, a bifurcation the path stops at
    gelx::set_default_option("arclength_", "stability", "inertia");
    gelx::ArcLength continuation(run.comm(), shell.system(),
                                 [&](double l) { shell.set_load_factor(l); });
    gelx::ResultsWriter& results = run.results(shell.mesh().mesh);
    PetscInt num_unknowns; // the dofs, less the constrained ones with --symmetry constraints
    GELX_PETSC(VecGetSize(shell.system().unknowns(), &num_unknowns));
    run.summary = {{"num_dofs",
                    shell.displacement()->function_space()->dofmap()->index_map->size_global()
                        * 3},
                   {"num_unknowns", num_unknowns}};

    // 3. Reference cost: one Newton solve of plain load stepping to a tenth of the closed-form
    //    maximum pressure, from the unloaded state
    const auto [la_ref, p_ref] = gelx::scenes::InflatedShell::closed_form_maximum(p);
    {
      gelx::NewtonSolver newton(run.comm());
      gelx::LoadSteppingOptions one_step;
      one_step.dt = one_step.dt_max = 1.0;
      gelx::LoadStepper(shell.system(), newton, one_step,
                        [&](double t) { shell.set_load_factor(0.1 * t * p_ref / p.G); })
          .run([&](const gelx::StepRecord& s, gelx::PathState&)
               { run.summary["time_per_newton_iteration"] = s.wall_time / s.newton.iterations; });
      VecSet(shell.system().unknowns(), 0.0); // back to the unloaded state
      shell.system().unknowns_changed();
      shell.set_load_factor(0.0);
    }

    // 4. Follow the path past the maximum, writing every point
    gelx::FieldSet fields;
    fields.add("displacement", shell.displacement());
    fields.add("cauchy_stress", shell.stress());
    fields.add("energy_density", shell.energy_density());
    double departure = 0; // the last point's asphericity (the observer's, for the stop test)
    gelx::PathState path = run.start_path(shell.system());
    continuation.run(
        path, c.max_steps,
        {[&](const gelx::StepRecord& pt, gelx::PathState& state)
         {
           auto curve = state.scene.value("curve", Curve{});
           const double la = shell.inner_stretch();
           departure = shell.asphericity();
           curve.stretch.push_back(la);
           curve.pressure.push_back(pt.load);
           curve.passed_maximum = curve.passed_maximum || pt.limit_point;
           curve.corrector_iterations += pt.newton.iterations;
           curve.time += pt.wall_time;
           state.scene["curve"] = curve;
           results.write_fields(pt.step, fields.update());
           nlohmann::json row
               = {{"step", pt.step},
                  {"arc_length", pt.arc_length},
                  {"pressure_over_G", pt.load},
                  {"inner_stretch", la},
                  {"closed_form_pressure_over_G",
                   gelx::scenes::InflatedShell::closed_form_pressure(p, la) / p.G},
                  {"newton_iterations", pt.newton.iterations},
                  {"cutbacks", pt.cutbacks},
                  {"limit_point", pt.limit_point},
                  {"asphericity", departure},
                  {"wall_time", pt.wall_time}};
           row.update(gelx::stability_columns(pt));
           results.append_step(row);
           if (pt.bifurcation)
             run.summary["bifurcation"] = {{"step", pt.step},
                                           {"pressure_over_G", pt.load},
                                           {"inner_stretch", la},
                                           {"negative_eigenvalues", pt.negative_eigenvalues}};
           run.summary.update(
               {{"steps", pt.step},
                {"final_pressure_over_G", pt.load},
                {"final_stretch", la},
                {"corrector_iterations_per_step", double(curve.corrector_iterations) / pt.step},
                {"time_per_step", curve.time / pt.step},
                {"time_per_corrector_iteration",
                 curve.time / std::max(curve.corrector_iterations, 1)}});
         },
         // The path ends on an event (descent past the maximum, a bifurcation), not at a
         // known load: no estimate of the time left
         gelx::ProgressLine(run.comm(),
                            {.load_name = "p/G",
                             .quantity = [&] {
                               return gelx::quantity_text("inner stretch",
                                                          run.summary["final_stretch"]);
                             },
                             .fraction = [](const gelx::StepRecord&) { return NAN; }}),
         run.checkpoints()},
        [&](const gelx::StepRecord& pt)
        {
          // At a bifurcation the spherical path goes on, but unstable in one more mode: the
          // shell the scene models (symmetric about its three planes) takes the other branch
          if (pt.bifurcation)
          {
            if (dolfinx::MPI::rank(run.comm()) == 0)
              std::printf("gelx-inflation: bifurcation between steps %d and %d (p/G = %.6g, "
                          "%d negative eigenvalues): the sphere loses sphericity; the "
                          "spherical path stops here\n",
                          pt.step - 1, pt.step, pt.load, pt.negative_eigenvalues);
            return true;
          }
          // The mesh is an imperfection: a bifurcation can turn into a smooth departure from
          // the sphere, with the second eigenvalue crossing at a load extremum (which the
          // inertia test counts as a limit point). The shape says it: the path stops once
          // the inner radius varies by asphericity_max over the surface
          if (departure > c.asphericity_max)
          {
            run.summary["lost_sphericity"] = {{"step", pt.step},
                                              {"pressure_over_G", pt.load},
                                              {"inner_stretch", shell.inner_stretch()},
                                              {"asphericity", departure},
                                              {"negative_eigenvalues",
                                               pt.negative_eigenvalues}};
            if (dolfinx::MPI::rank(run.comm()) == 0)
              std::printf("gelx-inflation: the shell left the spherical shape at step %d "
                          "(p/G = %.6g, inner radius varies by %.3g of its mean, %d negative "
                          "eigenvalues); the path stops here\n",
                          pt.step, pt.load, departure, pt.negative_eigenvalues);
            return true;
          }
          const auto curve = path.scene.value("curve", Curve{});
          const double peak = *std::max_element(curve.pressure.begin(), curve.pressure.end());
          return curve.passed_maximum && pt.load < c.descend_to * peak;
        });

    // 5. The limit point: vertex of the parabola through the three points around the maximum
    const auto curve = path.scene.value("curve", Curve{});
    const std::size_t k = std::max_element(curve.pressure.begin(), curve.pressure.end())
                          - curve.pressure.begin();
    if (!curve.passed_maximum || k == 0 || k + 1 == curve.pressure.size())
      throw gelx::ConvergenceError(
          run.summary.contains("bifurcation") || run.summary.contains("lost_sphericity")
              ? "the path stopped at a bifurcation before it passed the pressure maximum"
              : "the path did not pass the pressure maximum in " + std::to_string(path.step)
                    + " steps");
    const double la3[3] = {curve.stretch[k - 1], curve.stretch[k], curve.stretch[k + 1]};
    const double p3[3] = {curve.pressure[k - 1], curve.pressure[k], curve.pressure[k + 1]};
    const auto [la_max, lambda_max] = gelx::parabola_vertex(la3, p3);

    // 6. The limit point against the closed form
    run.summary.update({{"p_max_over_G", lambda_max},
                        {"stretch_at_p_max", la_max},
                        {"closed_form_p_max_over_G", p_ref / p.G},
                        {"closed_form_stretch_at_p_max", la_ref}});
  });
}
