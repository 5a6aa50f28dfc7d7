#pragma once
/// @file problem.h
/// The discrete equilibrium problem R(u) = 0 that the Newton solver and the load stepper drive.

#include <gelx/systems/system.h>

#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <array>
#include <dolfinx/mesh/MeshTags.h>
#include <functional>
#include <memory>
#include <petscmat.h>
#include <petscvec.h>
#include <vector>

namespace gelx
{

/// R(u) = 0 from a UFL residual form and its tangent, with Dirichlet conditions u_D = g.
///
/// The residual is lifted: in constrained rows it is u - g, elsewhere R(u) + K (g - u)_D. The
/// first Newton correction after a change of g therefore moves the constrained dofs onto g and
/// spreads that increment through the body with the tangent (a linear predictor), instead of
/// leaving it to a crushed layer of boundary elements; once u_D = g the lifted residual is R(u).
/// The option `-dirichlet_lifting 0` imposes u_D = g on the iterate instead (before each
/// residual), the textbook way, to measure what lifting saves (README.md).
class NonlinearProblem : public NonlinearSystem
{
public:
  using BCs = std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>>;

  /// @param u the unknown Function (coefficient of both forms)
  /// @param residual_form linear form R(u; v)
  /// @param tangent_form bilinear form dR/du
  /// @param bcs Dirichlet conditions on (sub-spaces of) u's space; their current values are
  ///        read at every residual evaluation
  /// @param admissibility optional Expression, at quadrature points, of a quantity that must stay
  ///        positive for the state to be physical: det F for a solid, J - phi0 for a gel whose
  ///        energy has ln(1 - phi0/J). Iterates where it is <= 0 are rejected.
  NonlinearProblem(std::shared_ptr<dolfinx::fem::Function<double>> u,
                   std::shared_ptr<const dolfinx::fem::Form<double>> residual_form,
                   std::shared_ptr<const dolfinx::fem::Form<double>> tangent_form, BCs bcs,
                   std::shared_ptr<const dolfinx::fem::Expression<double>> admissibility = nullptr);
  ~NonlinearProblem() override;
  NonlinearProblem(const NonlinearProblem&) = delete;
  NonlinearProblem& operator=(const NonlinearProblem&) = delete;

  Vec unknowns() override { return _x; }
  void unknowns_changed() override;
  void residual(Vec r) override;
  void tangent(Mat A) override;
  Vec create_vector() const override;
  Mat create_matrix() const override;
  bool admissible() const override;
  std::vector<PetscInt> prescribed_rows() const override;
  NonlinearProblem& problem() override { return *this; }
  const std::vector<PetscInt>& unknown_of_problem_dof() const override { return _identity; }

  /// Smallest value of the admissibility expression over the quadrature points of all cells
  /// (all ranks); +inf without one.
  double admissibility_margin() const;

  /// Internal force vector R(u) without Dirichlet rows zeroed: at equilibrium its entries on
  /// constrained dofs are the reaction forces.
  void internal_forces(Vec f) const;

  /// |R(u)| / |f_int(u)| at the current state, the reactions in f_int: how far the state is
  /// from a static equilibrium, on the scale of the forces it carries. Collective.
  double static_residual();

  std::shared_ptr<dolfinx::fem::Function<double>> u() const { return _u; }
  const BCs& bcs() const { return _bcs; }

  /// For a mixed problem (sub-space 1 a pressure, or a gel's chemical potential): a bilinear
  /// form on its space whose block of sub-space 1 preconditions the Schur complement of the
  /// fieldsplit linear solver (-PREFIX_pc_fieldsplit_schur_precondition user;
  /// define_displacement_pressure_fields, mixed.h): -1/G int p q dX for a nearly
  /// incompressible solid (forms/_mixed.py, pressure_mass), the fixed-stress operator for a
  /// swelling gel (forms/swelling.py). `follows_state`: the form depends on the state or on a
  /// solver's constant (TS's shift), so it is assembled again after every tangent().
  void set_schur_preconditioner(std::shared_ptr<const dolfinx::fem::Form<double>> form,
                                bool follows_state = false)
  {
    _schur_preconditioner = std::move(form);
    _schur_preconditioner_follows_state = follows_state;
  }
  std::shared_ptr<const dolfinx::fem::Form<double>> schur_preconditioner() const
  {
    return _schur_preconditioner;
  }
  bool schur_preconditioner_follows_state() const { return _schur_preconditioner_follows_state; }
  /// Call `update` after every tangent(), at the state the tangent was assembled at, for as
  /// long as it lives (a solver's preconditioner that follows the state: mixed.cpp).
  void after_tangent(std::weak_ptr<std::function<void()>> update)
  {
    _after_tangent.push_back(std::move(update));
  }

private:
  std::shared_ptr<dolfinx::fem::Function<double>> _u;
  std::shared_ptr<const dolfinx::fem::Form<double>> _R, _J, _schur_preconditioner;
  bool _schur_preconditioner_follows_state = false;
  std::vector<std::weak_ptr<std::function<void()>>> _after_tangent;
  BCs _bcs;
  std::shared_ptr<const dolfinx::fem::Expression<double>> _admissibility;
  bool _lifting; ///< -dirichlet_lifting (see the class comment)
  Vec _x = nullptr; // PETSc view of _u's coefficients (shares memory, with ghosts)
  std::vector<PetscInt> _identity; // unknown_of_problem_dof()
};

} // namespace gelx

namespace gelx
{
/// Resultant force and moment (about the origin, on the deformed configuration) of the
/// reactions on the facets tagged `tag`, from the internal forces at constrained dofs.
/// For a plain (blocked) displacement space. Collective.
struct Resultant
{
  std::array<double, 3> force{};
  std::array<double, 3> moment{};
};
/// The value of a functional (a rank-0 form) summed over all ranks. Collective.
double assemble_global_scalar(const dolfinx::fem::Form<double>& M);
/// A linear form's vector: assemble_local_vector into the owned and ghost entries of f (a
/// ghosted vector of the form's space), each rank its own cells; assemble_global_vector then
/// adds the ghost entries to their owners. Collective (the global one).
void assemble_local_vector(const dolfinx::fem::Form<double>& L, Vec f);
void assemble_global_vector(const dolfinx::fem::Form<double>& L, Vec f);

Resultant boundary_resultant(const NonlinearProblem& problem,
                             const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags, int tag);

/// Component `c` of the six rigid-body modes of 3-D space (three translations, three
/// rotations) at the point X: the near-nullspace of elasticity that algebraic multigrid needs.
inline std::array<double, 6> rigid_body_modes_at(const double* X, int c)
{
  const double x = X[0], y = X[1], z = X[2];
  const double modes[6][3]
      = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-y, x, 0}, {z, 0, -x}, {0, -z, y}};
  return {modes[0][c], modes[1][c], modes[2][c], modes[3][c], modes[4][c], modes[5][c]};
}
} // namespace gelx
