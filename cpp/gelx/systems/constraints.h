#pragma once
/// @file constraints.h
/// Multipoint constraints u_s = sum_m alpha_m u_m + sum_k beta_k U_k + g between the degrees of
/// freedom of a problem, with macro ("dummy node") unknowns U_k: periodic cells (thesis
/// Eq. 4.21-4.22), faces that stay plane, slip on inclined planes.

#include <gelx/systems/problem.h>
#include <array>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/MeshTags.h>
#include <memory>
#include <petscmat.h>
#include <petscvec.h>
#include <string>
#include <unordered_set>
#include <vector>

namespace gelx
{

/// The equilibrium problem restricted to the displacements that satisfy a set of linear
/// constraints, solved in a reduced space.
///
/// Every constraint makes one degree of freedom of the problem, the slave u_s, a linear
/// combination of other degrees of freedom (masters), of macro unknowns and of a constant:
///   u_s = sum_m alpha_m u_m + sum_k beta_k U_k + g.
/// The unknowns of the reduced space u_r are the dofs that are no slave and the macro unknowns
/// (owned by rank 0, after its dofs); the full vector is u = P u_r + g with the prolongation P,
/// a parallel AIJ matrix (rows: the problem's owned dofs, columns: the owned reduced unknowns;
/// an identity row for each master, the resolved coefficients for each slave). Slaves of
/// slaves are resolved transitively when the constraints are finalised, so a periodic edge or
/// corner depends on true masters only; a cycle is an error. The reduced equations are the
/// principle of virtual work restricted to u = P u_r + g:
///   P^T R(P u_r + g) - f_macro = 0,   tangent P^T K P (PETSc MatPtAP),
/// so a macro unknown is a generalised displacement whose conjugate force is the sum of the
/// forces on its slaves: a free macro unknown with no load means zero macro force (e.g. zero
/// mean stress across a periodic cell, Eq. 4.22), a load on it is a macro force, and a
/// prescribed value is a Dirichlet condition on it.
///
/// Why a reduced space: the constraints hold exactly at every iterate, because unknowns_changed()
/// sets u = P u_r + g before the problem's residual and tangent are assembled (other MPC
/// libraries assemble at iterates that violate them); the problem's assembly is untouched, so
/// every form, mixed spaces and degree 2 work as they are; the cost is one sparse triple
/// product per tangent (MatPtAP, its symbolic part done once) and one MatMultTranspose per
/// residual. Measured on a P2 periodic cell (tests/mpc_homogeneous_cell.cpp, 6591 dofs): the
/// reduced assembly is within the timing noise of the plain one (0.9-1.5 times on shared
/// cores); the direct solve takes 1.3-2.7 times longer, because a periodic cell's LU factors
/// fill in more (1.5-1.8 times the entries), not because of the reduction.
///
/// Dirichlet conditions of the wrapped problem: a Dirichlet dof may be a master (e.g. a pinned
/// corner of a periodic cell), never a slave (add_constraint throws; the builders choose other
/// slaves or skip, see below). Its reduced row is the problem's lifted row u_D - g_D (identity
/// in the tangent), while its reduced column keeps the coupling through the slaves that depend
/// on it, so the first Newton correction after a change of g_D is still a linear predictor.
/// Prescribed macro unknowns work the same way.
///
/// Usage: build the constraints (every builder is collective, add_constraint is not), then
/// finalize(), then give this object to NewtonSolver / LoadStepper in place of the problem.
/// The problem's Function u() always holds the full, constraint-consistent displacement.
/// Without a near-nullspace on the reduced tangent, GAMG is weaker than on the plain problem;
/// the default direct solve is unaffected.
class MultipointConstraint : public NonlinearSystem
{
public:
  /// A master dof (global index of the problem's vector) and its coefficient.
  struct DofTerm
  {
    std::int64_t dof;
    double coefficient;
  };
  /// A macro unknown (index from add_macro) and its coefficient.
  struct MacroTerm
  {
    int macro;
    double coefficient;
  };
  /// For periodic(): a component whose jump across the cell is zero (no macro unknown).
  static constexpr int no_macro = -1;

  /// @param problem the unconstrained problem (its Dirichlet conditions stay in force)
  /// @param displacement the displacement space: the problem's (blocked, 3 components) space,
  ///        or its sub-space W->sub({0}) for a mixed displacement-pressure formulation
  MultipointConstraint(NonlinearProblem& problem,
                       std::shared_ptr<const dolfinx::fem::FunctionSpace> displacement);
  ~MultipointConstraint() override;
  MultipointConstraint(const MultipointConstraint&) = delete;
  MultipointConstraint& operator=(const MultipointConstraint&) = delete;

  // --- Macro unknowns. Call the setters with the same arguments on every rank.

  /// A new macro unknown, free and unloaded, initially zero; returns its index.
  int add_macro();
  /// Prescribe U_k = value (a Dirichlet condition on the macro unknown; may change between
  /// load steps).
  void prescribe_macro(int k, double value);
  /// Free U_k with the conjugate force `force` on it (0: zero macro force).
  void load_macro(int k, double force);
  /// Current value of U_k. Collective.
  double macro_value(int k) const;
  /// The macro force conjugate to U_k at the current state: (P^T f_int)_k, f_int the internal
  /// forces of the problem; the sum of the forces on the slaves of U_k (for a periodic pair,
  /// the resultant of the tractions on the slave face: the first Piola stress times the
  /// reference area). At equilibrium it equals the load on a free U_k, and it is the reaction
  /// of a prescribed one. Collective.
  double macro_force(int k) const;

  // --- Constraints, before finalize().

  /// u_slave = sum dofs + sum macros + g. `slave` and the masters are global indices of the
  /// problem's vector; the slave must be owned by this rank and be neither a Dirichlet dof
  /// nor already a slave (throws std::runtime_error otherwise). Not collective.
  void add_constraint(std::int64_t slave, const std::vector<DofTerm>& dofs,
                      const std::vector<MacroTerm>& macros, double g = 0);

  /// Periodic pair of opposite faces: u(X + offset) = u(X) + U for the nodes X on the face
  /// `master_tag` and X + offset on the face `slave_tag`, component by component, with
  /// U_c the macro unknown macros[c] (or zero for no_macro). Nodes are matched by reference
  /// coordinates within `tolerance` times the cell size, across ranks; a slave-face node
  /// without a partner is an error, and so is a slave-face dof with a Dirichlet condition
  /// (pin the master side). Slave dofs that are constrained already, the edges and corners
  /// shared with an earlier pair, are skipped: the earlier constraint and this pair's chain
  /// through the master face imply this one, and after resolution each edge and corner
  /// depends on the master corner only. Collective.
  void periodic(const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags, int master_tag,
                int slave_tag, std::array<double, 3> offset, std::array<int, 3> macros,
                double tolerance = 1e-8);

  /// "Plane stays plane": u.n = U_macro at every node of the face `tag` (unit normal n), one
  /// macro unknown for the whole face (for symmetry-reduced cells). The slave of a node is
  /// the component with the largest |n_k| among those that are neither Dirichlet dofs nor
  /// slaves already; a node with no such component is skipped, as its other conditions must
  /// then imply this one (an edge with a periodic pair or a clamp). Collective.
  void plane_stays_plane(const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags, int tag,
                         std::array<double, 3> normal, int macro);

  /// Frictionless slip on an inclined plane: u.n = 0 at every node of the face `tag`; slave
  /// choice as plane_stays_plane (with an axis-aligned n, a roller). Collective.
  void slip(const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags, int tag,
            std::array<double, 3> normal);

  /// Resolve the constraints, build P and the reduced unknowns (from the problem's current u
  /// at the masters and the macro values), and make u consistent. Collective.
  void finalize();

  /// Global index, in the problem's vector, of the problem's local dof `local` (owned or ghost).
  std::int64_t global_dof(std::int32_t local) const;
  /// Number of constrained dofs, all ranks (after finalize).
  std::int64_t num_slaves() const { return _num_slaves; }
  /// The prolongation P (after finalize): u = P u_r + g.
  Mat prolongation() const { return _P; }

  // --- NonlinearSystem, on the reduced unknowns u_r.
  Vec unknowns() override { return _x; }
  /// Sets the problem's u = P u_r + g (owned and ghost values).
  void unknowns_changed() override;
  void residual(Vec r) override;
  void tangent(Mat A) override;
  Vec create_vector() const override;
  /// A matrix for tangent(): the symbolic product P^T K P, whose structure every later
  /// tangent() reuses.
  Mat create_matrix() const override;
  bool admissible() const override { return _problem.admissible(); }
  /// P^T A P (PETSc MatPtAP).
  Mat restrict_operator(Mat A) const override;
  /// P^T f and P x.
  void restrict_vector(Vec f, Vec r) const override;
  void prolong_vector(Vec x, Vec u) const override;
  /// The Dirichlet masters and the prescribed macro unknowns.
  std::vector<PetscInt> prescribed_rows() const override;
  NonlinearProblem& problem() override { return _problem; }
  /// The reduced index of each master dof, -1 for a slave (after finalize).
  const std::vector<PetscInt>& unknown_of_problem_dof() const override
  {
    return _unknown_of_problem_dof;
  }

private:
  /// One constraint row: slave, masters (macro k encoded as -(k + 1)), constant.
  struct Row
  {
    std::int64_t slave;
    std::vector<std::pair<std::int64_t, double>> terms;
    double g;
  };
  /// The error of adding this row (empty when it was added).
  std::string try_add(Row row);
  /// u.n = U_macro (macro may be no_macro) on a face.
  void normal_constraint(const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags, int tag,
                         std::array<double, 3> normal, int macro);
  /// Owned nodes (of the collapsed displacement space) on the facets tagged `tag`.
  std::vector<std::int32_t> owned_face_nodes(const dolfinx::mesh::MeshTags<std::int32_t>& facets,
                                             int tag) const;
  /// Local index in the problem's vector of component c of displacement node `node`.
  std::int32_t problem_dof(std::int32_t node, int c) const;
  /// Gather all rows to every rank and resolve this rank's slaves down to true masters.
  std::vector<Row> resolved_rows() const;
  void build_prolongation(const std::vector<Row>& rows);
  /// Reduced global index of each dof master of `rows` (which may live on other ranks).
  std::vector<std::pair<std::int64_t, PetscInt>>
  reduced_indices_of_masters(const std::vector<Row>& rows) const;
  void require_finalized(const char* what) const;
  void require_macro(int k) const;
  /// Local index in u_r of macro unknown k (on rank 0, which owns the macro unknowns).
  PetscInt macro_local_index(int k) const { return _num_masters_local + k; }

  NonlinearProblem& _problem;
  MPI_Comm _comm;
  std::shared_ptr<const dolfinx::fem::FunctionSpace> _V0; ///< collapsed displacement space
  std::vector<std::int32_t> _to_problem; ///< collapsed dof -> problem dof (empty: identity)
  std::int32_t _num_owned = 0;           ///< owned dofs of the problem (unrolled)
  std::int64_t _first_dof = 0;           ///< global index of the first owned problem dof
  std::vector<char> _is_dirichlet;       ///< per local problem dof (owned and ghost)

  std::vector<Row> _rows;                   ///< constraints whose slave this rank owns
  std::unordered_set<std::int64_t> _slaves; ///< their slaves
  struct Macro
  {
    bool prescribed = false;
    double value = 0; ///< prescribed value, or the load when free
  };
  std::vector<Macro> _macros;

  bool _finalized = false;
  std::int64_t _num_slaves = 0;
  PetscInt _num_masters_local = 0; ///< owned reduced unknowns that are dofs
  PetscInt _first_reduced = 0;     ///< global index of the first owned reduced unknown
  /// Owned Dirichlet masters: problem local dof and reduced local index
  std::vector<std::pair<std::int32_t, PetscInt>> _dirichlet_masters;
  std::vector<PetscInt> _unknown_of_problem_dof;
  Mat _P = nullptr;
  Vec _g = nullptr;          ///< constant part of u (slave rows), problem layout
  Vec _x = nullptr;          ///< reduced unknowns
  Vec _full = nullptr;       ///< work vector in the problem's layout
  mutable Mat _K = nullptr;  ///< the problem's tangent, the A of P^T A P
};

} // namespace gelx
