#include <gelx/io/units.h>

#include <map>
#include <stdexcept>

namespace gelx
{
namespace
{
enum class Dimension
{
  none, // a number without unit
  text, // a label, a flag
  length,
  area,
  per_length, // a curvature, a twist per length
  force,
  moment,
  energy,
  stress, // also an energy per volume
  time,
  temperature,
  per_temperature,
  memory
};

/// Every quantity by name, with its dimension. Names
/// with `_over_` (a quantity divided by a scale), `_ratio` or `iterations` are numbers without
/// unit and need no entry.
const std::map<std::string, Dimension>& dimensions()
{
  using D = Dimension;
  static const std::map<std::string, Dimension> table = {
      // Where a path is: step, load factor, time, legs, outputs
      {"step", D::none}, {"t", D::none}, {"load_factor", D::none}, {"amplitude", D::none},
      {"leg", D::none}, {"output", D::none}, {"mode", D::none}, {"equilibrium", D::none},
      {"branch", D::none},
      {"slab", D::none}, {"arc_length", D::none}, {"path", D::text},
      {"T", D::temperature}, {"time", D::time}, {"dt", D::time},
      // Counts
      {"cutbacks", D::none}, {"rejected", D::none}, {"rejected_steps", D::none},
      {"failed_solves", D::none}, {"steps", D::none}, {"arclength_steps", D::none},
      {"load_steps", D::none}, {"negative_eigenvalues", D::none},
      {"path_negative_eigenvalues", D::none}, {"perversions", D::none}, {"segments", D::none},
      {"active_nodes", D::none}, {"num_cells", D::none}, {"num_dofs", D::none},
      {"num_unknowns", D::none}, {"mpi_ranks", D::none}, {"diagram_branches", D::none},
      {"diagram_points", D::none},
      // Residuals: Newton's norms of the residual vector (nodal forces), the rest relative
      {"newton_residual", D::force}, {"newton_residual0", D::force},
      {"static_residual", D::none}, {"settled_residual", D::none},
      {"energy_balance_error", D::none},
      // Geometry and kinematics
      {"x", D::length}, {"y", D::length}, {"z", D::length}, {"Z", D::length},
      {"end_distance", D::length}, {"prebuckled_end_distance", D::length},
      {"settled_distance", D::length}, {"critical_end_distance", D::length},
      {"critical_shortening", D::length}, {"first_critical_shortening", D::length},
      {"perversion_positions", D::length}, {"helix_pitch", D::length},
      {"helix_radius", D::length}, {"max_penetration", D::length}, {"distance", D::length},
      {"start", D::length}, {"end", D::length}, {"pitch", D::length}, {"radius", D::length},
      {"frame_turns", D::none}, {"chirality", D::text},
      {"imperfection_amplitude", D::length}, {"contact_area", D::area},
      {"curvature", D::per_length}, {"twist", D::per_length}, {"d1x", D::none},
      {"d1y", D::none}, {"d1z", D::none}, {"min_det_F", D::none}, {"lateral_stretch", D::none},
      {"inner_stretch", D::none}, {"stretch", D::none}, {"final_stretch", D::none},
      {"last_stretch", D::none}, {"stretch_at_p_max", D::none},
      {"stretch_at_target", D::none}, {"closed_form_stretch_at_p_max", D::none},
      {"asphericity", D::none}, {"alpha_par", D::none}, {"alpha_perp", D::none},
      {"alpha_perp_y", D::none}, {"anisotropy", D::none}, {"theory_alpha0", D::none},
      {"theory_uniaxial_alpha_perp", D::none}, {"max_shear_macro", D::none},
      {"min_J_minus_phi0", D::none}, {"chemical_potential", D::none}, {"mu", D::none},
      {"mu0", D::none}, {"mu_midplane", D::none}, {"phi0", D::none}, {"chi", D::none},
      {"chi0", D::none},
      {"thickness", D::length}, {"front_depth", D::length}, {"phi_i", D::none}, {"phi_f", D::none},
      {"valley_depth", D::length}, {"fold_gap", D::length},
      {"slenderness", D::none}, {"area_ratio", D::none},
      // Inverse design: the distance to the target, the helix asked for and formed, the cost
      {"rms_distance", D::length}, {"rms_distance_start", D::length},
      {"rms_rate_error", D::per_length},
      {"target_radius", D::length}, {"target_pitch", D::length},
      {"target_helix_radius", D::length}, {"target_helix_pitch", D::length},
      {"start_helix_radius", D::length}, {"start_helix_pitch", D::length},
      // and the perversion asked for (demos/design --shape perversion)
      {"perversion_position", D::length}, {"helix_turns_before", D::none},
      {"helix_turns_after", D::none}, {"start_perversions", D::none},
      {"start_perversion_position", D::length}, {"start_helix_turns_before", D::none},
      {"start_helix_turns_after", D::none}, {"target_perversions", D::none},
      {"target_perversion_position", D::length}, {"target_helix_turns_before", D::none},
      {"target_helix_turns_after", D::none},
      {"radius_error", D::none}, {"pitch_error", D::none}, {"angle", D::none},
      {"num_parameters", D::none}, {"optimizer_reason", D::none}, {"forward_solves", D::none},
      {"adjoint_solves", D::none}, {"layer", D::text},
      // Fits of the pyramid's contact width l_c/L against d/H and sqrt(f)
      {"slope_lc_vs_d", D::none}, {"slope_lc_vs_d_extrapolated", D::none},
      {"slope_lc_vs_d_gap_law", D::none}, {"intercept_lc_vs_d", D::none},
      {"intercept_lc_vs_d_gap_law", D::none}, {"r2_lc_vs_d", D::none},
      {"r2_lc_vs_sqrtf", D::none}, {"slope_lc_vs_sqrtf", D::none},
      // Forces, moments, loads
      {"force", D::force}, {"final_force", D::force}, {"axial_force", D::force},
      {"end_force", D::force}, {"prebuckled_end_force", D::force}, {"euler_load", D::force},
      {"critical_load", D::force}, {"torque", D::moment}, {"in_contact", D::none},
      {"bifurcation_bracket", D::none}, {"elastica_at_branch_end", D::none},
      {"elastica_at_imperfect_end", D::none}, {"stability", D::none},
      {"stability_at_switch", D::none},
      // Energies (an energy_* without unit is Ẽ, the slab energy over its least value)
      {"strain_energy", D::energy}, {"strain_energy_A", D::energy},
      {"strain_energy_B", D::energy}, {"strain_energy_change", D::energy},
      {"energy_A", D::energy}, {"energy_B", D::energy}, {"energy_difference", D::energy},
      {"prebuckled_strain_energy_A", D::energy}, {"prebuckled_strain_energy_B", D::energy},
      {"prestress_energy", D::energy}, {"kinetic_energy", D::energy},
      {"dissipated_energy", D::energy}, {"external_work", D::energy}, {"work", D::energy},
      {"balance_residual", D::energy}, {"potential_energy", D::energy},
      {"energy_density", D::stress},
      {"energy_scaled", D::none}, {"energy_peak", D::none}, {"energy_peak_anywhere", D::none},
      {"energy_peak_slab", D::none}, {"energy_peak_width", D::none},
      {"kinetic_bound", D::none}, {"dissipation_bound", D::none},
      // Buckling modes' symmetry
      {"mirror_asymmetry", D::none}, {"mirror_antisymmetry", D::none}, {"odd_part", D::none},
      {"even_part", D::none}, {"symmetry", D::text}, {"mode_symmetry", D::text},
      // The gel of chapter 4: the Flory-Huggins parameter chi = A + B T, polymer fractions,
      // the contraction A_max over the maps of phi_i and eps_par, transition temperatures
      {"chi_A", D::none}, {"chi_B", D::per_temperature}, {"phi", D::none},
      {"phi_prime_i", D::none}, {"phi_prime_f", D::none}, {"eps_par", D::none},
      {"A_max", D::none}, {"A_measured", D::none}, {"alpha0", D::none}, {"bound", D::none},
      {"bound_alpha0", D::none}, {"n_nu_vm", D::none}, {"undefined", D::none},
      {"non_unique", D::none}, {"T_i", D::temperature}, {"T_f", D::temperature},
      {"T_free", D::temperature}, {"T_constrained", D::temperature},
      // Labels and flags
      {"verdict", D::text}, {"scheme", D::text}, {"mass", D::text}, {"outcome", D::text},
      {"quasi_static", D::text}, {"settled", D::text}, {"limit_point", D::text},
      {"bifurcation", D::text}, {"fold", D::text}, {"unstable", D::text},
      {"self_contact", D::text}, {"origin", D::text}, {"guess", D::text}, {"strip", D::text},
      {"site", D::text}, {"newton_snes_type", D::text}, {"csv", D::text},
      {"fig4_3b_peo", D::text},
      // The run's cost
      {"wall_time", D::time}, {"elapsed", D::time}, {"setup_time", D::time},
      {"eigen_time", D::time}, {"diagram_time", D::time}, {"seconds", D::time},
      {"seconds_total", D::time}, {"forward_time", D::time}, {"adjoint_time", D::time},
      {"time_per_step", D::time},
      {"time_per_arclength_step", D::time}, {"time_per_corrector_iteration", D::time},
      {"time_per_newton_iteration", D::time}, {"wall_time_with_extrapolation", D::time},
      {"stable_step", D::time}, {"smallest_stable_step", D::time}};
  return table;
}

/// Groups of a summary whose every key has one dimension: the time split by stage, the peak
/// memory, where a restart continued from
const std::map<std::string, Dimension> group_dimensions
    = {{"time_split", Dimension::time},
       {"peak_memory_MiB", Dimension::memory},
       {"restarted_from", Dimension::none}};

std::string written(Dimension d, const Units& u)
{
  switch (d)
  {
  case Dimension::none: return "1";
  case Dimension::text: return "text";
  case Dimension::length: return u.length;
  case Dimension::area: return u.area;
  case Dimension::per_length: return "1/" + u.length;
  case Dimension::force: return u.force;
  case Dimension::moment: return u.moment;
  case Dimension::energy: return u.energy;
  case Dimension::stress: return u.stress;
  case Dimension::time: return "s";
  case Dimension::temperature: return "K";
  case Dimension::per_temperature: return "1/K";
  case Dimension::memory: return "MiB";
  }
  return "";
}

/// The summary's record of the run's inputs, not quantities
bool is_input(const std::string& key)
{
  return key == "parameters" || key == "versions" || key == "sources" || key == "petsc_options"
         || key == "scene" || key == "status" || key == "unit_system";
}

void collect(const nlohmann::json& object, const std::string& prefix, const Units& units,
             nlohmann::json& out)
{
  for (auto it = object.begin(); it != object.end(); ++it)
  {
    if (prefix.empty() && is_input(it.key()))
      continue;
    const std::string path = prefix + it.key();
    const nlohmann::json& value = it.value();
    if (value.is_object() && !group_dimensions.count(path))
      collect(value, path + ".", units, out);
    else if (value.is_array() && !value.empty() && value.front().is_object())
      for (const auto& row : value)
        collect(row, path + ".", units, out);
    else
    {
      const std::string unit = unit_of(path, units);
      out[path] = unit.empty() ? "?" : unit;
    }
  }
}
} // namespace

std::string unit_of(const std::string& name, const Units& units)
{
  // A nested key: its group's unit (time_split.solve: s), else its own name's
  // (dynamics.kinetic_energy: an energy)
  if (const auto group = group_dimensions.find(name.substr(0, name.find('.')));
      group != group_dimensions.end())
    return written(group->second, units);
  const std::string leaf = name.substr(name.rfind('.') + 1);
  if (const auto it = dimensions().find(leaf); it != dimensions().end())
    return written(it->second, units);
  if (leaf.find("_over_") != std::string::npos || leaf.find("iterations") != std::string::npos
      || (leaf.size() > 6 && leaf.compare(leaf.size() - 6, 6, "_ratio") == 0))
    return "1";
  return "";
}

nlohmann::json summary_units(const nlohmann::json& summary, const Units& units)
{
  nlohmann::json out = nlohmann::json::object();
  collect(summary, "", units, out);
  return out;
}

std::string units_line(const std::vector<std::string>& columns, const Units& units)
{
  std::string line = "# units:";
  for (std::size_t i = 0; i < columns.size(); ++i)
  {
    const std::string unit = unit_of(columns[i], units);
    if (unit.empty())
      throw std::logic_error("the column '" + columns[i]
                             + "' has no unit: add it to gelx's dimensions (io/units.cpp)");
    line += (i ? ", " : " ") + columns[i] + " [" + unit + "]";
  }
  return line + "\n";
}

} // namespace gelx
