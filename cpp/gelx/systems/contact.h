#pragma once
/// @file contact.h
/// Frictionless, non-adhesive contact of a hyperelastic body with a rigid plane.

#include <gelx/systems/problem.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/MeshTags.h>
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <ufcx.h>
#include <utility>
#include <vector>

namespace gelx
{

/// What the contact looks like at the current state.
struct ContactState
{
  double force = 0;            ///< total contact force on the body, along the plane normal
  std::int64_t active = 0;     ///< nodes in contact (all ranks)
  double max_penetration = 0;  ///< largest distance of a candidate node behind the plane
};

/// How RigidPlaneContact solves the complementarity conditions of its nodes.
enum class ContactMethod
{
  /// gelx's own active set: the rows of the nodes in contact are replaced by u_i = u_i*, so
  /// any Newton solver needs nothing else
  active_set,
  /// PETSc's bound-constrained Newton (SNESVINEWTONRSLS): the plane is a bound on each
  /// candidate's normal displacement, the residual is the wrapped system's, and SNES keeps the
  /// active set (the rows at a bound that the residual pushes into it)
  vi
};

/// The method chosen by `-<prefix>method active_set|vi` (default active_set, see
/// demos/pyramid/README.md for the comparison). Throws InputError for other values.
ContactMethod contact_method_option(const std::string& prefix = "contact_");

/// A system with the unilateral constraint of a rigid plane x_k = position (axis k; the body on
/// the side `side` = +1 or -1 of it), imposed exactly by an active set on the nodes of a
/// candidate surface: a decorator of any NonlinearSystem whose unknowns hold the candidates'
/// normal displacement (the problem, or a MultipointConstraint that leaves it free).
///
/// Why an exact active set: the hard case of the pyramid scene is contact that starts at one
/// sharp apex node and grows into a patch with concave edges. A penalty lets the apex sink into
/// the plane by an amount that depends on the penalty and the mesh, and a sharp on/off penalty
/// made Newton cycle between two active sets (shared/NOTES.md); Nitsche's method needs a
/// stabilisation parameter tuned to the crushed tip elements. For a plane normal to an axis the
/// constraint is a bound on one displacement component per node, so it can be imposed exactly:
/// penetration is zero at every node, to round-off.
///
/// Every candidate node i carries the complementarity conditions gap_i >= 0, lambda_i >= 0,
/// gap_i lambda_i = 0, with gap_i = side (X_i + u_i - position) and the contact force
/// lambda_i = side R_i, R the residual of the wrapped system. They are solved by an active set:
/// a free node enters the set when it penetrates (gap_i < 0), a node in the set leaves it when
/// its force turns to tension (lambda_i < 0). The rows of the nodes in the set are replaced by
/// u_i - u_i*, u_i* the displacement that closes the gap (a prescribed row), the others keep
/// R_i, so any Newton solver needs nothing else. The set a residual uses follows from the state
/// and the set committed at the last accepted iterate (commit()); a trial state of a line search
/// changes nothing. A converged state has no penetration at any node and no tension in the
/// patch. c_i, the tangent's diagonal, turns gaps into forces for the contact level set.
///
/// With ContactMethod::vi the same conditions are a bound on the candidates' normal
/// displacement, u_k <= position - X_k (side -1) or u_k >= position - X_k (side +1), handed to
/// PETSc's SNESVINEWTONRSLS in configure(); residual and tangent are the wrapped system's, and
/// lambda_i = side R_i is still the force (zero at a converged free node, the bound's reaction
/// at a node held by it). The bounds are vectors of this system's layout, updated in place by
/// set_position() (SNES keeps a reference to them), so every solve sees the plane where it is.
/// The system must be the one the Newton solver solves (not wrapped by ArcLengthSystem, whose
/// shell tangent SNES cannot restrict to the inactive rows).
class RigidPlaneContact : public SystemDecorator
{
public:
  /// @param inner the system without the plane
  /// @param displacement the displacement space: the problem's space, or its sub-space
  ///        W->sub({0}) for a mixed displacement-pressure formulation
  /// @param facet_tags, tag the candidate surface
  /// @param axis, side the plane's normal axis and the side of the plane the body is on
  /// @param method how the complementarity conditions are solved
  RigidPlaneContact(NonlinearSystem& inner,
                    std::shared_ptr<const dolfinx::fem::FunctionSpace> displacement,
                    const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags, int tag, int axis,
                    int side, ContactMethod method = ContactMethod::active_set);
  ~RigidPlaneContact() override;
  RigidPlaneContact(const RigidPlaneContact&) = delete;
  RigidPlaneContact& operator=(const RigidPlaneContact&) = delete;

  /// Move the plane to x_axis = position (with ContactMethod::vi: and the bounds with it).
  void set_position(double position);
  double position() const { return _position; }

  void residual(Vec r) override;
  void tangent(Mat A) override;
  /// The wrapped system's prescribed rows and those of the nodes in contact (where their rows
  /// are replaced: not while a VI solver holds them at their bound).
  std::vector<PetscInt> prescribed_rows() const override;
  /// Accept the active set of the last residual evaluation.
  void commit() override;
  /// The committed active set: 1 in the normal row of a node in contact (and the wrapped
  /// system's history)
  void save_history(Vec h) const override;
  void load_history(Vec h) override;
  /// With ContactMethod::vi, the predictor is the active set's (NonlinearSystem::set_predicting):
  /// the nodes in contact at the last solution and those behind the moved plane are prescribed
  /// onto it. Without it SNES starts from the last solution projected onto the moved plane,
  /// the nodes pressed in without the body behind them (demos/pyramid/README.md measures it).
  void set_predicting(bool predicting) override
  {
    _predicting = predicting;
    _inner.set_predicting(predicting);
  }
  /// With ContactMethod::vi: make the SNES a bound-constrained Newton method
  /// (-PREFIX_snes_type vinewtonrsls unless the user chose another VI type) with the plane's
  /// bounds. Throws InputError for a SNES type that ignores bounds.
  void configure(SNES snes) const override;

  /// Force, active set size and penetration at the current state. Collective.
  ContactState state();

  /// The contact level set on the (collapsed) displacement space, every component equal, at
  /// the state of the last state() call: phi_i = lambda_i / c_i - gap_i at the candidate
  /// nodes, positive in contact (where the node's force, as a displacement, exceeds its gap)
  /// and negative outside, zero elsewhere. Its interpolant's zero line locates the patch edge
  /// between an active and an inactive node. Collective.
  std::shared_ptr<const dolfinx::fem::Function<double>> contact_level_set();

  /// The contact state at the candidates that are mesh vertices, as scalar nodal fields for
  /// fields.xdmf (ABAQUS's CSTATUS, COPEN and CNORMF): `contact_status` (1 in contact, 0
  /// free), `contact_gap` (distance to the plane) and `contact_force` (lambda, the node's
  /// share of the force), zero away from the candidates, at the state of the last state()
  /// call.
  std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>> state_fields() const
  {
    return {_status, _gap, _force};
  }

  /// The contact-area functional `form` of forms/_contact.py (generated as contact_area in
  /// contact.py, contact_hex.py) on the candidate surface: the current area where the level set
  /// is positive, without the O(h) steps of counting whole facets. `u` is the displacement as
  /// a plain function on the collapsed displacement space (refreshed by the caller). Assemble
  /// it after state() and contact_level_set().
  std::shared_ptr<dolfinx::fem::Form<double>>
  area_form(const ufcx_form& form, std::shared_ptr<const dolfinx::fem::Function<double>> u) const;

  /// The candidate nodes owned by this rank at the state of the last state() call: for
  /// contact widths and patch maps.
  struct Node
  {
    std::array<double, 3> X; ///< reference position
    std::array<double, 3> x; ///< current position
    double force;            ///< contact force (lambda)
    double level_set;        ///< lambda / c - gap, positive in contact
    bool active;
  };
  std::vector<Node> nodes() const;

  /// A candidate on a line that leaves the patch (a pyramid's edge, the trace of a symmetry
  /// plane): its place along the line (the order of the nodes, e.g. a reference distance), its
  /// current position along it and its level set.
  struct NodeOnLine
  {
    double place, position, level_set;
  };
  /// The candidates for which `locate(node)` gives (place, position), gathered on every rank
  /// and sorted by place: the input of patch_edge_by_level_set and patch_edge_by_gap_law.
  /// Collective.
  std::vector<NodeOnLine> nodes_on_line(
      const std::function<std::optional<std::pair<double, double>>(const Node&)>& locate) const;

private:
  /// Whether the candidates' rows are replaced in contact (the active set method, and the
  /// predictor of the VI method)
  bool rows_replaced() const { return _method == ContactMethod::active_set || _predicting; }
  /// The contact forces lambda and the active set at the current state, from the wrapped
  /// system's residual R and the committed set (into _lambda, _trial).
  void trial_active_set(Vec inner_residual);
  /// Fill state_fields() at the current state. Collective.
  void update_state_fields();

  int _axis, _side;
  ContactMethod _method;
  /// ContactMethod::vi: the bounds of the unknowns (-/+ infinity except at the candidates)
  Vec _lower = nullptr, _upper = nullptr;
  /// ContactMethod::vi: configure() handed the bounds to a solver
  mutable bool _bounds_in_use = false;
  bool _predicting = false;
  double _position = 0;
  /// Candidate nodes owned by this rank: the normal component's index in the unknowns and in
  /// the problem's vector, the problem dofs of all three components, the reference coordinates
  std::vector<std::int32_t> _row, _dof;
  std::vector<std::array<std::int32_t, 3>> _node_dofs;
  std::vector<std::array<double, 3>> _X;
  std::vector<std::int32_t> _node;   ///< the candidate's node in the displacement space
  std::vector<double> _scale;        ///< c_i
  double _release_gap = 0;           ///< round-off of lengths (see trial_active_set)
  std::vector<double> _lambda;       ///< contact force per candidate
  std::vector<char> _active;         ///< the committed active set
  std::vector<char> _trial;          ///< the set of the last residual evaluation
  PetscInt _first_row = 0; ///< global index of the first owned row
  std::shared_ptr<dolfinx::fem::Function<double>> _level_set;
  /// state_fields(), on vertex values, and each candidate's vertex there (-1: not a vertex)
  std::shared_ptr<dolfinx::fem::Function<double>> _status, _gap, _force;
  std::vector<std::int32_t> _vertex;
  /// The candidate facets, tagged 1 (the area form's ds(1))
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> _surface;
};

/// The patch's edge along a line of candidates (RigidPlaneContact::nodes_on_line, from inside
/// the patch outward): where the level set changes sign, linear between the last node in
/// contact and the first free one. Within one node spacing of the edge, biased by a fraction of
/// it (the force of one node against the gap of the next), so it converges like the spacing.
/// 0 without a node in contact.
double patch_edge_by_level_set(const std::vector<RigidPlaneContact::NodeOnLine>& line);

/// The patch's edge along a line of candidates from the gaps g1 < g2 of the first two free
/// nodes s1 < s2, assuming the gap opens like (s - s_edge)^(3/2) beyond the edge, as outside
/// the contact of smooth bodies (Hertz; Johnson, Contact Mechanics, Sec. 4.2): with
/// r = (g1/g2)^(2/3), s_edge = (s1 - r s2)/(1 - r), kept between the last node in contact and
/// s1. Why: the gap's shape does not depend on the node spacing, so the edge is located inside
/// the element (tests/contact_hertz.cpp, three meshes: +0.9 to +1.7 % from Hertz's radius,
/// where the level set's edge is -0.6 to +2.8 % off). Where no two free nodes have opening
/// gaps: patch_edge_by_level_set's edge.
double patch_edge_by_gap_law(const std::vector<RigidPlaneContact::NodeOnLine>& line);

} // namespace gelx
