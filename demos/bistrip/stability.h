#pragma once
/// @file stability.h
/// The bistrip's states and their stability: eigen-buckling about the bonded strip (thesis
/// Fig. 3.1c) and, at the path's final end distance, other equilibria found by deflation (the
/// thesis' metastable states of close energy and different perversion counts, section 3.3).

#include "analysis.h"
#include "bistrip.h"

#include <filesystem>
#include <gelx/solvers/buckling.h>
#include <gelx/io/output.h>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <vector>

namespace gelx::scenes
{

/// The first buckling modes of the bonded, straight strip at end distance L
struct BondedBuckling
{
  std::vector<BucklingMode> modes;
  /// A row of eigenvalues.csv per mode: critical shortening and end distance, symmetry about
  /// the mid-plane z = L/2
  std::vector<nlohmann::json> rows;
};

/// Eigen-buckling about the bonded strip (at u = 0, end distance L): the tangent K and the
/// tangent under a small end shortening (a.probe_shortening, the perturbation load), the
/// critical shortening of each of a.modes modes its load factor times the probe's; their
/// symmetry (Bistrip::mirror_asymmetry); the modes written to OUTPUT/modes; the critical
/// shortenings and symmetries into `summary`. Leaves the strip at L and u = 0. Collective.
BondedBuckling bonded_buckling(MPI_Comm comm, Bistrip& strip, const BistripParameters& p,
                               const BistripAnalysis& a, const std::filesystem::path& output,
                               nlohmann::json& summary);

/// Other equilibria at the strip's end distance now by deflation: the current state (the
/// path's, with `path_negative_eigenvalues` negative tangent eigenvalues) settled by a static
/// Newton solve (-settle_newton_*; summary "settled", "settled_residual" |R| / |f_int| and
/// "settled_distance" from the path's state; unsettled where it fails) and deflated, guesses it plus or minus each mode
/// at a.guess_amplitude, until a.equilibria are found. Each: energy, its difference to the
/// settled path state's, stability, perversions (equilibria.csv, equilibria_centreline.csv,
/// OUTPUT/equilibria/fields.xdmf, summary "equilibria"). Leaves the strip at the settled
/// state. Collective.
void seek_equilibria(MPI_Comm comm, Bistrip& strip, const BistripAnalysis& a,
                     const std::vector<BucklingMode>& modes, int path_negative_eigenvalues,
                     ResultsWriter& results, FieldSet& fields,
                     const std::filesystem::path& output, nlohmann::json& summary);

} // namespace gelx::scenes
