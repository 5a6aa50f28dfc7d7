#pragma once
/// @file adjoint.h
/// The gradient of an objective of an equilibrium with respect to design parameters (a
/// prestretch field, material constants as a field), by the adjoint method.

#include <gelx/systems/system.h>

#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <functional>
#include <memory>
#include <petscksp.h>
#include <string>

namespace gelx
{

/// An objective J(u, s) of the equilibrium u and the design s, as generated forms (a form file
/// writes J in UFL and lets ufl.derivative give the rest: forms/design_strip.py).
struct Objective
{
  std::shared_ptr<const dolfinx::fem::Form<double>> value;   ///< J, a functional
  std::shared_ptr<const dolfinx::fem::Form<double>> d_state; ///< dJ/du, on the problem's space
  /// dJ/ds at fixed u, a linear form on the design space; nullptr where J has no explicit s
  std::shared_ptr<const dolfinx::fem::Form<double>> d_design;
  /// A term UFL cannot write, a function of a few sampled nodal values of u (demos/design:
  /// the helix detector's curvature and twist of the centreline), added to the forms': its
  /// value at the system's current state (collective), and its dJ/du added into a vector of
  /// the problem's space (owned entries, collective). Both empty where J has none.
  std::function<double()> sampled_value;
  std::function<void(Vec)> add_sampled_d_state;
};

/// dJ/ds of J(u(s), s), u(s) the equilibrium R(u; s) = 0 of a NonlinearSystem at the design s
/// (a Function, e.g. DG0: one parameter per cell):
///
///   dJ/ds = dJ/ds|_u - lambda^T dR/ds,   K^T lambda = dJ/du^T,
///
/// K the system's tangent at the equilibrium. One linear solve with K^T, whatever the number of
/// design parameters; the direct method (du/ds by K du/ds = -dR/ds) needs one per parameter.
///
/// On a decorated system the equations are those of its unknowns: with a
/// MultipointConstraint, R_r = P^T R(P u_r + g) and dJ/du_r = P^T dJ/du, so the adjoint sees
/// the reduced tangent and dR_r/ds = P^T dR/ds (restrict_vector, prolong_vector). A prescribed
/// row (Dirichlet dof, prescribed macro unknown, contact node) holds u_i = g_i, which does not
/// depend on s: its entry of lambda multiplies nothing and is zeroed before lambda is prolonged
/// (lambda's other entries do not depend on dJ/du's prescribed entries: K's prescribed rows
/// are identity rows).
///
/// Why a tangent and a factorisation of its own (KSP prefix `prefix`, by default a direct
/// solve, MUMPS' transposed solve): NewtonSolver's last factorisation is that of the iterate
/// before the converged one, and the gradient would carry that last Newton step's error; one
/// more factorisation costs about one Newton iteration.
class AdjointGradient
{
public:
  /// @param system the equilibrium problem, possibly decorated; its problem's forms read the
  ///        design Function as a coefficient
  /// @param design the design field s
  /// @param residual_d_design dR/ds: a bilinear form, rows the problem's space, columns the
  ///        design space (ufl.derivative of the residual with a TrialFunction of the design)
  AdjointGradient(NonlinearSystem& system,
                  std::shared_ptr<const dolfinx::fem::Function<double>> design,
                  std::shared_ptr<const dolfinx::fem::Form<double>> residual_d_design,
                  Objective objective, const std::string& prefix = "adjoint_");
  ~AdjointGradient();
  AdjointGradient(const AdjointGradient&) = delete;
  AdjointGradient& operator=(const AdjointGradient&) = delete;

  /// J at the system's current state. Collective.
  double value() const;
  /// dJ/ds at the system's current state, which must be an equilibrium, into g (a vector of
  /// create_design_vector()'s layout: the design space's owned dofs). Collective.
  void gradient(Vec g);
  /// A vector of the design space's layout (ghosted). The caller destroys it.
  Vec create_design_vector() const;
  /// Krylov iterations of the last adjoint solve (1 for the default direct solve).
  int linear_iterations() const { return _iterations; }

private:
  NonlinearSystem& _system;
  std::shared_ptr<const dolfinx::fem::Function<double>> _design;
  std::shared_ptr<const dolfinx::fem::Form<double>> _residual_d_design;
  Objective _objective;
  KSP _ksp = nullptr;
  Mat _tangent = nullptr, _residual_d_design_matrix = nullptr;
  int _iterations = 0;
};

} // namespace gelx
