// gelx scene: buckling — Euler buckling and post-buckling of a slender 3-D column
//
// Sample runs:
//   ./gelx run buckling
//   ./gelx run buckling --ends clamped-clamped --nz 80
//   ./gelx run buckling --np 2 -branch_arclength_snes_monitor
//   ./gelx run buckling --ty 1.2 --base sliding --diagram true
//
// A column of compressible neo-Hookean solid (Eq. 3.1) is compressed along its axis, as the
// thesis' ABAQUS *BUCKLE / *IMPERFECTION / Riks analyses were. Up to five analyses:
//  1. linear buckling about the unloaded state (Eq. 1.13, SLEPc): critical loads against
//     Euler's pi^2 EI/(KL)^2, modes written to XDMF;
//  2. the perfect column followed by arc-length continuation along its straight path, the
//     tangent's eigenvalue nearest zero tracked at every point until it changes sign: the
//     bifurcation;
//  3. branch switching there: the continuation leaves along the critical mode and follows the
//     buckled branch, compared with the elastica;
//  4. with --diagram: the perfect column's bifurcation diagram by deflated continuation, the
//     stability of every point from the inertia of its tangent;
//  5. the imperfect column: mode 1 seeded into the geometry with a small amplitude, followed
//     from the unloaded state, approaching the same elastica.
// Load factors are in Euler loads; deflections are the largest lateral displacement over L.

#include "euler_column.h"

#include <gelx/solvers/arclength.h>
#include <gelx/solvers/deflation.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/systems/problem.h>
#include <gelx/io/program.h>
#include <algorithm>
#include <map>
#include <memory>

namespace
{
/// What the scene computes, and how far.
struct Analyses
{
  int modes = 4;             ///< linear buckling modes
  double imperfection = 0.01; ///< amplitude of the seeded mode 1, over tx
  double max_deflection = 0.3; ///< each path is followed up to this d/L
  int max_steps = 200;       ///< arc-length steps per path
  bool diagram = false;      ///< the bifurcation diagram by deflated continuation
  double diagram_max = 1.6;  ///< ... up to this load, in first critical loads
};

/// The loads of the bifurcation diagram, in Euler loads: steps of 0.05 P_cr1 from 0.95 P_cr1
/// to `last` P_cr1, none within 1 % of a critical load (a branch's continuation starts there
/// from a nearly singular tangent), and loads 1 % and 3 % above each critical load in that
/// range, where the new branches rise steeply (a bent column's deflection grows as the square
/// root of the load's excess), so that deflation finds them near the straight column.
std::vector<double> diagram_loads(const std::vector<double>& critical, double last)
{
  const double P1 = critical.front();
  std::vector<double> loads;
  for (int k = 0; 0.95 + 0.05 * k <= last + 1e-9; ++k)
  {
    const double load = (0.95 + 0.05 * k) * P1;
    if (std::none_of(critical.begin(), critical.end(),
                     [&](double P) { return std::abs(load / P - 1) < 0.01; }))
      loads.push_back(load);
  }
  for (double P : critical)
    for (double above : {1.01, 1.03})
      if (P * above < last * P1)
        loads.push_back(P * above);
  std::sort(loads.begin(), loads.end());
  return loads;
}
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters
  gelx::scenes::ColumnParameters p;
  Analyses a;
  gelx::Parameters prm;
  p.bind(prm);
  prm.bind("analysis", "modes", a.modes, "buckling modes to compute",
           gelx::Parameters::at_least_one);
  prm.bind("analysis", "imperfection", a.imperfection, "amplitude of the seeded mode 1, over tx",
           gelx::Parameters::positive);
  prm.bind("analysis", "max_deflection", a.max_deflection,
           "follow each path up to this deflection d/L",
           [](double v) { return v > 0 && v <= 0.35 ? "" : "must be in (0, 0.35]"; });
  prm.bind("analysis", "max_steps", a.max_steps, "largest number of arc-length steps per path",
           gelx::Parameters::at_least_one);
  prm.bind("analysis", "diagram", a.diagram,
           "the bifurcation diagram of the perfect column by deflated continuation");
  prm.bind("analysis", "diagram_max", a.diagram_max,
           "the diagram's last load, in first critical loads",
           [](double v) { return v > 1 && v <= 3 ? "" : "must be in (1, 3]"; });

  return gelx::run_program(argc, argv, "gelx-buckling", prm, [&](gelx::Run& run)
  {
    p.check();

    // 2. The column and its linear buckling modes ("time" in fields.xdmf: the mode number)
    gelx::scenes::EulerColumn column(run.comm(), p);
    gelx::ResultsWriter& results = run.results(column.mesh().mesh);
    const double eigen_start = run.elapsed();
    const auto modes = column.buckling_modes(a.modes);
    std::vector<nlohmann::json> eigen_rows;
    std::vector<double> critical;
    for (std::size_t k = 0; k < modes.size(); ++k)
    {
      auto [odd, even] = column.mode_odd_even_parts(modes[k].shape);
      // critical_load: the eigenvalue times the measured perturbation force, in force units
      eigen_rows.push_back({{"mode", k + 1},
                            {"critical_load", modes[k].load_factor * column.euler_load()},
                            {"critical_load_over_euler", modes[k].load_factor},
                            {"odd_part", odd},
                            {"even_part", even}});
      critical.push_back(modes[k].load_factor);
      gelx::FieldSet shape;
      shape.add("mode", modes[k].shape);
      results.write_fields(double(k + 1), shape.update());
    }
    results.write_table("eigenvalues.csv", eigen_rows);
    const double P_cr = modes[0].load_factor;
    run.summary = {{"num_dofs",
                    column.displacement()->function_space()->dofmap()->index_map->size_global()
                        * 3},
                   {"slenderness", column.slenderness()},
                   {"euler_load", column.euler_load()},
                   {"critical_loads_over_euler", critical},
                   {"critical_load_over_euler", P_cr},
                   {"eigen_time", run.elapsed() - eigen_start},
                   {"imperfection_amplitude", a.imperfection * p.tx}};

    // The points of all three paths go to steps.csv, told apart by `path`; the buckled
    // branch's shapes to branch/fields.xdmf
    gelx::FieldSet branch_fields;
    branch_fields.add("displacement", column.displacement());
    branch_fields.add("cauchy_stress", column.stress());
    branch_fields.add("energy_density", column.energy_density());
    gelx::ResultsWriter branch_results(run.comm(), results.folder() / "branch", column.mesh().mesh);
    int path_steps = 0, corrector_iterations = 0;
    double path_time = 0;
    // A progress line per path: the buckled branch ends at max_deflection, the others on an
    // event (a bifurcation, the end of the diagram's range), with no estimate of the time left
    std::map<std::string, gelx::ProgressLine> progress;
    double deflection_shown = 0;
    // Records one path point; returns its (deflection / L, axial force / Euler load)
    auto record = [&](const std::string& path, const gelx::StepRecord& pt)
    {
      path_time += pt.wall_time;
      ++path_steps;
      corrector_iterations += pt.newton.iterations;
      const double deflection = column.lateral_deflection();
      const double axial_force = column.axial_force(), force = axial_force / column.euler_load();
      nlohmann::json row = {{"path", path},
                            {"step", pt.step},
                            {"load_factor", pt.load},
                            {"axial_force", axial_force},
                            {"axial_force_over_euler", force},
                            {"deflection_over_L", deflection},
                            {"elastica_load_over_euler",
                             P_cr * column.elastica_load_ratio(deflection)},
                            {"newton_iterations", pt.newton.iterations},
                            {"cutbacks", pt.cutbacks}};
      row.update(gelx::stability_columns(pt));
      results.append_step(row);
      run.summary.update({{"arclength_steps", path_steps},
                          {"corrector_iterations_per_step",
                           double(corrector_iterations) / path_steps},
                          {"time_per_arclength_step", path_time / path_steps}});
      deflection_shown = deflection;
      progress
          .try_emplace(path, run.comm(),
                       gelx::ProgressLine::Options{
                           .load_name = "P/P_E",
                           .quantity = [&, path] {
                             return path + ": " + gelx::quantity_text("deflection/L", deflection_shown);
                           }})
          .first->second.print(pt, pt.load,
                               path == "branch" ? deflection / a.max_deflection : NAN);
      return std::pair{deflection, force};
    };
    // A path of the column with its own options prefix and the scene's defaults for it
    auto continuation = [&](const std::string& prefix,
                            const std::map<std::string, std::string>& defaults)
    {
      for (const auto& [name, value] : defaults)
        gelx::set_default_option(prefix, name, value);
      return std::make_unique<gelx::ArcLength>(run.comm(), column.problem(),
                                               [&](double l) { column.set_load_factor(l); },
                                               prefix);
    };
    // After the bifurcation, steps in the displacement alone (psi = 0; its 2-norm reaches
    // ~1e2 on the default mesh)
    const std::map<std::string, std::string> buckled = {{"ds", "1"}, {"ds_max", "40"}};

    // 3. The perfect column along its straight path. Steps of at most 0.1 Euler loads, with the
    //    load weighed into the step (psi = 1) since the straight column barely moves; the
    //    tangent's eigenvalue nearest zero is computed at every point.
    auto straight = continuation("straight_arclength_", {{"psi", "1"}, {"ds", "0.1"},
                                                         {"ds_max", "0.1"}, {"stability", "eigenvalue"}});
    double lambda_stable = 0, lambda_unstable = NAN;
    gelx::PathState straight_path;
    straight->run(straight_path, a.max_steps,
                  {[&](const gelx::StepRecord& pt, gelx::PathState&)
                   {
                     record("straight", pt);
                     (pt.bifurcation ? lambda_unstable : lambda_stable) = pt.load;
                     run.summary["bifurcation_bracket"] = {lambda_stable, lambda_unstable};
                   }},
                  [](const gelx::StepRecord& pt) { return pt.bifurcation || pt.limit_point; });
    if (std::isnan(lambda_unstable))
      throw gelx::ConvergenceError("no bifurcation found on the straight path up to "
                                   + std::to_string(lambda_stable) + " Euler loads");

    // 4. Branch switching: leave along the critical mode and follow the buckled branch
    auto branch = continuation("branch_arclength_", buckled);
    gelx::PathState branch_path;
    branch_path.load = lambda_unstable;
    run.summary["stability_at_switch"] = branch->switch_branch(branch_path);
    double branch_deflection = 0;
    branch->run(branch_path, a.max_steps,
                {[&](const gelx::StepRecord& pt, gelx::PathState&)
                 {
                   const auto [deflection, load] = record("branch", pt);
                   branch_deflection = deflection;
                   branch_results.write_fields(pt.step, branch_fields.update());
                   run.summary.update(
                       {{"branch_deflection_over_L", deflection},
                        {"branch_load_over_critical", load / P_cr},
                        {"elastica_at_branch_end", column.elastica_load_ratio(deflection)}});
                 }},
                [&](const gelx::StepRecord&) { return branch_deflection >= a.max_deflection; });

    // 5. The bifurcation diagram of the perfect column by deflated continuation: every branch
    //    continued from load to load with the others deflated, new branches sought where one
    //    changes stability, from its previous solution perturbed either way in x and in y
    //    (Newton keeps a straight column straight); each point's stability is the number of
    //    negative eigenvalues of its tangent
    if (a.diagram)
    {
      const double diagram_start = run.elapsed();
      column.displacement()->x()->set(0.0);
      column.set_load_factor(critical.front() * 0.95);
      gelx::NewtonSolver straight(run.comm(), "diagram_start_newton_");
      if (!straight.solve(column.problem()).converged)
        throw gelx::ConvergenceError("the straight column at 0.95 P_cr did not converge");
      gelx::OwnedVec start(column.problem().create_vector());
      GELX_PETSC(VecCopy(column.problem().unknowns(), start.get()));
      const std::array<gelx::OwnedVec, 2> perturbations
          = {column.lateral_perturbation(0, 0.1 * p.tx), column.lateral_perturbation(1, 0.1 * p.tx)};
      gelx::set_default_option("diagram_", "search", "at_bifurcations");
      gelx::DeflationSolver deflation(run.comm(), column.problem(), "diagram_");
      std::vector<nlohmann::json> diagram;
      const auto branches = gelx::deflated_continuation(
          deflation, diagram_loads(critical, a.diagram_max),
          [&](double l) { column.set_load_factor(l); }, start.get(),
          [&](Vec x)
          {
            std::vector<gelx::OwnedVec> guesses;
            for (const auto& perturbation : perturbations)
              for (double sign : {1.0, -1.0})
              {
                guesses.emplace_back(column.problem().create_vector());
                GELX_PETSC(VecWAXPY(guesses.back().get(), sign, perturbation.get(), x));
              }
            return guesses;
          },
          [&](const gelx::Branch& branch, const gelx::Equilibrium& point)
          {
            column.problem().set_state(point.state.get());
            const auto tip = column.tip_deflection();
            diagram.push_back({{"load_over_critical", branch.loads.back() / P_cr},
                               {"branch", branch.id},
                               {"tip_x_over_L", tip[0]},
                               {"tip_y_over_L", tip[1]},
                               {"potential_energy", column.potential_energy()},
                               {"negative_eigenvalues", point.negative_eigenvalues},
                               {"newton_iterations", point.newton.iterations}});
            results.write_table("diagram.csv", diagram);
          });
      run.summary.update({{"diagram_branches", branches.size()},
                          {"diagram_points", diagram.size()},
                          {"diagram_time", run.elapsed() - diagram_start}});
    }

    // 6. The imperfect column: mode 1 seeded into the geometry, from the unloaded state
    gelx::seed_imperfection(*column.mesh().mesh, {modes.at(0)}, {a.imperfection * p.tx});
    column.displacement()->x()->set(0.0);
    column.set_load_factor(0.0);
    auto imperfect = continuation("imperfect_arclength_", buckled);
    double imperfect_deflection = 0;
    gelx::PathState imperfect_path;
    imperfect->run(
        imperfect_path, a.max_steps,
        {[&](const gelx::StepRecord& pt, gelx::PathState&)
         {
           const auto [deflection, load] = record("imperfect", pt);
           imperfect_deflection = deflection;
           run.summary.update({{"imperfect_deflection_over_L", deflection},
                               {"imperfect_load_over_critical", load / P_cr},
                               {"elastica_at_imperfect_end", column.elastica_load_ratio(deflection)}});
         }},
        [&](const gelx::StepRecord&) { return imperfect_deflection >= a.max_deflection; });
  });
}
