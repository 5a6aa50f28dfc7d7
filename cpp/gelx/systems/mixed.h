#pragma once
/// @file mixed.h
/// Helpers for mixed displacement-pressure spaces (Taylor-Hood u-p, the analogue of ABAQUS
/// hybrid elements): one field of a mixed function as a plain function, and boundary reactions
/// when the displacement is a sub-space.

#include <gelx/systems/problem.h>
#include <array>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/MeshTags.h>
#include <memory>
#include <petscpc.h>

namespace gelx
{

/// Sub-function `i` of a mixed function (e.g. the pressure, i = 1, or the displacement,
/// i = 0) copied into a new function on the collapsed sub-space, owned and ghost values.
/// Output (NodalField, XDMF) and interpolation need this form. Not collective.
std::shared_ptr<dolfinx::fem::Function<double>>
collapse_sub_function(const dolfinx::fem::Function<double>& w, int i);

/// Copy the values of sub-function `i` of `w` into `target`, a function on the collapsed
/// sub-space made by collapse_sub_function (cheap refresh after each step).
void copy_sub_function(const dolfinx::fem::Function<double>& w, int i,
                       dolfinx::fem::Function<double>& target);

/// Resultant force of the reactions on the facets tagged `tag` when the displacement is the
/// sub-space `displacement` (W->sub({0})) of the problem's mixed space: the sum of the internal
/// forces at the displacement dofs there, component by component. Collective.
std::array<double, 3>
reaction_force(const NonlinearProblem& problem, const dolfinx::fem::FunctionSpace& displacement,
               const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags, int tag);

/// Define the fields `u` (displacement) and `p` (pressure) of a PCFIELDSPLIT preconditioner
/// of `system`'s tangent, whose base problem lives on a mixed space (sub-space 0 the
/// displacement, 1 the pressure): the index sets of their unknowns in system's layout (through
/// unknown_of_problem_dof, so a constrained space works too), and on `u` the rigid-body modes
/// as its near-nullspace, which PCFIELDSPLIT hands to the displacement block's matrix (GAMG);
/// with -PREFIX_pc_fieldsplit_schur_precondition user, the Schur complement's preconditioner
/// from the problem's schur_preconditioner() form (problem.h), which the PC owns. Unknowns of
/// neither sub-space (a constraint's macro unknowns, an arc-length load factor) belong to `u`.
/// Throws InputError when the space is not mixed. Collective.
void define_displacement_pressure_fields(PC pc, NonlinearSystem& system);

/// After a solver of `system` read its options, what its KSP needs from gelx: if the
/// preconditioner is PCFIELDSPLIT, its fields (define_displacement_pressure_fields), which only
/// the system knows; and a fresh factorisation after a failed one (refactor_after_failure,
/// petsc_utils.h). Every solver of a system calls it: NewtonSolver, TransientProblem,
/// DampedDynamics, InertialDynamics, ArcLengthSystem (on its K) and AdjointGradient.
/// Collective.
void prepare_linear_solver(KSP ksp, NonlinearSystem& system);

} // namespace gelx
