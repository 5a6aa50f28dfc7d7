#pragma once
/// @file units.h
/// The unit of every quantity gelx writes (a column of steps.csv or of another table, a key of
/// summary.json), defined once: a quantity has one name and one dimension in every scene, and
/// the scene's units say how that dimension is written.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace gelx
{
/// How a scene writes lengths, forces and energies. Every scene takes its moduli in MPa, so
/// the force unit is MPa times the length unit squared and the energy unit the force unit
/// times the length unit.
struct Units
{
  std::string length, area, force, moment, energy, stress;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Units, length, area, force, moment, energy, stress)
/// Millimetres: N, N mm, mJ (every scene but the pyramid).
inline const Units millimetre{"mm", "mm^2", "N", "N mm", "mJ", "MPa"};
/// Micrometres: uN, uN um, pJ (the pyramid's contact, chapter 2).
inline const Units micrometre{"um", "um^2", "uN", "uN um", "pJ", "MPa"};

/// The unit of the quantity `name` in `units`: "1" for a number without unit (a count, a
/// ratio, a quantity divided by a scale, named *_over_*), "text" for a label or a flag, s, K,
/// MiB, or the scene's length, force, energy ... A nested summary key is named by its path
/// (time_split.solve: s); a name not listed in units.cpp has none (empty): it is added
/// there, once, with its dimension.
std::string unit_of(const std::string& name, const Units& units);

/// {"path.of.key": unit} for every quantity of a summary (its nested objects' keys by path,
/// the keys of an array's objects by the array's name, a group of one unit such as
/// time_split by its name), but the run record's parameters,
/// versions, sources and PETSc options, which are inputs; a quantity without unit (unit_of)
/// gets "?", so that summary.json is written whole and the vocabulary test names it.
nlohmann::json summary_units(const nlohmann::json& summary, const Units& units);

/// The comment line that heads a table: "# units: step [1], end_distance [mm], ...". Throws
/// std::logic_error for a column without unit (unit_of), naming it.
std::string units_line(const std::vector<std::string>& columns, const Units& units);

} // namespace gelx
