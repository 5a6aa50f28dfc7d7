#pragma once
/// @file fiber_gel_cell.h
/// A gel reinforced by a periodic array of rigid fibers, contracting as the temperature rises
/// (thesis section 4.4): the unit cell of fiber_cell_mesh.h, the Flory-Rehner gel of Eq. 4.28
/// in its swollen reference state (forms/fiber_gel.py = forms/gel.py), the fiber surface
/// clamped (the fiber is rigid and, by symmetry, does not move) and the cell faces held by
/// multipoint constraints with free macro unknowns (gelx::MultipointConstraint): no load on
/// them, i.e. zero macro stress.

#include "fiber_cell_mesh.h"
#include "gel_contraction.h"

#include <array>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Function.h>
#include <gelx/systems/boundary.h>
#include <gelx/systems/constraints.h>
#include <gelx/systems/problem.h>
#include <map>
#include <memory>
#include <string>
#include <utility>

namespace gelx::scenes
{

/// Contraction ratios of the cell: deformed over reference edge length (Eq. 4.21: the lattice
/// vectors' stretches), x and y across the fiber, z along it (alpha_x NaN in a film, whose
/// surface x = D/2 is free).
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
  /// normal displacement each (what periodicity reduces to for this symmetric cell); in a
  /// film, the face x = D/2 free (its surface), the fibers of its further layers translating
  /// along x at a free macro displacement each.
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
