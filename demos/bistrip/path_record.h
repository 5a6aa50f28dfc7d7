#pragma once
/// @file path_record.h
/// What the bistrip scene records along its path, whichever method follows it (analysis.h):
/// the work of the end force at every step and, at every output distance, the state read as
/// the thesis reads it (Figs. 3.2-3.7): the strips' energies, the helices and perversions of
/// the centreline (centreline.h), the energy of every slab and its condensation at the
/// central perversion, the tangent's stability.

#include "analysis.h"
#include "bistrip.h"
#include "centreline.h"

#include <gelx/io/output.h>
#include <gelx/io/program.h>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

namespace gelx::scenes
{

/// "a;b;c": a list in one CSV cell
std::string joined(const std::vector<double>& values);

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
                          int last);

/// The condensation at the perversion nearest mid-length: the peak searched from the middle
/// of the helical segment before it to the middle of the one after, so that the clamps'
/// boundary layers (which hold the helices' ends flat, and store energy too) do not count
/// as the perversion's; none without a perversion
Condensation perversion_condensation(const std::vector<std::pair<double, double>>& slabs,
                                     const CentrelineAnalysis& helices, double L);

/// The record of one path of the strip, into the run's results: after every step the work
/// of the end force (trapezoidal in the end distance); at every `output_every` of end travel
/// and at the last step of a leg an output: a row of steps.csv (what the method says of the
/// step, the end distance and force, the strips' energies, the work, the energy balance, the
/// tangent's negative eigenvalues, segments and perversions, the helices' pitch and radius,
/// the condensation), the fields, the centreline (centreline.csv) and the slabs' energies
/// (slab_energy.csv); the summary's quantities kept current.
class PathRecord
{
public:
  /// `prebuckled_distance`: end distances above it are before the first critical one (the
  /// straight strip, recorded as such in the summary); NAN when not known.
  PathRecord(Run& run, ResultsWriter& results, FieldSet& fields, Bistrip& strip,
             const BistripParameters& p, const BistripAnalysis& a, double prebuckled_distance);

  /// A leg begins: 0 the bonding at L (no balance), 1 the end driven to end_distance (the
  /// energy balance counts from the strips' energies now), 2 the end driven back out, 3 the
  /// end held while the flow settles the strip (--settle_time). Every
  /// path begins one (or restores a record, restore()) before its first step.
  void begin_leg(int leg);

  /// After every step: `method_row` what the path's method says of it (its `step` is
  /// replaced by the run's: steps are counted over all legs), `dissipated` the
  /// energy its damping has dissipated so far on legs 1 and 2 and `kinetic` the kinetic
  /// energy now (0 without inertia: the balance is W = dSE + KE + ED), `output_now` an
  /// output besides those by travel (the last step of a leg, a held leg's every tenth).
  void step_done(const nlohmann::json& method_row, double dissipated, double kinetic,
                 bool output_now);

  double end_force() const { return _last_force; }
  const CentrelineAnalysis& last_analysis() const { return _analysis; }
  int last_negative_eigenvalues() const { return _negative; }

  /// What the record has accumulated (the work, the outputs so far and their tables), for a
  /// checkpoint's PathState::scene, and its restoration on a restart: the record then
  /// continues as if never stopped.
  nlohmann::json state() const;
  void restore(const nlohmann::json& state);
  int leg() const { return _leg; }
  /// Steps taken so far, over all legs: the run's step numbering
  int steps() const { return _steps; }

  /// The energy density over three cross-sections of the state of the last output (Fig. 3.6):
  /// the perversion nearest mid-length, its edge and the helix beyond it (sections.csv);
  /// nothing without a perversion.
  void write_sections() const;

private:
  void output(nlohmann::json row, double dissipated, double kinetic);

  Run& _run;
  ResultsWriter& _results;
  FieldSet& _fields;
  Bistrip& _strip;
  const BistripParameters& _p;
  const BistripAnalysis& _a;
  double _prebuckled_distance;
  double _energy_A0 = 0, _energy_B0 = 0; ///< the strips' energies the balance starts from
  double _work = 0, _last_force = 0, _last_distance = 0;
  double _travelled = 0, _next_output = 0;
  int _steps = 0, _output_step = 0, _leg = 1, _negative = -1;
  std::vector<nlohmann::json> _centreline_rows, _slab_rows;
  CentrelineAnalysis _analysis;
  Condensation _condensation;
};

} // namespace gelx::scenes
