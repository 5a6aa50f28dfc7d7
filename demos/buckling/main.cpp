// gelx scene: buckling — Euler buckling and post-buckling of a slender 3-D column
//
// Sample runs:
//   ./gelx run buckling
//   ./gelx run buckling --ends clamped-clamped --nz 80
//   ./gelx run buckling --np 2 -branch_arclength_monitor 1
//
// A column of compressible neo-Hookean solid (Eq. 3.1) is compressed along its axis, as the
// thesis' ABAQUS *BUCKLE / *IMPERFECTION / Riks analyses were. Four analyses:
//  1. linear buckling about the unloaded state (Eq. 1.13, SLEPc): critical loads against
//     Euler's pi^2 EI/(KL)^2, modes written to XDMF;
//  2. the perfect column followed by arc-length continuation along its straight path, the
//     tangent's eigenvalue nearest zero tracked at every point until it changes sign: the
//     bifurcation;
//  3. branch switching there: the continuation leaves along the critical mode and follows the
//     buckled branch, compared with the elastica;
//  4. the imperfect column: mode 1 seeded into the geometry with a small amplitude, followed
//     from the unloaded state, approaching the same elastica.
// Load factors are in Euler loads; deflections are the largest lateral displacement over L.

#include "euler_column.h"

#include <chrono>
#include <map>
#include <tuple>
#include <utility>
#include <memory>
#include <gelx/arclength.h>
#include <gelx/load_stepping.h>
#include <gelx/output.h>
#include <gelx/petsc_utils.h>
#include <gelx/program.h>

int main(int argc, char* argv[])
{
  // 1. Scene parameters
  gelx::Parameters prm;
  const gelx::scenes::ColumnParameters d;
  prm.add("geometry", "tx", d.tx, "cross-section width (the buckling direction)",
          gelx::Parameters::positive);
  prm.add("geometry", "ty", d.ty, "cross-section depth (> tx)", gelx::Parameters::positive);
  prm.add("geometry", "L", d.L, "length", gelx::Parameters::positive);
  prm.add("geometry", "nx", int(d.cells[0]), "box cells across tx", gelx::Parameters::at_least_one);
  prm.add("geometry", "ny", int(d.cells[1]), "box cells across ty", gelx::Parameters::at_least_one);
  prm.add("geometry", "nz", int(d.cells[2]), "box cells along L", gelx::Parameters::at_least_one);
  prm.add("geometry", "ends", "clamped-free", "clamped-free or clamped-clamped",
          [](const std::string& v)
          { return v == "clamped-free" || v == "clamped-clamped" ? "" : "must be clamped-free or clamped-clamped"; });
  prm.add("material", "G", d.G, "shear modulus", gelx::Parameters::positive);
  prm.add("material", "nu", d.nu, "Poisson's ratio",
          [](double v) { return v > -1 && v < 0.5 ? "" : "must be in (-1, 0.5)"; });
  prm.add("analysis", "modes", 4, "buckling modes to compute", gelx::Parameters::at_least_one);
  prm.add("analysis", "imperfection", 0.01, "amplitude of the seeded mode 1, over tx",
          gelx::Parameters::positive);
  prm.add("analysis", "max_deflection", 0.3, "follow each path up to this deflection d/L",
          [](double v) { return v > 0 && v <= 0.35 ? "" : "must be in (0, 0.35]"; });
  prm.add("analysis", "max_steps", 200, "largest number of arc-length steps per path",
          gelx::Parameters::at_least_one);

  return gelx::run_program(argc, argv, "gelx-buckling", prm, [&](MPI_Comm comm)
  {
    using clock = std::chrono::steady_clock;
    auto seconds = [](clock::time_point t0)
    { return std::chrono::duration<double>(clock::now() - t0).count(); };
    gelx::scenes::ColumnParameters p;
    p.tx = prm.real("tx");
    p.ty = prm.real("ty");
    p.L = prm.real("L");
    p.cells = {std::size_t(prm.integer("nx")), std::size_t(prm.integer("ny")),
               std::size_t(prm.integer("nz"))};
    p.G = prm.real("G");
    p.nu = prm.real("nu");
    p.clamped_clamped = prm.text("ends") == "clamped-clamped";
    if (p.ty <= p.tx)
      throw gelx::InputError("the depth ty must exceed the width tx, so that the column "
                             "buckles in x");
    const double max_deflection = prm.real("max_deflection");
    const int max_steps = prm.integer("max_steps");

    // 2. The column and its linear buckling modes
    gelx::scenes::EulerColumn column(comm, p);
    gelx::ResultsWriter writer(comm, prm.text("output"), column.mesh().mesh);
    auto t0 = clock::now();
    const auto modes = column.buckling_modes(prm.integer("modes"));
    const double eigen_time = seconds(t0);
    std::vector<nlohmann::json> eigen_rows;
    for (std::size_t k = 0; k < modes.size(); ++k)
    {
      auto [odd, even] = column.mode_odd_even_parts(modes[k].shape);
      // critical_load: the eigenvalue times the measured perturbation force, in force units
      eigen_rows.push_back({{"mode", k + 1},
                            {"critical_load", modes[k].load_factor * column.euler_load()},
                            {"critical_load_over_euler", modes[k].load_factor},
                            {"odd_part", odd},
                            {"even_part", even}});
      gelx::NodalField shape("mode", modes[k].shape);
      shape.update();
      writer.write_fields(double(k + 1), {shape.function()}); // "time" = mode number
    }
    writer.write_table("eigenvalues.csv", eigen_rows);

    // The path points of all three analyses go to steps.csv, told apart by `path`
    gelx::NodalField displacement("displacement", column.displacement());
    gelx::ResultsWriter branch_writer(comm, writer.folder() / "branch", column.mesh().mesh);
    double path_time = 0;
    int path_steps = 0, corrector_iterations = 0;
    auto step_start = clock::now();
    // Writes one path point; returns its (deflection / L, axial force / Euler load)
    auto record = [&](const std::string& path, const gelx::PathPoint& pt)
    {
      path_time += seconds(step_start);
      ++path_steps;
      corrector_iterations += pt.iterations;
      const double deflection = column.lateral_deflection();
      const double axial_force = column.axial_force(), force = axial_force / column.euler_load();
      writer.append_step({{"path", path},
                          {"step", pt.step},
                          {"load_factor", pt.load_factor},
                          {"axial_force", axial_force},
                          {"axial_force_over_euler", force},
                          {"deflection_over_L", deflection},
                          {"elastica_load_over_euler",
                           modes[0].load_factor * column.elastica_load_ratio(deflection)},
                          {"iterations", pt.iterations},
                          {"cutbacks", pt.cutbacks},
                          {"stability", std::isnan(pt.stability) ? nlohmann::json(nullptr)
                                                                 : nlohmann::json(pt.stability)}});
      step_start = clock::now();
      return std::pair{deflection, force};
    };
    auto set_load = [&](double lambda) { column.set_load_factor(lambda); };
    // A continuation with its own options prefix and the scene's defaults for it
    auto continuation = [&](const std::string& prefix,
                            const std::map<std::string, std::string>& defaults)
    {
      for (const auto& [name, value] : defaults)
        gelx::set_default_option(prefix, name, value);
      gelx::set_default_option(prefix, "monitor", "0");
      return std::make_unique<gelx::ArcLength>(comm, column.problem(), set_load, prefix);
    };
    // After the bifurcation: a cylindrical constraint on the displacement (its 2-norm reaches
    // ~1e2 on the default mesh)
    const std::map<std::string, std::string> buckled = {{"ds", "1"}, {"ds_max", "40"}};

    // What the paths reached, for the summary; a path that fails keeps them as they were and its
    // completed points in steps.csv
    double lambda_stable = 0, lambda_unstable = NAN, stability_at_switch = NAN;
    double branch_deflection = 0, branch_load = NAN, imperfect_deflection = 0, imperfect_load = NAN;
    const double amplitude = prm.real("imperfection") * p.tx;
    std::vector<double> critical;
    for (const auto& m : modes)
      critical.push_back(m.load_factor);
    const double P_cr = modes[0].load_factor;
    auto summary = [&](const std::string& status)
    {
      writer.write_summary(
          "buckling", status, prm,
          {{"num_dofs",
            column.displacement()->function_space()->dofmap()->index_map->size_global() * 3},
           {"slenderness", column.slenderness()},
           {"euler_load", column.euler_load()},
           {"critical_loads_over_euler", critical},
           {"critical_load_over_euler", P_cr},
           {"bifurcation_bracket", {lambda_stable, lambda_unstable}},
           {"stability_at_switch", stability_at_switch},
           {"branch_deflection_over_L", branch_deflection},
           {"branch_load_over_critical", branch_load / P_cr},
           {"elastica_at_branch_end", column.elastica_load_ratio(branch_deflection)},
           {"imperfection_amplitude", amplitude},
           {"imperfect_deflection_over_L", imperfect_deflection},
           {"imperfect_load_over_critical", imperfect_load / P_cr},
           {"elastica_at_imperfect_end", column.elastica_load_ratio(imperfect_deflection)},
           {"eigen_time", eigen_time},
           {"arclength_steps", path_steps},
           {"corrector_iterations_per_step", double(corrector_iterations) / path_steps},
           {"time_per_arclength_step", path_time / path_steps}});
    };

    try
    {
      // 3. The perfect column along its straight path. Steps of at most 0.1 Euler loads, with
      //    the load weighed into the constraint (psi = 1) since the straight column barely
      //    moves; the tangent's eigenvalue nearest zero is computed at every point.
      auto straight = continuation("straight_arclength_", {{"psi", "1"}, {"ds", "0.1"},
                                                           {"ds_max", "0.1"}, {"stability", "1"}});
      step_start = clock::now();
      straight->run(0.0, max_steps,
                    [&](const gelx::PathPoint& pt)
                    {
                      record("straight", pt);
                      (pt.bifurcation ? lambda_unstable : lambda_stable) = pt.load_factor;
                    },
                    [](const gelx::PathPoint& pt) { return pt.bifurcation || pt.limit_point; });
      if (std::isnan(lambda_unstable))
        throw gelx::ConvergenceError("no bifurcation found on the straight path up to "
                                     + std::to_string(lambda_stable) + " Euler loads");

      // 4. Branch switching: leave along the critical mode and follow the buckled branch
      auto branch = continuation("branch_arclength_", buckled);
      stability_at_switch = branch->switch_branch();
      step_start = clock::now();
      branch->run(lambda_unstable, max_steps,
                  [&](const gelx::PathPoint& pt)
                  {
                    std::tie(branch_deflection, branch_load) = record("branch", pt);
                    displacement.update();
                    branch_writer.write_fields(pt.step, {displacement.function()});
                  },
                  [&](const gelx::PathPoint&) { return branch_deflection >= max_deflection; });

      // 5. The imperfect column: mode 1 seeded into the geometry, from the unloaded state
      gelx::seed_imperfection(*column.mesh().mesh, {modes.at(0)}, {amplitude});
      column.displacement()->x()->set(0.0);
      column.set_load_factor(0.0);
      auto imperfect = continuation("imperfect_arclength_", buckled);
      step_start = clock::now();
      imperfect->run(
          0.0, max_steps,
          [&](const gelx::PathPoint& pt)
          { std::tie(imperfect_deflection, imperfect_load) = record("imperfect", pt); },
          [&](const gelx::PathPoint&) { return imperfect_deflection >= max_deflection; });
    }
    catch (const gelx::ConvergenceError& e)
    {
      summary(std::string("failed: ") + e.what());
      throw;
    }

    // 6. Summary: critical loads against Euler, the paths' ends against the elastica
    summary("completed");
  });
}
