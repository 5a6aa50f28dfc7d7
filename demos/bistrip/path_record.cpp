#include "path_record.h"

#include <algorithm>
#include <cmath>
#include <gelx/solvers/buckling.h>
#include <gelx/common/timing.h>
#include <sstream>

namespace gelx::scenes
{

std::string joined(const std::vector<double>& values)
{
  std::ostringstream s;
  for (std::size_t i = 0; i < values.size(); ++i)
    s << (i ? ";" : "") << values[i];
  return s.str();
}

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

namespace
{
/// The index of the perversion nearest mid-length (P not empty)
std::size_t central(const std::vector<double>& P, double L)
{
  return std::min_element(P.begin(), P.end(), [&](double x, double y)
                          { return std::abs(x - L / 2) < std::abs(y - L / 2); })
         - P.begin();
}
} // namespace

Condensation perversion_condensation(const std::vector<std::pair<double, double>>& slabs,
                                     const CentrelineAnalysis& helices, double L)
{
  const int nz = slabs.size();
  const auto& P = helices.perversions;
  if (P.empty())
    return condensation(slabs, 0, -1);
  const std::size_t k = central(P, L);
  // Perversion k lies between segments k and k + 1
  const auto middle = [&](const HelicalSegment& s)
  { return std::clamp(static_cast<int>(0.5 * (s.start + s.end) / L * nz), 0, nz - 1); };
  return condensation(slabs, middle(helices.segments[k]), middle(helices.segments[k + 1]));
}

PathRecord::PathRecord(Run& run, ResultsWriter& results, FieldSet& fields, Bistrip& strip,
                       const BistripParameters& p, const BistripAnalysis& a,
                       double prebuckled_distance)
    : _run(run), _results(results), _fields(fields), _strip(strip), _p(p), _a(a),
      _prebuckled_distance(prebuckled_distance), _next_output(a.output_every)
{
}

void PathRecord::begin_leg(int leg)
{
  _leg = leg;
  if (leg == 1)
    std::tie(_energy_A0, _energy_B0) = _strip.strip_energies();
  _last_force = _strip.end_force();
  _last_distance = _strip.end_distance();
}

nlohmann::json PathRecord::state() const
{
  return {{"energy_A0", _energy_A0},           {"energy_B0", _energy_B0},
          {"work", _work},                     {"last_force", _last_force},
          {"last_distance", _last_distance},   {"travelled", _travelled},
          {"next_output", _next_output},       {"output_step", _output_step},
          {"steps", _steps},
          {"leg", _leg},                       {"negative_eigenvalues", _negative},
          {"centreline_rows", _centreline_rows}, {"slab_rows", _slab_rows}};
}

void PathRecord::restore(const nlohmann::json& state)
{
  _energy_A0 = state.at("energy_A0");
  _energy_B0 = state.at("energy_B0");
  _work = state.at("work");
  _last_force = state.at("last_force");
  _last_distance = state.at("last_distance");
  _travelled = state.at("travelled");
  _next_output = state.at("next_output");
  _output_step = state.at("output_step");
  _steps = state.at("steps");
  _leg = state.at("leg");
  _negative = state.at("negative_eigenvalues");
  _centreline_rows = state.at("centreline_rows").get<std::vector<nlohmann::json>>();
  _slab_rows = state.at("slab_rows").get<std::vector<nlohmann::json>>();
  // The helices for write_sections should the run end at once: those of the restored state
  _analysis = analyse_centreline(_strip.centreline(), _a.min_frame_turns);
  _condensation = perversion_condensation(_strip.slab_energies(), _analysis, _p.L);
}

void PathRecord::step_done(const nlohmann::json& method_row, double dissipated, double kinetic,
                           bool output_now)
{
  ++_steps;
  const double force = _strip.end_force(), d = _strip.end_distance();
  _work += 0.5 * (force + _last_force) * (d - _last_distance);
  _travelled += std::abs(d - _last_distance);
  _last_force = force;
  _last_distance = d;
  if (_travelled >= _next_output - 1e-9 * _p.L || output_now)
  {
    output(method_row, dissipated, kinetic);
    while (_next_output <= _travelled + 1e-9 * _p.L)
      _next_output += _a.output_every;
  }
}

void PathRecord::output(nlohmann::json row, double dissipated, double kinetic)
{
  gelx::TimedStage timing("output");
  ++_output_step;
  const double d = _strip.end_distance();
  const auto [energy_A, energy_B] = _strip.strip_energies();
  const int negative = _negative
      = gelx::tangent_negative_eigenvalues(_run.comm(), _strip.problem());
  const CentrelineSamples c = _strip.centreline();
  _analysis = analyse_centreline(c, _a.min_frame_turns);
  const auto slabs = _strip.slab_energies();
  const Condensation& e = _condensation
      = perversion_condensation(slabs, _analysis, _p.L);
  const double peak_anywhere = *std::max_element(e.scaled.begin(), e.scaled.end());
  const double change = energy_A + energy_B - _energy_A0 - _energy_B0;
  // The helices' mean pitch and radius, weighted by their lengths
  double pitch = 0, radius = 0, length = 0;
  for (const auto& h : _analysis.segments)
  {
    pitch += h.pitch * (h.end - h.start);
    radius += h.radius * (h.end - h.start);
    length += h.end - h.start;
  }
  row.update({{"step", _steps},
              {"leg", _leg},
              {"end_distance", d},
              {"end_force", _last_force},
              {"strain_energy_A", energy_A},
              {"strain_energy_B", energy_B},
              {"strain_energy_change", change},
              {"work", _work},
              // Relative to the largest term: on a return leg W goes back towards 0
              {"energy_balance_error",
               _leg == 0 ? NAN
                         : (_work - change - kinetic - dissipated)
                               / std::max({std::abs(_work), std::abs(change), dissipated})},
              {"negative_eigenvalues", negative},
              // How far from a static equilibrium the path's state is (the flow's and the
              // motion's states carry viscous and inertial forces): |R| / |f_int|
              {"static_residual", _strip.problem().static_residual()},
              {"segments", _analysis.segments.size()},
              {"perversions", _analysis.perversions.size()},
              {"perversion_positions", joined(_analysis.perversions)},
              {"helix_pitch", length > 0 ? pitch / length : NAN},
              {"helix_radius", length > 0 ? radius / length : NAN},
              {"energy_peak", e.peak},
              {"energy_peak_slab", e.peak_slab},
              {"energy_peak_width", e.width()},
              {"energy_peak_anywhere", peak_anywhere},
              {"output", _output_step},
              {"elapsed", _run.elapsed()}});
  _results.append_step(row);
  // Stamped with the output's number, not its end distance, which goes down and back up
  // over the legs: ParaView plays a series in the order of its time stamps
  _results.write_fields(_output_step, _fields.update());
  for (std::size_t k = 0; k < c.Z.size(); ++k)
    _centreline_rows.push_back({{"output", _output_step}, {"end_distance", d}, {"Z", c.Z[k]},
                               {"x", c.centre[k][0]}, {"y", c.centre[k][1]},
                               {"z", c.centre[k][2]},
                               {"curvature", _analysis.curvature[k]},
                               {"twist", _analysis.twist[k]},
                               {"d1x", _analysis.frame[k][0]},
                               {"d1y", _analysis.frame[k][1]},
                               {"d1z", _analysis.frame[k][2]}});
  _results.write_table("centreline.csv", _centreline_rows);
  for (int n = 0; n < _p.nz; ++n)
    _slab_rows.push_back({{"output", _output_step}, {"end_distance", d}, {"slab", n},
                         {"z", (n + 0.5) * _p.L / _p.nz}, {"energy_A", slabs[n].first},
                         {"energy_B", slabs[n].second},
                         {"energy_scaled", e.scaled[n]}});
  _results.write_table("slab_energy.csv", _slab_rows);
  // The last state before the first critical end distance: straight, the same on any
  // number of ranks (tests/CMakeLists.txt compares them)
  if (_leg == 1 && d > _prebuckled_distance)
    _run.summary.update({{"prebuckled_end_distance", d},
                        {"prebuckled_end_force", _last_force},
                        {"prebuckled_strain_energy_A", energy_A},
                        {"prebuckled_strain_energy_B", energy_B}});
  _run.summary.update({{"end_distance", d},
                      {"strain_energy_A", energy_A},
                      {"strain_energy_B", energy_B},
                      {"work", _work},
                      {"energy_balance_error", row["energy_balance_error"]},
                      {"negative_eigenvalues", negative},
                      {"static_residual", row["static_residual"]},
                      {"helices", _analysis.to_json()},
                      {"energy_peak", e.peak},
                      {"energy_peak_slab", e.peak_slab},
                      {"energy_peak_width", e.width()},
                      {"energy_peak_anywhere", peak_anywhere}});
}

void PathRecord::write_sections() const
{
  std::vector<nlohmann::json> section_rows;
  const Condensation& e = _condensation;
  if (e.peak_slab >= 0)
  {
    // The perversion's centre, its edge (the last slab of its condensation) and the middle
    // of the helix beyond it
    const auto& P = _analysis.perversions;
    const std::size_t k = central(P, _p.L);
    const auto& helix = _analysis.segments[k + 1];
    const double slab = _p.L / _p.nz;
    for (const auto& [site, n] :
         {std::pair{"perversion_centre", static_cast<int>(P[k] / slab)},
          std::pair{"perversion_edge", e.last_slab},
          std::pair{"helix", static_cast<int>(0.5 * (helix.start + helix.end) / slab)}})
    {
      const int slab_index = std::clamp(n, 0, _p.nz - 1);
      for (const auto& q : _strip.section_energy(slab_index))
        section_rows.push_back({{"site", site}, {"slab", slab_index}, {"x", q.x}, {"y", q.y},
                                {"strip", std::string(1, q.strip)},
                                {"energy_density", q.psi}});
    }
    _results.write_table("sections.csv", section_rows);
  }

}

} // namespace gelx::scenes
