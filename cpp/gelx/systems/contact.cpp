#include <gelx/systems/contact.h>
#include <gelx/common/collectives.h>
#include <gelx/io/output.h>
#include <gelx/io/parameters.h>
#include <gelx/common/petsc_utils.h>

#include <algorithm>
#include <cmath>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/fem/utils.h>

namespace gelx
{

ContactMethod contact_method_option(const std::string& prefix)
{
  return choice_option(prefix, "method", "active_set", {"active_set", "vi"}) == "vi"
             ? ContactMethod::vi
             : ContactMethod::active_set;
}

RigidPlaneContact::RigidPlaneContact(NonlinearSystem& inner,
                                     std::shared_ptr<const dolfinx::fem::FunctionSpace> displacement,
                                     const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags,
                                     int tag, int axis, int side, ContactMethod method)
    : SystemDecorator(inner), _axis(axis), _side(side), _method(method)
{
  const auto& W = *inner.problem().u()->function_space();
  const std::int32_t num_owned = W.dofmap()->index_map->size_local() * W.dofmap()->index_map_bs();
  // The displacement as a plain vector space V0, and where its dofs sit in the problem's vector
  std::shared_ptr<const dolfinx::fem::FunctionSpace> V0 = displacement;
  std::vector<std::int32_t> to_problem;
  if (!displacement->component().empty())
  {
    auto [collapsed, map] = displacement->collapse();
    V0 = std::make_shared<dolfinx::fem::FunctionSpace>(std::move(collapsed));
    to_problem = std::move(map);
  }
  auto problem_dof = [&](std::int32_t node, int c)
  {
    const std::int32_t i = 3 * node + c;
    return to_problem.empty() ? i : to_problem[i];
  };
  _level_set = std::make_shared<dolfinx::fem::Function<double>>(V0);
  const std::vector<double> X = V0->tabulate_dof_coordinates(false);
  const int fdim = V0->mesh()->topology().dim() - 1;
  const std::vector<PetscInt>& row_of = inner.unknown_of_problem_dof();
  // remote = true: a rank can own a node of the surface without holding any tagged facet
  // through it (its cells touch the node by an edge only); dolfinx then finds it for the owner
  std::string error;
  for (std::int32_t node :
       dolfinx::fem::locate_dofs_topological(*V0, fdim, facet_tags.find(tag), true))
  {
    const std::int32_t dof = problem_dof(node, axis);
    if (dof >= num_owned)
      continue;
    if (row_of[dof] < 0)
      error = "contact: the normal displacement of a candidate node is constrained by a "
              "multipoint constraint (the plane must act on free unknowns)";
    _node.push_back(node);
    _dof.push_back(dof);
    _row.push_back(row_of[dof]);
    _node_dofs.push_back({problem_dof(node, 0), problem_dof(node, 1), problem_dof(node, 2)});
    _X.push_back({X[3 * node], X[3 * node + 1], X[3 * node + 2]});
  }
  // Round-off in lengths: 1e-10 of the body's extent
  double extent = 0;
  for (const auto& X : _X)
    extent = std::max({extent, std::abs(X[0]), std::abs(X[1]), std::abs(X[2])});
  MPI_Allreduce(MPI_IN_PLACE, &extent, 1, MPI_DOUBLE, MPI_MAX, V0->mesh()->comm());
  _release_gap = 1e-10 * extent;
  int failed = !error.empty();
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_LOR, V0->mesh()->comm());
  if (failed)
    throw std::runtime_error(error.empty() ? "contact: constrained candidates on another rank"
                                           : error);
  _lambda.assign(_dof.size(), 0.0);

  // The state fields hold vertex values: a Lagrange element numbers its vertex nodes first in
  // each cell, so a cell's first dofs in V0 and in P1 are the same vertices
  auto P1 = lagrange_space(V0->mesh(), 1, 1);
  const auto V0_nodes = V0->dofmap()->index_map;
  std::vector<std::int32_t> vertex_of_node(V0_nodes->size_local() + V0_nodes->num_ghosts(), -1);
  const auto cells = V0->mesh()->topology().index_map(fdim + 1);
  for (std::int32_t c = 0; c < cells->size_local() + cells->num_ghosts(); ++c)
  {
    const auto vertices = P1->dofmap()->cell_dofs(c);
    const auto nodes = V0->dofmap()->cell_dofs(c);
    for (std::size_t k = 0; k < vertices.size(); ++k)
      vertex_of_node[nodes[k]] = vertices[k];
  }
  for (std::int32_t node : _node)
    _vertex.push_back(vertex_of_node[node]);
  _status = std::make_shared<dolfinx::fem::Function<double>>(P1);
  _gap = std::make_shared<dolfinx::fem::Function<double>>(P1);
  _force = std::make_shared<dolfinx::fem::Function<double>>(P1);
  _status->name = "contact_status";
  _gap->name = "contact_gap";
  _force->name = "contact_force";
  const std::vector<std::int32_t> surface = facet_tags.find(tag);
  _surface = std::make_shared<dolfinx::mesh::MeshTags<std::int32_t>>(
      V0->mesh(), fdim, std::vector<std::int32_t>(surface),
      std::vector<std::int32_t>(surface.size(), 1));
  _active.assign(_dof.size(), 0);
  _trial = _active;

  // c_i: the diagonal of the tangent at the current (reference) state
  Mat A = inner.create_matrix();
  Vec diagonal = inner.create_vector();
  inner.tangent(A);
  GELX_PETSC(MatGetDiagonal(A, diagonal));
  GELX_PETSC(VecGetOwnershipRange(diagonal, &_first_row, nullptr));
  const PetscScalar* d;
  GELX_PETSC(VecGetArrayRead(diagonal, &d));
  for (std::int32_t row : _row)
    _scale.push_back(std::abs(d[row]));
  GELX_PETSC(VecRestoreArrayRead(diagonal, &d));
  VecDestroy(&diagonal);
  MatDestroy(&A);

  if (_method == ContactMethod::vi)
  {
    _lower = inner.create_vector();
    _upper = inner.create_vector();
    GELX_PETSC(VecSet(_lower, PETSC_NINFINITY));
    GELX_PETSC(VecSet(_upper, PETSC_INFINITY));
    set_position(_position);
  }
}

RigidPlaneContact::~RigidPlaneContact()
{
  VecDestroy(&_lower);
  VecDestroy(&_upper);
}

void RigidPlaneContact::set_position(double position)
{
  _position = position;
  if (_method != ContactMethod::vi)
    return;
  // The body on side -1 stays below the plane: an upper bound; on side +1 a lower one. Only
  // owned rows: every candidate here is owned
  PetscScalar* bound;
  Vec bounds = _side < 0 ? _upper : _lower;
  GELX_PETSC(VecGetArray(bounds, &bound));
  for (std::size_t i = 0; i < _row.size(); ++i)
    bound[_row[i]] = position - _X[i][_axis];
  GELX_PETSC(VecRestoreArray(bounds, &bound));
}

void RigidPlaneContact::configure(SNES snes) const
{
  _inner.configure(snes);
  if (_method != ContactMethod::vi)
    return;
  // The type is set here rather than as a default option, which would outlive this system
  // and turn every later solver of that prefix into a VI solver
  const char* prefix;
  GELX_PETSC(SNESGetOptionsPrefix(snes, &prefix));
  const std::string p = prefix ? prefix : "";
  const std::string type = string_option(p, "snes_type", SNESVINEWTONRSLS);
  if (type != SNESVINEWTONRSLS && type != SNESVINEWTONSSLS)
    throw InputError("contact method vi needs a bound-constrained SNES: -" + p
                     + "snes_type vinewtonrsls or vinewtonssls, not " + type);
  GELX_PETSC(SNESSetType(snes, type.c_str()));
  GELX_PETSC(SNESVISetVariableBounds(snes, _lower, _upper));
  _bounds_in_use = true;
}

void RigidPlaneContact::trial_active_set(Vec inner_residual)
{
  const PetscScalar* R;
  GELX_PETSC(VecGetArrayRead(inner_residual, &R));
  const auto& u = _inner.problem().u()->x()->array();
  for (std::size_t i = 0; i < _dof.size(); ++i)
  {
    _lambda[i] = _side * R[_row[i]];
    const double gap = _side * (_X[i][_axis] + u[_dof[i]] - _position);
    if (!rows_replaced())
    {
      // SNES's active set: at the bound, pushed into it
      _trial[i] = gap <= _release_gap && _lambda[i] > 0;
      continue;
    }
    // A free node enters when it penetrates, a node in contact leaves when it is pulled
    // (a force below -c_i _release_gap, beyond round-off). The primal-dual test
    // c gap < lambda also for free nodes reads their out-of-balance force during the
    // iterations as a contact force and activates nodes that do not touch, which then pull
    // and leave again: Newton cycled for 40 iterations at d/H = 0.12 in the pyramid scene.
    _trial[i] = _active[i] ? _lambda[i] > -_scale[i] * _release_gap : gap < 0;
  }
  GELX_PETSC(VecRestoreArrayRead(inner_residual, &R));
}

void RigidPlaneContact::commit()
{
  _inner.commit();
  _active = _trial;
}

void RigidPlaneContact::save_history(Vec h) const
{
  _inner.save_history(h);
  PetscScalar* values;
  GELX_PETSC(VecGetArray(h, &values));
  for (std::size_t i = 0; i < _row.size(); ++i)
    values[_row[i]] = _active[i];
  GELX_PETSC(VecRestoreArray(h, &values));
}

void RigidPlaneContact::load_history(Vec h)
{
  _inner.load_history(h);
  const PetscScalar* values;
  GELX_PETSC(VecGetArrayRead(h, &values));
  for (std::size_t i = 0; i < _row.size(); ++i)
    _active[i] = values[_row[i]] > 0.5;
  GELX_PETSC(VecRestoreArrayRead(h, &values));
  _trial = _active;
}

void RigidPlaneContact::residual(Vec r)
{
  if (_method == ContactMethod::vi && !_bounds_in_use)
    throw std::logic_error("contact: with -contact_method vi the contact system must be the "
                           "one the Newton solver solves (its configure() sets the bounds)");
  _inner.residual(r);
  trial_active_set(r);
  if (!rows_replaced())
    return;
  const auto& u = _inner.problem().u()->x()->array();
  PetscScalar* values;
  GELX_PETSC(VecGetArray(r, &values));
  for (std::size_t i = 0; i < _dof.size(); ++i)
    if (_trial[i])
      values[_row[i]] = u[_dof[i]] - (_position - _X[i][_axis]);
  GELX_PETSC(VecRestoreArray(r, &values));
}

void RigidPlaneContact::tangent(Mat A)
{
  _inner.tangent(A);
  if (!rows_replaced())
    return;
  std::vector<PetscInt> rows;
  for (std::size_t i = 0; i < _dof.size(); ++i)
    if (_trial[i])
      rows.push_back(_first_row + _row[i]);
  // Later assemblies write into these rows again: keep their sparsity
  GELX_PETSC(MatSetOption(A, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));
  GELX_PETSC(MatZeroRows(A, rows.size(), rows.data(), 1.0, nullptr, nullptr));
}

std::vector<PetscInt> RigidPlaneContact::prescribed_rows() const
{
  std::vector<PetscInt> rows = _inner.prescribed_rows();
  for (std::size_t i = 0; rows_replaced() && i < _dof.size(); ++i)
    if (_trial[i])
      rows.push_back(_row[i]);
  std::sort(rows.begin(), rows.end());
  return rows;
}

ContactState RigidPlaneContact::state()
{
  Vec r = _inner.create_vector();
  _inner.residual(r);
  trial_active_set(r);
  VecDestroy(&r);
  const auto& u = _inner.problem().u()->x()->array();
  double sums[2] = {0, 0}, penetration = 0;
  for (std::size_t i = 0; i < _dof.size(); ++i)
  {
    sums[0] += _lambda[i];
    sums[1] += _trial[i];
    penetration
        = std::max(penetration, -_side * (_X[i][_axis] + u[_dof[i]] - _position));
  }
  MPI_Comm comm = _inner.problem().u()->function_space()->mesh()->comm();
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, &penetration, 1, MPI_DOUBLE, MPI_MAX, comm);
  update_state_fields();
  return {sums[0], static_cast<std::int64_t>(sums[1]), penetration};
}

void RigidPlaneContact::update_state_fields()
{
  for (const auto& f : {_status, _gap, _force})
    std::ranges::fill(f->x()->mutable_array(), 0.0);
  auto status = _status->x()->mutable_array(), gap = _gap->x()->mutable_array(),
       force = _force->x()->mutable_array();
  const std::vector<Node> current = nodes();
  for (std::size_t i = 0; i < current.size(); ++i)
  {
    if (const std::int32_t v = _vertex[i]; v >= 0)
    {
      status[v] = current[i].active;
      gap[v] = _side * (current[i].x[_axis] - _position);
      force[v] = current[i].force;
    }
  }
  // A candidate's vertex may be a ghost of P1 on the rank that owns the node: add the values to
  // the owner (every other rank holds 0 there), then copy them back to the ghosts
  for (const auto& f : {_status, _gap, _force})
  {
    f->x()->scatter_rev(std::plus<double>());
    f->x()->scatter_fwd();
  }
}

std::shared_ptr<const dolfinx::fem::Function<double>> RigidPlaneContact::contact_level_set()
{
  auto values = _level_set->x()->mutable_array();
  std::fill(values.begin(), values.end(), 0.0);
  const std::vector<Node> current = nodes();
  for (std::size_t i = 0; i < current.size(); ++i)
    std::fill_n(values.begin() + 3 * _node[i], 3, current[i].level_set);
  _level_set->x()->scatter_fwd();
  return _level_set;
}

std::shared_ptr<dolfinx::fem::Form<double>>
RigidPlaneContact::area_form(const ufcx_form& form,
                             std::shared_ptr<const dolfinx::fem::Function<double>> u) const
{
  std::vector<double> normal(3, 0.0);
  normal[_axis] = 1;
  return std::make_shared<dolfinx::fem::Form<double>>(dolfinx::fem::create_form<double>(
      form, {}, {{"u", u}, {"level_set", _level_set}},
      {{"normal", std::make_shared<dolfinx::fem::Constant<double>>(normal)}},
      {{dolfinx::fem::IntegralType::exterior_facet, _surface.get()}}, u->function_space()->mesh()));
}

std::vector<RigidPlaneContact::Node> RigidPlaneContact::nodes() const
{
  const auto& u = _inner.problem().u()->x()->array();
  std::vector<Node> result;
  for (std::size_t i = 0; i < _dof.size(); ++i)
  {
    Node n{_X[i], _X[i], _lambda[i], 0, bool(_trial[i])};
    for (int c = 0; c < 3; ++c)
      n.x[c] += u[_node_dofs[i][c]];
    const double gap = _side * (n.x[_axis] - _position);
    n.level_set = _lambda[i] / _scale[i] - gap;
    result.push_back(n);
  }
  return result;
}

std::vector<RigidPlaneContact::NodeOnLine> RigidPlaneContact::nodes_on_line(
    const std::function<std::optional<std::pair<double, double>>(const Node&)>& locate) const
{
  std::vector<double> local; // (place, position, level set) per node
  for (const Node& n : nodes())
    if (const auto at = locate(n))
      local.insert(local.end(), {at->first, at->second, n.level_set});
  MPI_Comm comm = _inner.problem().u()->function_space()->mesh()->comm();
  const std::vector<double> all = all_gather(comm, local);
  std::vector<NodeOnLine> line;
  for (std::size_t i = 0; i < all.size(); i += 3)
    line.push_back({all[i], all[i + 1], all[i + 2]});
  std::sort(line.begin(), line.end(),
            [](const NodeOnLine& a, const NodeOnLine& b) { return a.place < b.place; });
  return line;
}

double patch_edge_by_level_set(const std::vector<RigidPlaneContact::NodeOnLine>& line)
{
  double edge = 0;
  for (std::size_t k = 0; k < line.size() && line[k].level_set > 0; ++k)
  {
    edge = line[k].position;
    if (k + 1 < line.size() && line[k + 1].level_set <= 0)
    {
      const double s = line[k].level_set / (line[k].level_set - line[k + 1].level_set);
      edge += s * (line[k + 1].position - line[k].position);
    }
  }
  return edge;
}

double patch_edge_by_gap_law(const std::vector<RigidPlaneContact::NodeOnLine>& line)
{
  std::size_t k = 0; // the first free node
  while (k < line.size() && line[k].level_set > 0)
    ++k;
  const double g1 = k < line.size() ? -line[k].level_set : 0;
  const double g2 = k + 1 < line.size() ? -line[k + 1].level_set : 0;
  if (k == 0 || !(g1 > 0 && g2 > g1)) // no patch, or no opening gap to fit the law to
    return patch_edge_by_level_set(line);
  const double s1 = line[k].position, s2 = line[k + 1].position;
  const double r = std::pow(g1 / g2, 2.0 / 3.0);
  const auto [lo, hi] = std::minmax(line[k - 1].position, s1);
  return std::clamp((s1 - r * s2) / (1 - r), lo, hi);
}

} // namespace gelx
