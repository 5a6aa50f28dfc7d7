#pragma once
/// @file bistrip.h
/// The prestretched bistrip of thesis chapter 3 (Fig. 3.1b, Table 3.1): strip B (lower) is
/// stress-free, strip A (upper) was stretched from its natural length L / stretch to L before
/// the two were bonded. Compressible neo-Hookean (Eq. 3.1) or Mooney-Rivlin with A's stretch
/// carried as the prestretch F0 of its cells (forms/prestretched_strip.py), structured hexahedra
/// (section.h). Other cross-sections (Fig. 3.10: tristrips, other widths) and a
/// pre-compressed strip A (stretch < 1, Fig. 3.8) are the same model with other parameters.
/// End z = 0 encastred; end z = L moves as a rigid face without rotation (u1 = u2 = 0, one
/// u3 for all its nodes), or both ends free (the small-misfit check).
/// Lengths in mm, stresses in MPa, forces in N, energies in mJ.

#include "centreline.h"
#include "section.h"

#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Function.h>
#include <gelx/systems/boundary.h>
#include <gelx/systems/forms.h>
#include <gelx/io/mesh.h>
#include <gelx/systems/problem.h>
#include <memory>
#include <mpi.h>
#include <string>
#include <utility>
#include <vector>

namespace gelx
{
class Parameters;
}

namespace gelx::scenes
{

struct BistripParameters
{
  double w = 5;       ///< width of each strip (mm; the thesis varies it from 5 to 9)
  double h = 3;       ///< thickness of each strip (mm), before A is stretched
  double L = 300;     ///< length (mm)
  double stretch = 3.5; ///< L / L': how far A was stretched (< 1: compressed) before bonding
  /// The cross-section, layers from the bottom up (parse_section); empty: "B wxh, A wxh",
  /// the bistrip of Fig. 3.10a
  std::string section;
  std::string law = "nh"; ///< "nh" neo-Hookean (Eq. 3.1) or "mr" Mooney-Rivlin
  double mooney_share = 0; ///< Mooney-Rivlin C01 / (C10 + C01), law mr
  double G = 1.5;     ///< shear modulus (MPa)
  double K = 40;      ///< bulk modulus (MPa)
  double rho = 1e-9;  ///< mass density (t/mm^3: 1000 kg/m^3, with time in s)
  int degree = 2;     ///< displacement element: Q2 (default) or Q1 hexahedra
  int nz = 100;       ///< cell layers (slabs) along the strip
  int nx = 2;         ///< cells across the narrowest layer (A's width)
  int ns = 1;         ///< cells across each overhang of a wider layer (B's beside A)
  int nb = 1;         ///< cells through each stress-free layer (B)
  int na = 1;         ///< cells through each prestretched layer (A)
  std::string ends = "clamped"; ///< "clamped" (Table 3.1) or "free" (no support at all)

  void bind(Parameters& prm);
  /// Throws gelx::InputError on a non-physical value.
  void check() const;
  /// The lateral stretch of A's uniaxial stretch (its cross-section shrinks by it).
  double lateral_stretch() const;
  /// The cross-section's layers in the bonded state.
  std::vector<Layer> layers() const;
};

/// The lateral stretch l of a compressible Mooney-Rivlin bar, U = C10 (I1_bar - 3) +
/// C01 (I2_bar - 3) + K/2 (J - 1)^2 with C10 = (1 - mooney_share) G/2, C01 = mooney_share G/2
/// (mooney_share 0: the neo-Hookean solid of Eq. 3.1), stretched (or, below 1, compressed) by
/// `stretch` along its axis with free sides: the root of sigma_lateral = 0 (bisection, to
/// round-off).
double uniaxial_lateral_stretch(double stretch, double G, double K, double mooney_share);

class Bistrip
{
public:
  Bistrip(MPI_Comm comm, BistripParameters p);

  NonlinearProblem& problem() { return *_problem; }
  const TaggedMesh& mesh() const { return _geo; }
  const BistripParameters& parameters() const { return _p; }
  std::shared_ptr<dolfinx::fem::Function<double>> displacement() const { return _u; }
  std::shared_ptr<const dolfinx::fem::FunctionSpace> space() const
  {
    return _u->function_space();
  }

  /// Give strip A the fraction s in [0, 1] of its prestretch, log-linearly: F0^s (I at 0,
  /// the bonded prestretch at 1, the default), as a growth or thermal strain would build
  /// it up: a strip whose full prestretch leaves the bonded state unstable (pre-compressed)
  /// can then buckle on the way.
  void set_prestretch_fraction(double s);
  /// Move the end z = L to the end-to-end distance d (mm).
  void set_end_distance(double d);
  double end_distance() const { return _end_distance; }
  /// The axial force on the moving end (N): positive while the strip pulls it inwards (A's
  /// prestretch holds the bonded strip in tension). Collective.
  double end_force() const;

  /// Stored energy of strip A and of strip B. Collective.
  std::pair<double, double> strip_energies() const;
  double strain_energy() const;
  /// Stored energy of each slab (cell layer) n = 0 .. nz - 1, strip A and strip B. Collective.
  std::vector<std::pair<double, double>> slab_energies() const;
  /// The energy density over the mid-section of slab n: rows (x, y, strip 'A' or 'B', psi)
  /// on a 5 x 5 grid per cell, in reference coordinates (thesis Fig. 3.6). Collective.
  struct SectionPoint
  {
    double x, y;
    char strip;
    double psi;
  };
  std::vector<SectionPoint> section_energy(int slab) const;

  /// The deformed centreline and width direction (the material frame: the bottom layer's
  /// top face, across) at every node layer. Collective.
  CentrelineSamples centreline() const;
  /// How far a mode (or any displacement) is from mirror symmetry about z = L/2:
  /// (|v - S v| / |v|, |v + S v| / |v|) with S v(x, y, z) = (v1, v2, -v3)(x, y, L - z): the
  /// first is 0 for a mirror-symmetric shape, the second for an antisymmetric one. Collective.
  std::pair<double, double> mirror_asymmetry(const dolfinx::fem::Function<double>& v) const;

  /// A smooth random imperfection for a strip whose bonded state is already unstable
  /// (pre-compressed: eigen-buckling about it is meaningless): every cross-section moved
  /// sideways by (sum_k a_k sin(k pi z / L), sum_k b_k sin(k pi z / L), 0), k = 1 ..
  /// `harmonics`, a_k and b_k uniform in [-1, 1] from a Mersenne twister with `seed` (the
  /// same on every rank and machine), scaled to largest component 1. Zero at the clamps; the
  /// damped dynamics amplifies its fastest-growing wavelengths, as noise seeds a pattern.
  std::shared_ptr<dolfinx::fem::Function<double>> random_imperfection(int harmonics,
                                                                      unsigned seed) const;

  std::shared_ptr<dolfinx::fem::Form<double>> mass_form() const;
  std::shared_ptr<dolfinx::fem::Expression<double>> stress() const;
  std::shared_ptr<dolfinx::fem::Expression<double>> energy_density() const;

private:
  BistripParameters _p;
  TaggedMesh _geo;
  std::shared_ptr<dolfinx::fem::Function<double>> _u, _F0;
  std::unique_ptr<FormBinding> _forms;
  std::unique_ptr<DirichletConditions> _bcs;
  std::unique_ptr<NonlinearProblem> _problem;
  std::shared_ptr<dolfinx::fem::Form<double>> _energy_A, _energy_B, _cell_energy;
  std::shared_ptr<dolfinx::fem::Expression<double>> _psi_section;
  std::vector<int> _slab_of_cell, _strip_of_cell; ///< owned cells
  /// The nodes' reference positions before any imperfection: where they sit in the
  /// structured mesh (layer, cross-section position)
  std::vector<double> _X;
  double _frame_half_width; ///< the bottom layer's: the frame's edges are x = +-this, y = 0
  double _end_distance;
};

} // namespace gelx::scenes
