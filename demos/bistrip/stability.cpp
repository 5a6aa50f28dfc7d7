#include "stability.h"
#include "path_record.h"

#include <dolfinx/la/petsc.h>
#include <gelx/solvers/buckling.h>
#include <gelx/solvers/deflation.h>
#include <gelx/io/field_series.h>
#include <gelx/solvers/newton.h>
#include <gelx/common/petsc_utils.h>

namespace gelx::scenes
{

BondedBuckling bonded_buckling(MPI_Comm comm, Bistrip& strip, const BistripParameters& p,
                               const BistripAnalysis& a, const std::filesystem::path& output,
                               nlohmann::json& summary)
{
  NonlinearProblem& problem = strip.problem();
  BondedBuckling b;
  Mat K = problem.create_matrix(), K_probe = problem.create_matrix();
  problem.tangent(K);
  strip.set_end_distance(p.L - a.probe_shortening);
  NewtonSolver probe(comm, "probe_newton_");
  if (!probe.solve(problem).converged)
    throw ConvergenceError("the eigen-buckling's probe state did not converge");
  problem.tangent(K_probe);
  LinearBuckling buckling(comm);
  b.modes = buckling.solve(K, K_probe, a.modes, strip.space());
  MatDestroy(&K);
  MatDestroy(&K_probe);
  strip.set_end_distance(p.L);
  VecSet(problem.unknowns(), 0);
  problem.unknowns_changed();

  // The modes on the bonded strip's mesh, before the imperfection moves it
  FieldSeries mode_shapes(
      comm, std::filesystem::path(output) / "modes", *strip.mesh().mesh);
  nlohmann::json critical = nlohmann::json::array(), symmetry = nlohmann::json::array();
  for (std::size_t k = 0; k < b.modes.size(); ++k)
  {
    const auto [asymmetry, antisymmetry] = strip.mirror_asymmetry(*b.modes[k].shape);
    // A mode is one or the other to solver accuracy (the problem is mirror-symmetric);
    // 1e-3 leaves room for the eigensolver's tolerance
    const std::string kind = asymmetry < 1e-3       ? "mirror-symmetric"
                             : antisymmetry < 1e-3 ? "antisymmetric"
                                                    : "neither";
    const double shortening = b.modes[k].load_factor * a.probe_shortening;
    b.rows.push_back({{"mode", k + 1},
                          {"critical_shortening", shortening},
                          {"critical_end_distance", p.L - shortening},
                          {"mirror_asymmetry", asymmetry},
                          {"mirror_antisymmetry", antisymmetry},
                          {"symmetry", kind}});
    critical.push_back(shortening);
    symmetry.push_back(kind);
    FieldSet shape;
    shape.add("mode", b.modes[k].shape);
    mode_shapes.write(double(k + 1), shape.update());
  }
  summary.update({{"critical_shortening", critical},
                      {"first_critical_shortening", critical[0]},
                      {"mode_symmetry", symmetry}});
  return b;
}

void seek_equilibria(MPI_Comm comm, Bistrip& strip, const BistripAnalysis& a,
                     const std::vector<BucklingMode>& modes, int path_negative_eigenvalues,
                     ResultsWriter& results, FieldSet& fields,
                     const std::filesystem::path& output, nlohmann::json& summary)
{
  NonlinearProblem& problem = strip.problem();
  set_default_option("deflation_", "max_solutions", std::to_string(a.equilibria + 1));
  DeflationSolver deflation(comm, problem, "deflation_");
  std::vector<Equilibrium> found(1);
  // The path's state settled: a static Newton solve from it (a dynamic path ends moving, if
  // slowly; the damped flow's end state is one already: 0 or 1 iterations), to
  // |R| <= 1e-10 |R0| or 1e-9 N, its residual against the internal forces reported. Where
  // it does not converge (measured: from the bistrip's three-perversion state after T = 0.3 s
  // with inertia, |R| stalled at 0.012 N from 0.95 N with line-search steps of 1e-2, a flat
  // landscape), the path's state is kept and the summary says "settled": false
  set_default_options("settle_newton_", {{"snes_rtol", "1e-10"}, {"snes_atol", "1e-9"}});
  NewtonSolver settle(comm, "settle_newton_");
  const OwnedVec path_state = copy_of(problem.unknowns());
  found[0].newton = settle.solve(problem);
  summary["settled"] = found[0].newton.converged;
  if (!found[0].newton.converged)
    problem.set_state(path_state.get());
  summary["settled_residual"] = problem.static_residual();
  found[0].state = copy_of(problem.unknowns());
  found[0].negative_eigenvalues = found[0].newton.converged
                                      ? tangent_negative_eigenvalues(comm, problem)
                                      : path_negative_eigenvalues;
  summary["settled_distance"] = deflation.distance(found[0].state.get(), path_state.get());
  summary["path_negative_eigenvalues"] = path_negative_eigenvalues;
  deflation.deflate(found[0].state.get());
  std::vector<OwnedVec> guesses;
  std::vector<std::string> guess_names;
  for (std::size_t k = 0; k < modes.size(); ++k)
    for (double sign : {1.0, -1.0})
    {
      OwnedVec mode(dolfinx::la::petsc::create_vector_wrap(*modes[k].shape->x()));
      guesses.emplace_back(problem.create_vector());
      GELX_PETSC(VecWAXPY(guesses.back().get(), sign * a.guess_amplitude, mode.get(),
                          found[0].state.get()));
      guess_names.push_back((sign > 0 ? "+mode " : "-mode ") + std::to_string(k + 1));
    }
  // One guess at a time (not find()), to know which guess found each equilibrium
  std::vector<std::string> origin = {"path"};
  for (std::size_t g = 0; g < guesses.size() && found.size() <= std::size_t(a.equilibria);
       ++g)
    if (auto e = deflation.solve(guesses[g].get()))
    {
      found.push_back(std::move(*e));
      origin.push_back(guess_names[g]);
    }
  FieldSeries equilibrium_fields(
      comm, std::filesystem::path(output) / "equilibria",
      *strip.mesh().mesh);
  std::vector<nlohmann::json> rows, rows_centreline;
  double path_energy = NAN; // found[0]'s, the first in the loop
  for (std::size_t i = 0; i < found.size(); ++i)
  {
    problem.set_state(found[i].state.get());
    const auto [energy_A, energy_B] = strip.strip_energies();
    if (i == 0)
      path_energy = energy_A + energy_B;
    const CentrelineSamples c = strip.centreline();
    const auto helices = analyse_centreline(c, a.min_frame_turns);
    rows.push_back({{"equilibrium", i},
                    {"origin", i == 0 ? (found[0].newton.converged ? "path, settled" : "path")
                                      : "deflation"},
                    {"guess", origin[i]},
                    {"end_distance", strip.end_distance()},
                    {"strain_energy", energy_A + energy_B},
                    {"strain_energy_A", energy_A},
                    {"strain_energy_B", energy_B},
                    {"energy_difference", energy_A + energy_B - path_energy},
                    {"negative_eigenvalues", found[i].negative_eigenvalues},
                    {"segments", helices.segments.size()},
                    {"perversions", helices.perversions.size()},
                    {"perversion_positions", joined(helices.perversions)},
                    {"distance", deflation.distance(found[i].state.get(),
                                                    found[0].state.get())},
                    {"newton_iterations", found[i].newton.iterations}});
    for (std::size_t k = 0; k < c.Z.size(); ++k)
      rows_centreline.push_back({{"equilibrium", i}, {"Z", c.Z[k]}, {"x", c.centre[k][0]},
                                 {"y", c.centre[k][1]}, {"z", c.centre[k][2]},
                                 {"twist", helices.twist[k]}});
    equilibrium_fields.write(double(i), fields.update());
  }
  results.write_table("equilibria.csv", rows);
  results.write_table("equilibria_centreline.csv", rows_centreline);
  problem.set_state(found[0].state.get());
  summary["equilibria"] = rows;
}

} // namespace gelx::scenes
