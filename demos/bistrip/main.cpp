// gelx scene: the prestretched bistrip of thesis chapter 3 — helices, a perversion, and where
// the strain energy goes
//
// Sample runs:
//   ./gelx run bistrip                                    (the whole path, 30 -> 9 cm)
//   ./gelx run bistrip --end_distance 200 --nz 60         (coarse, up to the first helices)
//   ./gelx run bistrip --ends free --stretch 1.02 --L 60 --nz 20   (the small-misfit check)
//   ./gelx run bistrip --w 9 --section "B 9x3, S 9x3, B 9x0.2"     (a tristrip, Fig. 3.10c)
//   ./gelx run bistrip --w 3 --stretch 0.4 --seed random --bonding ramp --end_distance 270
//                      --return_distance 300                     (pre-compressed, Figs. 3.8-9)
//   ./gelx run bistrip --end_distance 233 --equilibria 6          (other equilibria there)
//   ./gelx sweep bistrip                                  (the studies of thesis section 3.4)
//
// The model (thesis section 3.2-3.3, Table 3.1): strip B (lower, w x h) is stress-free; strip A
// (upper) was stretched from its natural length L / stretch to L, its cross-section shrinking
// by the lateral stretch of that uniaxial stretch (Fig. 3.10a), and bonded to B's top face. A
// carries the stretch as its prestretch F0, so the bonded, straight strip is the reference
// state. End z = 0 is encastred; end z = L moves along z as a rigid face that does not rotate.
//
//  1. Eigen-buckling about the bonded state (Fig. 3.1c): the first modes, their critical
//     end shortening and their symmetry about the mid-plane z = L/2 (eigenvalues.csv, modes/).
//  2. The mode to seed (mode 1 by default) is added to the mesh at the thesis' amplitude, as
//     ABAQUS' *IMPERFECTION does.
//  3. Damped quasi-static dynamics (gelx::DampedDynamics, ABAQUS' *STABILIZE) brings the ends
//     together from L to the final end distance on a smooth-step ramp. At every output
//     distance: end force, the strain energy of each strip, kinetic and dissipated energy, the
//     work of the end force, the number of negative tangent eigenvalues, the helical segments
//     and perversions read off the centreline (centreline.h), the energy of every slab (Fig.
//     3.4b) and the shape coloured by von Mises stress (fields.xdmf). With --method arclength
//     the path is followed by arc-length continuation in the end shortening instead: it stays
//     on the unstable branch that continues the straight strip (demos/bistrip/README.md).
//     With --return_distance the end then moves back out (the stretching of Fig. 3.9).
//  4. At the final distance: the energy density over three cross-sections (Fig. 3.6): a
//     helical site, the edge and the centre of the perversion nearest mid-length; with
//     --equilibria, further equilibria there by deflation, their energies and stability.
// With --ends free (no support, the misfit alone) the scene solves the bonded strip's free
// equilibrium instead: the curvature of the bilayer (tests/bistrip.py checks it against
// Timoshenko's bimetal formula).

#include "bistrip.h"

#include <algorithm>
#include <cmath>
#include <dolfinx/la/petsc.h>
#include <filesystem>
#include <gelx/arclength.h>
#include <gelx/buckling.h>
#include <gelx/deflation.h>
#include <gelx/dynamics.h>
#include <gelx/newton.h>
#include <gelx/output.h>
#include <gelx/field_series.h>
#include <gelx/petsc_utils.h>
#include <gelx/program.h>
#include <gelx/timing.h>
#include <sstream>

namespace
{
struct Analysis
{
  double end_distance = 90;  ///< final end-to-end distance (mm)
  /// After end_distance, drive the end back out to this distance (mm; 0: no return leg): the
  /// stretching back of thesis Fig. 3.9
  double return_distance = 0;
  double output_every = 10;  ///< output every this much of end travel (mm)
  int modes = 5;             ///< buckling modes to compute
  int seed_mode = 1;         ///< the mode seeded as the imperfection
  /// Amplitude of the seeded mode (mm; largest component 1): the thesis' *IMPERFECTION
  /// "1, 1e-3" in its length unit, the cm of Table 3.1
  double imperfection = 0.01;
  /// The shortening of the eigen-buckling's perturbation load (mm): small, so that the
  /// tangent is still linear in it
  double probe_shortening = 0.1;
  double min_frame_turns = 0.25; ///< a helical segment's frame turns at least this much
  /// How the path is followed: "dynamics" (damped quasi-static dynamics) or "arclength"
  /// (continuation in the end shortening, to compare where it gets through)
  std::string method = "dynamics";
  int max_steps = 2000; ///< arc-length steps at most
  /// The imperfection: "mode" (the seed_mode-th buckling mode) or "random" (a smooth random
  /// shape of the centreline with `harmonics` sines along it, Bistrip::random_imperfection)
  std::string seed = "mode";
  /// How A's prestretch is there: "instant" (bonded carrying all of it, thesis Table 3.1);
  /// for a pre-compressed A, whose bonded state is unstable from the start, a leg 0 at end
  /// distance L first (damped dynamics, options -bonding_dynamics_): "quench" (bonded with
  /// all of it, the strip left to buckle) or "ramp" (built up log-linearly)
  std::string bonding = "instant";
  int harmonics = 60;
  /// Equilibria to seek by deflation at the final end distance, besides the path's (0: none)
  int equilibria = 0;
  /// The deflation's guesses: the path's state plus or minus each buckling mode at this
  /// amplitude (mm, the mode's largest component)
  double guess_amplitude = 3;
};

/// "a;b;c": a list in one CSV cell
std::string joined(const std::vector<double>& values)
{
  std::ostringstream s;
  for (std::size_t i = 0; i < values.size(); ++i)
    s << (i ? ";" : "") << values[i];
  return s.str();
}

/// The energy condensation of a slab profile E(n) (A and B summed): E~(n) = E(n) / min E - 1,
/// and the peak of E~ within slabs [first, last] (around a perversion), its slab, and its
/// extent: the slabs around the peak where E~ stays above half the peak (a double hump
/// counts whole)
struct Condensation
{
  std::vector<double> scaled;
  double peak = NAN;
  int peak_slab = -1, first_slab = -1, last_slab = -1;
  int width() const { return last_slab - first_slab + 1; }
};
Condensation condensation(const std::vector<std::pair<double, double>>& slabs, int first,
                          int last)
{
  Condensation c;
  double least = INFINITY;
  for (const auto& [A, B] : slabs)
    least = std::min(least, A + B);
  for (const auto& [A, B] : slabs)
    c.scaled.push_back((A + B) / least - 1);
  if (first > last)
    return c;
  c.peak_slab = std::max_element(c.scaled.begin() + first, c.scaled.begin() + last + 1)
                - c.scaled.begin();
  c.peak = c.scaled[c.peak_slab];
  c.first_slab = c.last_slab = c.peak_slab;
  while (c.first_slab > first && c.scaled[c.first_slab - 1] >= c.peak / 2)
    --c.first_slab;
  while (c.last_slab < last && c.scaled[c.last_slab + 1] >= c.peak / 2)
    ++c.last_slab;
  return c;
}

/// The index of the perversion nearest mid-length (P not empty)
std::size_t central(const std::vector<double>& P, double L)
{
  return std::min_element(P.begin(), P.end(), [&](double x, double y)
                          { return std::abs(x - L / 2) < std::abs(y - L / 2); })
         - P.begin();
}

/// The condensation at the perversion nearest mid-length: the peak searched from the middle
/// of the helical segment before it to the middle of the one after, so that the clamps'
/// boundary layers (which hold the helices' ends flat, and store energy too) do not count
/// as the perversion's; none without a perversion
Condensation perversion_condensation(const std::vector<std::pair<double, double>>& slabs,
                                     const gelx::scenes::CentrelineAnalysis& helices, double L)
{
  const int nz = slabs.size();
  const auto& P = helices.perversions;
  if (P.empty())
    return condensation(slabs, 0, -1);
  const std::size_t k = central(P, L);
  // Perversion k lies between segments k and k + 1
  const auto middle = [&](const gelx::scenes::HelicalSegment& s)
  { return std::clamp(static_cast<int>(0.5 * (s.start + s.end) / L * nz), 0, nz - 1); };
  return condensation(slabs, middle(helices.segments[k]), middle(helices.segments[k + 1]));
}
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters
  gelx::scenes::BistripParameters p;
  Analysis a;
  gelx::Parameters prm;
  p.bind(prm);
  prm.bind("analysis", "end_distance", a.end_distance, "final end-to-end distance (mm)",
           gelx::Parameters::positive);
  prm.bind("analysis", "return_distance", a.return_distance,
           "after end_distance, drive the end back to this distance (mm; 0: no return)",
           gelx::Parameters::non_negative);
  prm.bind("analysis", "output_every", a.output_every, "output every this much end travel (mm)",
           gelx::Parameters::positive);
  prm.bind("analysis", "modes", a.modes, "buckling modes to compute",
           gelx::Parameters::at_least_one);
  prm.bind("analysis", "seed_mode", a.seed_mode, "the buckling mode seeded as imperfection",
           gelx::Parameters::at_least_one);
  prm.bind("analysis", "seed", a.seed, "imperfection: mode (a buckling mode) or random",
           [](const std::string& m)
           { return m == "mode" || m == "random" ? "" : "must be mode or random"; });
  prm.bind("analysis", "bonding", a.bonding,
           "instant (A bonded with its prestretch), quench (then left to buckle at L) or ramp "
           "(the prestretch built up at L first)",
           [](const std::string& m)
           {
             return m == "instant" || m == "quench" || m == "ramp"
                        ? ""
                        : "must be instant, quench or ramp";
           });
  prm.bind("analysis", "harmonics", a.harmonics, "sines along the strip of --seed random",
           gelx::Parameters::at_least_one);
  prm.bind("analysis", "imperfection", a.imperfection,
           "amplitude of the seeded mode (mm, its largest component 1)",
           gelx::Parameters::non_negative);
  prm.bind("analysis", "probe_shortening", a.probe_shortening,
           "the eigen-buckling's perturbation: an end shortening (mm)", gelx::Parameters::positive);
  prm.bind("analysis", "method", a.method, "path: dynamics or arclength",
           [](const std::string& m)
           { return m == "dynamics" || m == "arclength" ? "" : "must be dynamics or arclength"; });
  prm.bind("analysis", "max_steps", a.max_steps, "arc-length steps at most",
           gelx::Parameters::at_least_one);
  prm.bind("analysis", "equilibria", a.equilibria,
           "equilibria to seek by deflation at the final end distance (0: none)",
           gelx::Parameters::non_negative);
  prm.bind("analysis", "guess_amplitude", a.guess_amplitude,
           "deflation's guesses: the path's state +- each mode at this amplitude (mm)",
           gelx::Parameters::positive);
  prm.bind("analysis", "min_frame_turns", a.min_frame_turns,
           "turns of the frame below which a stretch of one twist sign is noise",
           gelx::Parameters::positive);

  return gelx::run_program(argc, argv, "gelx-bistrip", prm, [&](gelx::Run& run)
  {
    p.check();
    if (p.ends == "clamped" && a.end_distance >= p.L)
      throw gelx::InputError("end_distance must be below L");
    if (a.return_distance > 0
        && (a.return_distance <= a.end_distance || a.return_distance > p.L))
      throw gelx::InputError("return_distance must lie in (end_distance, L]");
    if (a.equilibria > 0 && a.seed != "mode")
      throw gelx::InputError("equilibria need the buckling modes for guesses: --seed mode");
    if (a.bonding != "instant" && (a.seed != "random" || a.method != "dynamics"))
      throw gelx::InputError("--bonding " + a.bonding
                             + " needs --seed random and --method dynamics");
    if (a.return_distance > 0 && a.method != "dynamics")
      throw gelx::InputError("return_distance needs --method dynamics");
    if (a.seed_mode > a.modes)
      throw gelx::InputError("seed_mode must be one of the computed modes (1 .. modes)");

    // 2. The bonded strip
    gelx::scenes::Bistrip strip(run.comm(), p);
    gelx::NonlinearProblem& problem = strip.problem();
    // The strip energies the path's energy balance starts from
    double energy_A0, energy_B0;
    std::tie(energy_A0, energy_B0) = strip.strip_energies();
    run.summary = {{"num_dofs", strip.space()->dofmap()->index_map->size_global() * 3},
                   {"lateral_stretch", p.lateral_stretch()},
                   {"prestress_energy", energy_A0 + energy_B0}};
    gelx::FieldSet fields;
    fields.add("displacement", strip.displacement());
    fields.add("stress", strip.stress());
    fields.add("energy_density", strip.energy_density());

    if (p.ends == "free")
    {
      // The misfit alone: the free bilayer's equilibrium. Newton's linearised steps stretch
      // the bending strip, so |R| grows on the way to the solution and a backtracking line
      // search on |R| stalls (measured: 25 steps of 4 %); full Newton steps converge in 7
      gelx::set_default_option("newton_", "snes_linesearch_type", "basic");
      gelx::NewtonSolver newton(run.comm());
      gelx::ResultsWriter& results = run.results(strip.mesh().mesh);
      const gelx::NewtonReport report = newton.solve(problem);
      if (!report.converged)
        throw gelx::ConvergenceError("the free bilayer's equilibrium: " + report.reason);
      results.write_fields(1, fields.update());
      const gelx::scenes::CentrelineSamples c = strip.centreline();
      std::vector<nlohmann::json> rows;
      for (std::size_t k = 0; k < c.Z.size(); ++k)
        rows.push_back({{"Z", c.Z[k]}, {"x", c.centre[k][0]}, {"y", c.centre[k][1]},
                        {"z", c.centre[k][2]}});
      results.write_table("centreline.csv", rows);
      run.summary["newton_iterations"] = report.iterations;
      return;
    }

    // 3. The bonded state's stability, when A is pre-compressed (a strip A in tension leaves
    //    the bonded strip stable): the inertia of its tangent at u = 0. Compressed enough, A
    //    makes it unstable already, and it needs a leg 0 (--bonding quench or ramp). About a
    //    stable one, eigen-buckling: the tangent K and the tangent under a small end
    //    shortening (the perturbation load), the critical shortening its load factor times
    //    the probe's
    if (p.stretch < 1)
    {
      const int bonded_negative = gelx::tangent_negative_eigenvalues(run.comm(), problem);
      run.summary["bonded_negative_eigenvalues"] = bonded_negative;
      if (bonded_negative > 0 && a.bonding == "instant")
        throw gelx::InputError(
            "the bonded strip is unstable (" + std::to_string(bonded_negative)
            + " negative eigenvalues of its tangent): eigen-buckling about it does not apply "
              "and dynamics from it needs steps of 1e-9 s: use --bonding quench or ramp with "
              "--seed random");
    }
    std::vector<gelx::BucklingMode> modes;
    std::vector<nlohmann::json> eigen_rows;
    if (a.seed == "mode")
    {
      Mat K = problem.create_matrix(), K_probe = problem.create_matrix();
      problem.tangent(K);
      strip.set_end_distance(p.L - a.probe_shortening);
      gelx::NewtonSolver probe(run.comm(), "probe_newton_");
      if (!probe.solve(problem).converged)
        throw gelx::ConvergenceError("the eigen-buckling's probe state did not converge");
      problem.tangent(K_probe);
      gelx::LinearBuckling buckling(run.comm());
      modes = buckling.solve(K, K_probe, a.modes, strip.space());
      MatDestroy(&K);
      MatDestroy(&K_probe);
      strip.set_end_distance(p.L);
      VecSet(problem.unknowns(), 0);
      problem.unknowns_changed();

      // The modes on the bonded strip's mesh, before the imperfection moves it
      gelx::FieldSeries mode_shapes(
          run.comm(), std::filesystem::path(prm.text("output")) / "modes", *strip.mesh().mesh);
      nlohmann::json critical = nlohmann::json::array(), symmetry = nlohmann::json::array();
      for (std::size_t k = 0; k < modes.size(); ++k)
      {
        const auto [asymmetry, antisymmetry] = strip.mirror_asymmetry(*modes[k].shape);
        // A mode is one or the other to solver accuracy (the problem is mirror-symmetric);
        // 1e-3 leaves room for the eigensolver's tolerance
        const std::string kind = asymmetry < 1e-3       ? "mirror-symmetric"
                                 : antisymmetry < 1e-3 ? "antisymmetric"
                                                        : "neither";
        const double shortening = modes[k].load_factor * a.probe_shortening;
        eigen_rows.push_back({{"mode", k + 1},
                              {"critical_shortening", shortening},
                              {"critical_end_distance", p.L - shortening},
                              {"mirror_asymmetry", asymmetry},
                              {"mirror_antisymmetry", antisymmetry},
                              {"symmetry", kind}});
        critical.push_back(shortening);
        symmetry.push_back(kind);
        gelx::FieldSet shape;
        shape.add("mode", modes[k].shape);
        mode_shapes.write(double(k + 1), shape.update());
      }
      run.summary.update({{"critical_shortening", critical},
                          {"first_critical_shortening", critical[0]},
                          {"mode_symmetry", symmetry}});
    }

    // 4. The imperfection (and, with --bonding ramp, A without its prestretch yet)
    if (a.bonding == "ramp")
      strip.set_prestretch_fraction(0);
    gelx::seed_imperfection(*strip.mesh().mesh,
                            {a.seed == "mode" ? modes[a.seed_mode - 1]
                                              : gelx::BucklingMode{0, strip.random_imperfection(
                                                                          a.harmonics, 1)}},
                            {a.imperfection});
    gelx::ResultsWriter& results = run.results(strip.mesh().mesh);
    if (!modes.empty())
      results.write_table("eigenvalues.csv", eigen_rows);

    // 5. The path from L to the final end distance (leg 1), and with --return_distance back
    //    out (leg 2). At every step the work of the end force (trapezoidal); at every
    //    output_every of end travel, and at the end of each leg, the output
    const double travel = p.L - a.end_distance;
    double work = 0, last_force = strip.end_force(), last_distance = p.L;
    double travelled = 0, next_output = a.output_every;
    int output_step = 0, leg = 1;
    std::vector<nlohmann::json> centreline_rows, slab_rows;
    gelx::scenes::CentrelineAnalysis last_analysis;
    Condensation last_condensation;
    int last_negative = -1;
    // `row`: what the path's method says of the step; `dissipated`: the energy its
    // damping has dissipated so far (0 for arc-length)
    auto output = [&](nlohmann::json row, double dissipated)
    {
      gelx::TimedStage timing("output");
      ++output_step;
      const double d = strip.end_distance();
      const auto [energy_A, energy_B] = strip.strip_energies();
      const int negative = last_negative
          = gelx::tangent_negative_eigenvalues(run.comm(), problem);
      const gelx::scenes::CentrelineSamples c = strip.centreline();
      last_analysis = gelx::scenes::analyse_centreline(c, a.min_frame_turns);
      const auto slabs = strip.slab_energies();
      const Condensation& e = last_condensation
          = perversion_condensation(slabs, last_analysis, p.L);
      const double peak_anywhere = *std::max_element(e.scaled.begin(), e.scaled.end());
      const double change = energy_A + energy_B - energy_A0 - energy_B0;
      // The helices' mean pitch and radius, weighted by their lengths
      double pitch = 0, radius = 0, length = 0;
      for (const auto& h : last_analysis.segments)
      {
        pitch += h.pitch * (h.end - h.start);
        radius += h.radius * (h.end - h.start);
        length += h.end - h.start;
      }
      row.update({{"end_distance", d},
                  {"end_force", last_force},
                  {"strain_energy_A", energy_A},
                  {"strain_energy_B", energy_B},
                  {"strain_energy_change", change},
                  {"work", work},
                  // Relative to the largest term: on a return leg W goes back towards 0
                  {"energy_balance_error",
                   leg == 0 ? NAN
                            : (work - change - dissipated)
                                  / std::max({std::abs(work), std::abs(change), dissipated})},
                  {"negative_eigenvalues", negative},
                  {"segments", last_analysis.segments.size()},
                  {"perversions", last_analysis.perversions.size()},
                  {"perversion_positions", joined(last_analysis.perversions)},
                  {"helix_pitch", length > 0 ? pitch / length : NAN},
                  {"helix_radius", length > 0 ? radius / length : NAN},
                  {"energy_peak", e.peak},
                  {"energy_peak_slab", e.peak_slab},
                  {"energy_peak_width", e.width()},
                  {"energy_peak_anywhere", peak_anywhere},
                  {"output", output_step},
                  {"leg", leg},
                  {"elapsed", run.elapsed()}});
      results.append_step(row);
      // Stamped with the output's number, not its end distance, which goes down and back up
      // over the legs: ParaView plays a series in the order of its time stamps
      results.write_fields(output_step, fields.update());
      for (std::size_t k = 0; k < c.Z.size(); ++k)
        centreline_rows.push_back({{"output", output_step}, {"end_distance", d}, {"Z", c.Z[k]},
                                   {"x", c.centre[k][0]}, {"y", c.centre[k][1]},
                                   {"z", c.centre[k][2]},
                                   {"curvature", last_analysis.curvature[k]},
                                   {"twist", last_analysis.twist[k]},
                                   {"d1x", last_analysis.frame[k][0]},
                                   {"d1y", last_analysis.frame[k][1]},
                                   {"d1z", last_analysis.frame[k][2]}});
      results.write_table("centreline.csv", centreline_rows);
      for (int n = 0; n < p.nz; ++n)
        slab_rows.push_back({{"output", output_step}, {"end_distance", d}, {"slab", n},
                             {"z", (n + 0.5) * p.L / p.nz}, {"energy_A", slabs[n].first},
                             {"energy_B", slabs[n].second},
                             {"energy_scaled", e.scaled[n]}});
      results.write_table("slab_energy.csv", slab_rows);
      // The last state before the first critical end distance: straight, the same on any
      // number of ranks (tests/CMakeLists.txt compares them)
      if (leg == 1 && !modes.empty()
          && d > p.L - modes[0].load_factor * a.probe_shortening)
        run.summary.update({{"prebuckled_end_distance", d},
                            {"prebuckled_end_force", last_force},
                            {"prebuckled_strain_energy_A", energy_A},
                            {"prebuckled_strain_energy_B", energy_B}});
      run.summary.update({{"end_distance", d},
                          {"strain_energy_A", energy_A},
                          {"strain_energy_B", energy_B},
                          {"work", work},
                          {"energy_balance_error", row["energy_balance_error"]},
                          {"negative_eigenvalues", negative},
                          {"helices", last_analysis.to_json()},
                          {"energy_peak", e.peak},
                          {"energy_peak_slab", e.peak_slab},
                          {"energy_peak_width", e.width()},
                          {"energy_peak_anywhere", peak_anywhere}});
    };
    auto step_done = [&](const nlohmann::json& method_row, double dissipated, bool last)
    {
      const double force = strip.end_force(), d = strip.end_distance();
      work += 0.5 * (force + last_force) * (d - last_distance);
      travelled += std::abs(d - last_distance);
      last_force = force;
      last_distance = d;
      if (travelled >= next_output - 1e-9 * p.L || last)
      {
        output(method_row, dissipated);
        while (next_output <= travelled + 1e-9 * p.L)
          next_output += a.output_every;
      }
    };

    // One progress line per step: the end distance, the end force
    const gelx::ProgressLine::Options progress_options{
        .load_name = "end distance",
        .load = [&](const gelx::StepRecord&) { return strip.end_distance(); },
        .quantity = [&] { return gelx::quantity_text("end force", last_force); }};
    if (a.method == "dynamics")
    {
      // Damped quasi-static dynamics. Time in s with the
      //    density of rubber (rho = 1e-9 t/mm^3 in mm, MPa units): the strip's first bending
      //    vibration is a few Hz; c = 1/s relaxes it within milliseconds, so a loading time of
      //    1 s is quasi-static wherever the path is stable
      gelx::set_default_option("dynamics_", "loading_time", "1");
      gelx::set_default_option("dynamics_", "hold_time", "0.05");
      gelx::set_default_option("dynamics_", "damping", "1");
      gelx::set_default_option("dynamics_", "ts_rtol", "1e-3");
      gelx::set_default_option("dynamics_", "ts_atol", "1e-3");
      // A leg from the current end distance to `to`; `dissipated_before`: the energy the
      // damping dissipated on the legs before it (each leg's TS counts from 0)
      auto drive = [&](std::function<void(double)> load, double dissipated_before,
                       const std::string& key, const std::string& prefix = "dynamics_")
      {
        gelx::DampedDynamics dynamics(run.comm(), problem, *strip.mass_form(),
                                      [&] { return strip.strain_energy(); }, load, prefix);
        gelx::ProgressLine progress(run.comm(), progress_options);
        const gelx::DynamicsSummary summary = dynamics.run(
            {[&](const gelx::DynamicsRecord& r)
             {
               step_done(r.to_json(), dissipated_before + r.dissipated_energy,
                         r.time >= dynamics.end_time() - 1e-12);
               run.summary[key] = dynamics.summary().to_json();
               progress.print(r.step, strip.end_distance(), r.time / dynamics.end_time());
             }});
        run.summary[key] = summary.to_json();
        return dissipated_before + summary.dissipated_energy;
      };
      // The end from its distance now to `to`
      auto move_end = [&](double to)
      {
        const double from = strip.end_distance();
        return [&strip, from, to](double amplitude)
        { strip.set_end_distance(from + amplitude * (to - from)); };
      };
      if (a.bonding != "instant")
      {
        // Leg 0, the end held at L: a ramp builds the prestretch up over 1 s, at the path's
        // damping. A quench leaves the bonded strip to buckle: under a fixed load the
        // first-order dynamics c M u' = -R(u) is a gradient flow whose trajectory does not
        // depend on c, only its time scale does (t / c), so c is chosen for the steps: the
        // fastest modes grow at ~1e8/s for c = 1 (stretch 0.4), at a few per second for
        // c = 1e8; 2000 s of it settle (Fig. 3.8a's pattern from the fastest-growing
        // wavelengths; measured at nz = 60: after 200 s, 16 perversions and still 6 negative
        // eigenvalues, from which the path at c = 1 needs microsecond steps). The balance of the legs after it starts from where it ends (the
        // prestretch's own work is not the end force's)
        const bool quench = a.bonding == "quench";
        gelx::set_default_option("bonding_dynamics_", "loading_time", quench ? "2000" : "1");
        gelx::set_default_option("bonding_dynamics_", "hold_time", "0.05");
        gelx::set_default_option("bonding_dynamics_", "damping", quench ? "1e8" : "1");
        gelx::set_default_option("bonding_dynamics_", "ts_rtol", "1e-3");
        gelx::set_default_option("bonding_dynamics_", "ts_atol", "1e-3");
        leg = 0;
        drive([&](double s) { strip.set_prestretch_fraction(quench ? 1 : s); }, 0,
              "bonding_dynamics", "bonding_dynamics_");
        std::tie(energy_A0, energy_B0) = strip.strip_energies();
        leg = 1;
      }
      const double dissipated = drive(move_end(a.end_distance), 0, "dynamics");
      if (a.return_distance > 0)
      {
        leg = 2;
        drive(move_end(a.return_distance), dissipated, "return_dynamics");
      }
    }
    else
    {
      // Arc-length continuation in the end shortening: the Dirichlet values follow the load
      // factor, and ArcLength's dR/dlambda of the lifted residual carries them
      gelx::set_default_option("arclength_", "ds", "20");
      gelx::set_default_option("arclength_", "ds_max", "200");
      gelx::ArcLength continuation(run.comm(), problem,
                                   [&](double shortening)
                                   { strip.set_end_distance(p.L - shortening); });
      gelx::PathState path;
      gelx::ProgressLine::Options arclength_progress = progress_options;
      arclength_progress.fraction = [&](const gelx::StepRecord& pt) { return pt.load / travel; };
      continuation.run(
          path, a.max_steps,
          {[&](const gelx::StepRecord& pt, gelx::PathState&)
           {
             step_done({{"step", pt.step},
                        {"arc_length", pt.arc_length},
                        {"iterations", pt.newton.iterations},
                        {"cutbacks", pt.cutbacks},
                        {"wall_time", pt.wall_time}},
                       0.0, pt.load >= travel);
           },
           gelx::ProgressLine(run.comm(), arclength_progress)},
          [&](const gelx::StepRecord& pt) { return pt.load >= travel; });
      run.summary["arclength_steps"] = path.step;
      if (strip.end_distance() > a.end_distance)
        throw gelx::ConvergenceError("arc-length stopped at end distance "
                                     + std::to_string(strip.end_distance()) + " mm after "
                                     + std::to_string(path.step) + " steps");
    }

    // 6. The energy density over three cross-sections of the final state (Fig. 3.6): the
    //    perversion nearest mid-length, its edge and the helix beyond it
    std::vector<nlohmann::json> section_rows;
    const Condensation& e = last_condensation;
    if (e.peak_slab >= 0)
    {
      // The perversion's centre, its edge (the last slab of its condensation) and the middle
      // of the helix beyond it
      const auto& P = last_analysis.perversions;
      const std::size_t k = central(P, p.L);
      const auto& helix = last_analysis.segments[k + 1];
      const double slab = p.L / p.nz;
      for (const auto& [site, n] :
           {std::pair{"perversion_centre", static_cast<int>(P[k] / slab)},
            std::pair{"perversion_edge", e.last_slab},
            std::pair{"helix", static_cast<int>(0.5 * (helix.start + helix.end) / slab)}})
      {
        const int slab_index = std::clamp(n, 0, p.nz - 1);
        for (const auto& q : strip.section_energy(slab_index))
          section_rows.push_back({{"site", site}, {"slab", slab_index}, {"x", q.x}, {"y", q.y},
                                  {"strip", std::string(1, q.strip)},
                                  {"energy_density", q.psi}});
      }
      results.write_table("sections.csv", section_rows);
    }

    // 7. With --equilibria: other equilibria at the final end distance by deflation (the
    //    thesis' "metastable states ... with very close strain energy but different numbers
    //    of perversions"). The path's state, settled by the hold, is deflated; the guesses
    //    are it plus or minus each buckling mode. Each equilibrium: energy, stability (the
    //    tangent's inertia), perversions, fields (equilibria/fields.xdmf)
    if (a.equilibria > 0)
    {
      gelx::set_default_option("deflation_", "max_solutions", std::to_string(a.equilibria + 1));
      gelx::DeflationSolver deflation(run.comm(), problem, "deflation_");
      std::vector<gelx::Equilibrium> found(1);
      found[0].state = gelx::OwnedVec(problem.create_vector());
      GELX_PETSC(VecCopy(problem.unknowns(), found[0].state.get()));
      found[0].negative_eigenvalues = last_negative; // the last output's, of this state
      deflation.deflate(found[0].state.get());
      std::vector<gelx::OwnedVec> guesses;
      std::vector<std::string> guess_names;
      for (std::size_t k = 0; k < modes.size(); ++k)
        for (double sign : {1.0, -1.0})
        {
          gelx::OwnedVec mode(dolfinx::la::petsc::create_vector_wrap(*modes[k].shape->x()));
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
      gelx::FieldSeries equilibrium_fields(
          run.comm(), std::filesystem::path(prm.text("output")) / "equilibria",
          *strip.mesh().mesh);
      std::vector<nlohmann::json> rows, rows_centreline;
      double path_energy = NAN; // found[0]'s, the first in the loop
      for (std::size_t i = 0; i < found.size(); ++i)
      {
        problem.set_state(found[i].state.get());
        const auto [energy_A, energy_B] = strip.strip_energies();
        if (i == 0)
          path_energy = energy_A + energy_B;
        const gelx::scenes::CentrelineSamples c = strip.centreline();
        const auto helices = gelx::scenes::analyse_centreline(c, a.min_frame_turns);
        rows.push_back({{"equilibrium", i},
                        {"origin", i == 0 ? "path" : "deflation"},
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
      run.summary["equilibria"] = rows;
    }
  });
}
