#pragma once
/// @file system.h
/// The interface every solver in gelx drives, and that constraints, contact and continuation
/// decorate.

#include <memory>
#include <petscmat.h>
#include <petscsnes.h>
#include <petscvec.h>
#include <vector>

namespace gelx
{
class NonlinearProblem;

/// A discrete nonlinear system R(x) = 0 with its tangent dR/dx, in the form PETSc's SNES needs.
///
/// The base system is a NonlinearProblem (forms, Dirichlet conditions). Decorators wrap another
/// system and change its unknowns or equations, and compose in this order, innermost first:
///   NonlinearProblem  <  MultipointConstraint (reduced unknowns, macro unknowns)
///                     <  RigidPlaneContact   (active rows)
///                     <  ArcLengthSystem     (one more unknown: the load factor)
/// so that, e.g., contact acts on a constrained cell and continuation on either.
///
/// A system holds a current state. Solvers never evaluate at a vector of their own directly:
/// they set_state(x) first, then ask for residual(), tangent(), admissible(); decorators pass
/// the state inward (MultipointConstraint sets u = P x + g in its problem).
class NonlinearSystem
{
public:
  virtual ~NonlinearSystem() = default;

  /// The current state, in the layout of create_vector(). Decorators and drivers read it;
  /// change it through set_state().
  virtual Vec unknowns() = 0;
  /// Make the owned entries of x (a vector of create_vector()'s layout) the current state.
  void set_state(Vec x)
  {
    if (x != unknowns())
      VecCopy(x, unknowns());
    unknowns_changed();
  }
  /// To be called after the owned entries of unknowns() changed: update what depends on them
  /// (ghost values, the constrained dofs of a reduced space, ...).
  virtual void unknowns_changed() = 0;

  /// Residual at the current state. Rows with a prescribed value (Dirichlet, contact) hold
  /// x_i - g_i.
  virtual void residual(Vec r) = 0;
  /// Tangent dR/dx at the current state (identity in the rows of prescribed values).
  virtual void tangent(Mat A) = 0;
  virtual Vec create_vector() const = 0;
  /// A matrix for tangent(), with its near-nullspace where one is known.
  virtual Mat create_matrix() const = 0;
  /// False when the current state is physically inadmissible (det F <= 0 somewhere).
  virtual bool admissible() const { return true; }
  /// Local indices of the owned rows that prescribe a value (Dirichlet conditions, prescribed
  /// macro unknowns, nodes in contact): their tangent row is the identity.
  virtual std::vector<PetscInt> prescribed_rows() const = 0;

  /// The current state is an accepted iterate or solution: history-dependent equations (the
  /// contact active set) move on to it. Solvers call it once per Newton iteration, at the
  /// state of their last residual evaluation, and after convergence; never at trial states,
  /// so that a rejected trial leaves no trace.
  virtual void commit() {}

  /// History beyond the unknowns that the next step depends on (the contact's committed
  /// active set), as one value per unknown: save_history adds this system's entries to h (a
  /// zeroed vector of create_vector()'s layout), load_history reads them back. A checkpoint
  /// stores h beside the unknowns, so that a restarted path continues exactly where it was.
  /// Decorators with their inner system's layout pass both calls inward.
  virtual void save_history(Vec /*h*/) const {}
  virtual void load_history(Vec /*h*/) {}

  /// After each Newton update (a line-search post-check), move the new iterate x onto the set
  /// where an equation of this system holds exactly, if it has one; returns whether x changed.
  /// ArcLengthSystem puts it back on the arc-length sphere (Crisfield's choice of the load
  /// increment), which the linearised condition of the Newton step misses at second order.
  virtual bool project(Vec /*x*/) { return false; }

  /// Before each Newton update x <- x - y (a line-search pre-check, and the predictor), the
  /// factor y is scaled by: 1 for a plain system. DeflatedSystem returns the factor that
  /// makes y the Newton step of its deflated residual (deflation.h).
  virtual double step_factor(Vec /*x*/, Vec /*y*/) { return 1.0; }

  /// Set up what a solver of this system needs beyond residual and tangent (a shell
  /// preconditioner for a bordered tangent); NewtonSolver calls it before reading its options.
  virtual void configure(SNES) const {}

  /// While `predicting`, residual() and tangent() are those of NewtonSolver's predictor step:
  /// a system whose bounds a VI solver handles (RigidPlaneContact with ContactMethod::vi)
  /// prescribes there the rows that will lie on a bound, at the bound's new value, so that the
  /// bound's increment carries the body with it as a Dirichlet condition's lifting does.
  /// Decorators with such rows override it and pass it inward.
  virtual void set_predicting(bool /*predicting*/) {}

  /// A bilinear operator A of the problem's space (a mass matrix, assembled in the pattern of
  /// problem().create_matrix()) as an operator on this system's unknowns, in the pattern of
  /// create_matrix(): A itself, a new reference, where the unknowns are the problem's dofs
  /// (no copy: a caller that changes the result while it still uses A must duplicate it),
  /// P^T A P on a reduced space (MultipointConstraint). The caller destroys the result.
  /// Layouts with unknowns of their own (the arc-length bordering) have no such operator and
  /// throw. Collective.
  virtual Mat restrict_operator(Mat A) const;
  /// The same for vectors. restrict_vector: a linear form f on the problem's dofs (forces,
  /// the derivative of an objective) as one on this system's unknowns, r = P^T f (a copy where
  /// the unknowns are the problem's dofs). prolong_vector: a vector x of this system's
  /// unknowns (a direction, an adjoint solution) as one on the problem's dofs, u = P x, without
  /// the constant g of the constraints. Layouts with unknowns of their own throw, as for
  /// restrict_operator. f and u are in the layout of problem().create_vector(), r and x in that
  /// of create_vector(). Collective.
  virtual void restrict_vector(Vec f, Vec r) const;
  virtual void prolong_vector(Vec x, Vec u) const;

  /// The base problem: its mesh, displacement and forms (for outputs and for decorators).
  virtual NonlinearProblem& problem() = 0;
  /// For each owned entry of the base problem's vector, its local index in unknowns(), or -1
  /// where it is no unknown of its own (a constrained slave). The identity for the problem.
  virtual const std::vector<PetscInt>& unknown_of_problem_dof() const = 0;
};

/// A system that wraps another of the same layout and changes some of its equations: every
/// call goes to the wrapped system unless the decorator overrides it.
class SystemDecorator : public NonlinearSystem
{
public:
  explicit SystemDecorator(NonlinearSystem& inner) : _inner(inner) {}

  Vec unknowns() override { return _inner.unknowns(); }
  void unknowns_changed() override { _inner.unknowns_changed(); }
  void residual(Vec r) override { _inner.residual(r); }
  void tangent(Mat A) override { _inner.tangent(A); }
  Vec create_vector() const override { return _inner.create_vector(); }
  Mat create_matrix() const override { return _inner.create_matrix(); }
  bool admissible() const override { return _inner.admissible(); }
  std::vector<PetscInt> prescribed_rows() const override { return _inner.prescribed_rows(); }
  void commit() override { _inner.commit(); }
  void save_history(Vec h) const override { _inner.save_history(h); }
  void load_history(Vec h) override { _inner.load_history(h); }
  bool project(Vec x) override { return _inner.project(x); }
  double step_factor(Vec x, Vec y) override { return _inner.step_factor(x, y); }
  void configure(SNES snes) const override { _inner.configure(snes); }
  void set_predicting(bool predicting) override { _inner.set_predicting(predicting); }
  Mat restrict_operator(Mat A) const override { return _inner.restrict_operator(A); }
  void restrict_vector(Vec f, Vec r) const override { _inner.restrict_vector(f, r); }
  void prolong_vector(Vec x, Vec u) const override { _inner.prolong_vector(x, u); }
  NonlinearProblem& problem() override { return _inner.problem(); }
  const std::vector<PetscInt>& unknown_of_problem_dof() const override
  {
    return _inner.unknown_of_problem_dof();
  }

  NonlinearSystem& inner() { return _inner; }

protected:
  NonlinearSystem& _inner;
};

} // namespace gelx
