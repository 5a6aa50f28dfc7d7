#pragma once
/// @file fiber_gel_cell.h
/// A gel reinforced by a periodic array of rigid fibers, contracting as the temperature rises
/// (thesis section 4.4): the unit cell of fiber_cell_mesh.h, the Flory-Rehner gel of Eq. 4.28
/// in its swollen reference state (forms/fiber_gel.py = forms/gel.py), the fiber surface
/// clamped (the fiber is rigid and, by symmetry, does not move) and the cell faces held by
/// multipoint constraints with free macro unknowns (gelx::MultipointConstraint): no load on
/// them, i.e. zero macro stress.

#include "fiber_cell_mesh.h"

#include <array>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Function.h>
#include <gelx/systems/boundary.h>
#include <gelx/systems/constraints.h>
#include <gelx/systems/problem.h>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace gelx::scenes
{

/// The gel and its contraction, after thesis section 4.4.2 steps (1)-(5): the free gel
/// contracts isotropically by alpha0 from phi_i at T_i to phi_f = phi_i / alpha0^3 at T_f,
/// which fixes chi_i = chi(phi_i) and chi_f = chi(phi_f) by Eq. 4.7 and the line
/// chi = chi_A + chi_B T through (T_i, chi_i) and (T_f, chi_f). Or the other way round: chi(T)
/// given (set_chi), phi_i and alpha0 are the free gel's states at T_i and T_f.
struct GelContraction
{
  double n = 0.01;     ///< N nu / V_m
  double phi_i = 0.3;  ///< polymer volume fraction of the stress-free reference state at T_i
  double alpha0 = 0.8; ///< contraction ratio of the free gel from T_i to T_f (Eq. 4.13)
  double T_i = 298;    ///< initial temperature (K)
  double T_f = 363;    ///< final temperature (K)

  /// Eq. 4.13 inverted: the free gel's volume fraction at T_f.
  double phi_f() const;
  /// chi_B (1/K) and chi_A of chi = chi_A + chi_B T: given (set_chi), or steps (1)-(2).
  std::pair<double, double> chi_line() const;
  /// Take chi(T) = chi_A + chi_B T as given, and phi_i and alpha0 from it: the free gel's volume
  /// fractions at T_i and T_f (Eq. 4.7 inverted). Throws InputError where chi(T) has no
  /// free-swelling state. Call after n, T_i and T_f are set.
  void set_chi(double chi_A, double chi_B);
  /// The limit of a fiber of no thickness through the cell (L = l, D/d -> infinity): the
  /// transverse contraction ratio of the uniaxially constrained gel without prestrain (Eq. 4.14,
  /// phi_i = phi'_i = phi_c), from the theory library.
  double uniaxial_alpha_perp() const;

private:
  std::optional<std::pair<double, double>> _given_chi; ///< {chi_B, chi_A}, when set_chi gave it
};

/// Contraction ratios of the cell: deformed over reference edge length (Eq. 4.21: the lattice
/// vectors' stretches), x and y across the fiber, z along it.
struct CellContraction
{
  double alpha_x = 1, alpha_y = 1, alpha_z = 1;
  /// Largest |off-diagonal macro displacement| over the cell size (full cell; 0 for the 1/8
  /// cell, whose mirror planes exclude shear): zero by the cell's symmetry.
  double shear = 0;
};

class FiberGelCell
{
public:
  /// @param order displacement degree, 1 or 2
  FiberGelCell(MPI_Comm comm, const FiberCellGeometry& geometry, const GelContraction& gel,
               int order);

  /// The constrained equilibrium problem for NewtonSolver / LoadStepper.
  NonlinearSystem& system() { return *_mpc; }
  /// chi = chi_A + chi_B T at temperature T (K).
  void set_temperature(double T);
  /// The cell's contraction ratios at the current state. Collective.
  CellContraction contraction() const;

  const TaggedMesh& mesh() const { return _mesh; }
  std::shared_ptr<const dolfinx::fem::Function<double>> displacement() const { return _u; }
  /// Cauchy stress (MPa) expression, for gelx::CellField (von Mises: Fig. 4.8).
  std::shared_ptr<const dolfinx::fem::Expression<double>> stress() const { return _stress; }
  /// The gel's free energy density per cell (gelx::CellField)
  std::shared_ptr<const dolfinx::fem::Expression<double>> energy_density() const
  {
    return _energy_density;
  }
  /// Smallest J - phi0 over the quadrature points (the gel's admissibility). Collective.
  double admissibility_margin() const { return _problem->admissibility_margin(); }
  std::int64_t num_dofs() const;

private:
  /// The 1/8 cell: rollers on the mirror planes, the outer faces plane with a free macro
  /// normal displacement each (what periodicity reduces to for this symmetric cell).
  void constrain_eighth();
  /// The full cell: Eq. 4.21 on each pair of opposite faces, the jump u(r + c) - u(r) a free
  /// macro vector per pair (nine unknowns).
  void constrain_periodic();

  FiberCellGeometry _g;
  TaggedMesh _mesh;
  std::shared_ptr<dolfinx::fem::Function<double>> _u;
  /// The forms' constants by name (T changes with the load)
  std::map<std::string, std::shared_ptr<dolfinx::fem::Constant<double>>> _constants;
  std::unique_ptr<DirichletConditions> _bcs;
  std::unique_ptr<NonlinearProblem> _problem;
  std::unique_ptr<MultipointConstraint> _mpc;
  /// Macro unknowns: _macro[i][j] the jump of u_i across the cell along axis j (-1: none)
  std::array<std::array<int, 3>, 3> _macro;
  std::shared_ptr<const dolfinx::fem::Expression<double>> _stress, _energy_density;
};

} // namespace gelx::scenes
