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

#include "shell.h"

#include <chrono>
#include <gelx/arclength.h>
#include <gelx/load_stepping.h>
#include <gelx/output.h>
#include <gelx/petsc_utils.h>
#include <gelx/program.h>

int main(int argc, char* argv[])
{
  // 1. Scene parameters
  gelx::Parameters prm;
  const gelx::scenes::ShellParameters d;
  prm.add("geometry", "A", d.A, "inner radius", gelx::Parameters::positive);
  prm.add("geometry", "B", d.B, "outer radius (> A)", gelx::Parameters::positive);
  prm.add("geometry", "h", d.h, "mesh size", gelx::Parameters::positive);
  prm.add("geometry", "mesh", GELX_MESHES "/sphere_shell.geo", "gmsh geometry file");
  prm.add("material", "G", d.G, "shear modulus", gelx::Parameters::positive);
  prm.add("material", "K", d.K, "bulk modulus", gelx::Parameters::positive);
  prm.add("continuation", "descend_to", 0.8,
          "stop when the pressure has fallen to this fraction of its maximum",
          [](double v) { return v > 0 && v < 1 ? "" : "must be in (0, 1)"; });
  prm.add("continuation", "max_steps", 200, "largest number of arc-length steps",
          gelx::Parameters::at_least_one);

  return gelx::run_program(argc, argv, "gelx-inflation", prm, [&](MPI_Comm comm)
  {
    using clock = std::chrono::steady_clock;
    auto seconds = [](clock::time_point t0)
    { return std::chrono::duration<double>(clock::now() - t0).count(); };
    const gelx::scenes::ShellParameters p{prm.real("A"), prm.real("B"), prm.real("h"),
                                          prm.real("G"), prm.real("K")};
    if (p.B <= p.A)
      throw gelx::InputError("the outer radius B must exceed the inner radius A");

    // 2. The shell octant: mesh, forms, symmetry conditions
    gelx::scenes::InflatedShell shell(comm, prm.text("mesh"), p);

    // 3. Reference cost: one Newton solve of plain load stepping to a tenth of the closed-form
    //    maximum pressure, from the unloaded state
    const auto [la_ref, p_ref] = gelx::scenes::InflatedShell::closed_form_maximum(p);
    gelx::NewtonSolver newton(comm);
    gelx::LoadSteppingOptions one_step;
    one_step.dt = one_step.dt_max = 1.0;
    int newton_iterations = 0;
    auto t0 = clock::now();
    gelx::LoadStepper(shell.problem(), newton, one_step,
                      [&](double t) { shell.set_load_factor(0.1 * t * p_ref / p.G); })
        .run([&](const gelx::StepRecord& s) { newton_iterations = s.newton.iterations; });
    const double newton_iteration_time = seconds(t0) / newton_iterations;
    shell.displacement()->x()->set(0.0);
    shell.set_load_factor(0.0);

    // 4. Follow the path past the maximum, writing every point. The arc length is measured in
    //    the 2-norm of the dof vector (~1.5e4 entries at h = 0.125): steps from 0.5 to 6
    //    resolve the path with 2-5 corrector iterations each (override with -arclength_ds ...)
    gelx::set_default_option("arclength_", "ds", "0.5");
    gelx::set_default_option("arclength_", "ds_max", "6");
    gelx::ResultsWriter writer(comm, prm.text("output"), shell.mesh().mesh);
    gelx::NodalField displacement("displacement", shell.displacement());
    std::vector<double> s_path, lambda_path, stretch_path;
    double lambda_peak = 0, path_time = 0;
    int corrector_iterations = 0, steps = 0;
    bool passed_max = false;
    gelx::ArcLength continuation(comm, shell.problem(),
                                 [&](double l) { shell.set_load_factor(l); });
    auto step_start = clock::now();
    continuation.run(
        0.0, prm.integer("max_steps"),
        [&](const gelx::PathPoint& pt)
        {
          const double step_time = seconds(step_start);
          path_time += step_time;
          corrector_iterations += pt.iterations;
          steps = pt.step;
          const double la = shell.inner_stretch();
          s_path.push_back(pt.arc_length);
          lambda_path.push_back(pt.load_factor);
          stretch_path.push_back(la);
          passed_max = passed_max || pt.limit_point;
          displacement.update();
          writer.write_fields(pt.step, {displacement.function()});
          writer.append_step({{"step", pt.step},
                              {"arc_length", pt.arc_length},
                              {"pressure_over_G", pt.load_factor},
                              {"inner_stretch", la},
                              {"closed_form_pressure_over_G",
                               gelx::scenes::InflatedShell::closed_form_pressure(p, la) / p.G},
                              {"iterations", pt.iterations},
                              {"cutbacks", pt.cutbacks},
                              {"limit_point", pt.limit_point},
                              {"wall_time", step_time}});
          step_start = clock::now();
        },
        [&](const gelx::PathPoint& pt)
        {
          lambda_peak = std::max(lambda_peak, pt.load_factor);
          return passed_max && pt.load_factor < prm.real("descend_to") * lambda_peak;
        });

    // 5. The limit point: vertex of the parabola through the three points around the maximum
    const std::size_t k
        = std::max_element(lambda_path.begin(), lambda_path.end()) - lambda_path.begin();
    if (!passed_max || k == 0 || k + 1 == lambda_path.size())
      throw gelx::ConvergenceError("the path did not pass the pressure maximum in "
                                   + std::to_string(steps) + " steps");
    const double la3[3] = {stretch_path[k - 1], stretch_path[k], stretch_path[k + 1]};
    const double p3[3] = {lambda_path[k - 1], lambda_path[k], lambda_path[k + 1]};
    const auto [la_max, lambda_max] = gelx::parabola_vertex(la3, p3);

    // 6. Summary: the limit point against the closed form, and the cost figures
    writer.write_summary(
        "inflation", "completed", prm,
        {{"num_dofs", shell.displacement()->function_space()->dofmap()->index_map->size_global()
                          * 3},
         {"steps", steps},
         {"p_max_over_G", lambda_max},
         {"stretch_at_p_max", la_max},
         {"closed_form_p_max_over_G", p_ref / p.G},
         {"closed_form_stretch_at_p_max", la_ref},
         {"final_pressure_over_G", lambda_path.back()},
         {"final_stretch", stretch_path.back()},
         {"corrector_iterations_per_step", double(corrector_iterations) / steps},
         {"time_per_step", path_time / steps},
         {"time_per_corrector_iteration", path_time / std::max(corrector_iterations, 1)},
         {"time_per_newton_iteration", newton_iteration_time},
         {"wall_time", path_time}});
  });
}
