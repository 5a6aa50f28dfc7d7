#include <gelx/systems/constraints.h>
#include <gelx/common/collectives.h>
#include <gelx/common/petsc_utils.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <dolfinx/common/MPI.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/DofMap.h>
#include <functional>
#include <map>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace gelx
{

namespace
{
/// Throw, on every rank, the error of the lowest rank that has one (an empty string: none).
/// Builders detect bad input locally after their collective calls; this keeps every rank in
/// step instead of leaving the others waiting in the next collective.
void throw_if_any(MPI_Comm comm, const std::string& error)
{
  int first = error.empty() ? INT_MAX : dolfinx::MPI::rank(comm);
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == INT_MAX)
    return;
  std::string message = error;
  int length = message.size();
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  message.resize(length);
  MPI_Bcast(message.data(), length, MPI_CHAR, first, comm);
  throw std::runtime_error(message);
}

std::string point(const double* X)
{
  std::ostringstream s;
  s << "(" << X[0] << ", " << X[1] << ", " << X[2] << ")";
  return s.str();
}

/// Macro unknown k as a master index: negative, so it never collides with a dof.
std::int64_t encode_macro(int k) { return -(k + 1); }
bool is_macro(std::int64_t master) { return master < 0; }
int decode_macro(std::int64_t master) { return int(-master - 1); }
} // namespace

MultipointConstraint::MultipointConstraint(
    NonlinearProblem& problem, std::shared_ptr<const dolfinx::fem::FunctionSpace> displacement)
    : _problem(problem), _comm(problem.u()->function_space()->mesh()->comm())
{
  const auto& W = *problem.u()->function_space();
  const auto& map = *W.dofmap()->index_map;
  const int bs = W.dofmap()->index_map_bs();
  _num_owned = map.size_local() * bs;
  PetscInt first;
  GELX_PETSC(VecGetOwnershipRange(problem.unknowns(), &first, nullptr));
  _first_dof = first;

  _V0 = displacement;
  if (!displacement->component().empty())
  {
    auto [collapsed, to_problem] = displacement->collapse();
    _V0 = std::make_shared<dolfinx::fem::FunctionSpace>(std::move(collapsed));
    _to_problem = std::move(to_problem);
  }
  if (_V0->dofmap()->index_map_bs() != 3)
    throw std::runtime_error("MultipointConstraint needs a 3-D vector displacement space");

  _is_dirichlet.assign((map.size_local() + map.num_ghosts()) * bs, 0);
  for (const auto& bc : problem.bcs())
    for (std::int32_t dof : bc->dof_indices().first)
      _is_dirichlet[dof] = 1;
}

MultipointConstraint::~MultipointConstraint()
{
  MatDestroy(&_P);
  MatDestroy(&_K);
  VecDestroy(&_g);
  VecDestroy(&_x);
  VecDestroy(&_full);
}

std::int64_t MultipointConstraint::global_dof(std::int32_t local) const
{
  if (local < _num_owned)
    return _first_dof + local;
  const auto& W = *_problem.u()->function_space();
  const int bs = W.dofmap()->index_map_bs();
  const std::int32_t block = local / bs;
  std::int64_t global_block;
  W.dofmap()->index_map->local_to_global(std::span(&block, 1), std::span(&global_block, 1));
  return global_block * bs + local % bs;
}

std::int32_t MultipointConstraint::problem_dof(std::int32_t node, int c) const
{
  const std::int32_t i = 3 * node + c;
  return _to_problem.empty() ? i : _to_problem[i];
}

std::vector<std::int32_t>
MultipointConstraint::owned_face_nodes(const dolfinx::mesh::MeshTags<std::int32_t>& facets,
                                       int tag) const
{
  const int fdim = _V0->mesh()->topology().dim() - 1;
  // remote = true: a rank also finds its dofs on facets that only a neighbour has tagged
  std::vector<std::int32_t> nodes
      = dolfinx::fem::locate_dofs_topological(*_V0, fdim, facets.find(tag), true);
  std::erase_if(nodes, [&](std::int32_t n) { return problem_dof(n, 0) >= _num_owned; });
  return nodes;
}

// --- Macro unknowns ----------------------------------------------------------------------

int MultipointConstraint::add_macro()
{
  if (_finalized)
    throw std::runtime_error("MultipointConstraint: add_macro after finalize");
  _macros.push_back({});
  return int(_macros.size()) - 1;
}

void MultipointConstraint::require_macro(int k) const
{
  if (k < 0 || k >= int(_macros.size()))
    throw std::runtime_error("multipoint constraint: no macro unknown " + std::to_string(k));
}

void MultipointConstraint::prescribe_macro(int k, double value)
{
  require_macro(k);
  _macros[k] = {true, value};
}

void MultipointConstraint::load_macro(int k, double force)
{
  require_macro(k);
  _macros[k] = {false, force};
}

double MultipointConstraint::macro_value(int k) const
{
  require_macro(k);
  require_finalized("macro_value");
  double value = 0;
  if (dolfinx::MPI::rank(_comm) == 0)
    GELX_PETSC(VecGetValues(_x, 1, std::array<PetscInt, 1>{_first_reduced + macro_local_index(k)}
                                       .data(),
                            &value));
  MPI_Bcast(&value, 1, MPI_DOUBLE, 0, _comm);
  return value;
}

double MultipointConstraint::macro_force(int k) const
{
  require_macro(k);
  require_finalized("macro_force");
  Vec f = _problem.create_vector(), reduced = create_vector();
  _problem.internal_forces(f);
  restrict_vector(f, reduced);
  double value = 0;
  if (dolfinx::MPI::rank(_comm) == 0)
    GELX_PETSC(VecGetValues(
        reduced, 1, std::array<PetscInt, 1>{_first_reduced + macro_local_index(k)}.data(), &value));
  VecDestroy(&f);
  VecDestroy(&reduced);
  MPI_Bcast(&value, 1, MPI_DOUBLE, 0, _comm);
  return value;
}

// --- Constraints -------------------------------------------------------------------------

std::string MultipointConstraint::try_add(Row row)
{
  std::ostringstream error;
  const std::int64_t local = row.slave - _first_dof;
  if (_finalized)
    error << "constraints added after finalize";
  else if (local < 0 || local >= _num_owned)
    error << "slave dof " << row.slave << " is not owned by this rank";
  else if (_is_dirichlet[local])
    error << "dof " << row.slave << " is both a slave and a Dirichlet dof";
  else if (_slaves.count(row.slave))
    error << "dof " << row.slave << " is already a slave";
  for (const auto& [master, a] : row.terms)
    if (master == row.slave)
      error << "dof " << row.slave << " is its own master";
  if (!error.str().empty())
    return "multipoint constraint: " + error.str();
  _slaves.insert(row.slave);
  _rows.push_back(std::move(row));
  return {};
}

void MultipointConstraint::add_constraint(std::int64_t slave, const std::vector<DofTerm>& dofs,
                                          const std::vector<MacroTerm>& macros, double g)
{
  Row row{slave, {}, g};
  for (const auto& t : dofs)
    row.terms.emplace_back(t.dof, t.coefficient);
  for (const auto& t : macros)
  {
    require_macro(t.macro);
    row.terms.emplace_back(encode_macro(t.macro), t.coefficient);
  }
  if (std::string error = try_add(std::move(row)); !error.empty())
    throw std::runtime_error(error);
}

void MultipointConstraint::periodic(const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags,
                                    int master_tag, int slave_tag, std::array<double, 3> offset,
                                    std::array<int, 3> macros, double tolerance)
{
  for (int k : macros)
    if (k != no_macro)
      require_macro(k);
  const std::vector<double> X = _V0->tabulate_dof_coordinates(false);

  // The master face on every rank: coordinates and the global dofs of its three components
  std::vector<double> local_X;
  std::vector<std::int64_t> local_dofs;
  for (std::int32_t node : owned_face_nodes(facet_tags, master_tag))
    for (int c = 0; c < 3; ++c)
    {
      local_X.push_back(X[3 * node + c]);
      local_dofs.push_back(global_dof(problem_dof(node, c)));
    }
  const std::vector<double> master_X = all_gather(_comm, local_X);
  const std::vector<std::int64_t> master_dofs = all_gather(_comm, local_dofs);
  const std::vector<std::int32_t> slave_nodes = owned_face_nodes(facet_tags, slave_tag);
  const std::size_t num_masters = master_dofs.size() / 3;

  // Lengths within tolerance * (face extent + |offset|) are equal
  double extent = std::hypot(offset[0], offset[1], offset[2]);
  for (int c = 0; c < 3; ++c)
  {
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t i = 0; i < num_masters; ++i)
    {
      lo = std::min(lo, master_X[3 * i + c]);
      hi = std::max(hi, master_X[3 * i + c]);
    }
    extent += num_masters > 0 ? hi - lo : 0;
  }
  const double tol = tolerance * extent;

  // Masters sorted by x, so that each slave looks at a narrow window only
  std::vector<std::size_t> by_x(num_masters);
  std::iota(by_x.begin(), by_x.end(), 0);
  std::sort(by_x.begin(), by_x.end(),
            [&](std::size_t a, std::size_t b) { return master_X[3 * a] < master_X[3 * b]; });
  auto partner = [&](const double* target) -> std::ptrdiff_t
  {
    auto it = std::lower_bound(by_x.begin(), by_x.end(), target[0] - tol,
                               [&](std::size_t i, double x) { return master_X[3 * i] < x; });
    for (; it != by_x.end() && master_X[3 * *it] <= target[0] + tol; ++it)
      if (std::abs(master_X[3 * *it + 1] - target[1]) <= tol
          && std::abs(master_X[3 * *it + 2] - target[2]) <= tol)
        return *it;
    return -1;
  };

  std::string error;
  for (std::int32_t node : slave_nodes)
  {
    const double* Xs = &X[3 * node];
    const std::array<double, 3> target = {Xs[0] - offset[0], Xs[1] - offset[1], Xs[2] - offset[2]};
    const std::ptrdiff_t m = partner(target.data());
    if (m < 0)
    {
      error = "periodic: the node at " + point(Xs) + " on face " + std::to_string(slave_tag)
              + " has no partner at " + point(target.data()) + " on face "
              + std::to_string(master_tag);
      break;
    }
    for (int c = 0; c < 3 && error.empty(); ++c)
    {
      Row row{global_dof(problem_dof(node, c)), {{master_dofs[3 * m + c], 1.0}}, 0.0};
      if (_slaves.count(row.slave))
        continue; // an edge or corner of an earlier pair (see the header)
      if (macros[c] != no_macro)
        row.terms.emplace_back(encode_macro(macros[c]), 1.0);
      error = try_add(std::move(row));
    }
    if (!error.empty())
      break;
  }
  throw_if_any(_comm, error);
}

void MultipointConstraint::normal_constraint(
    const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags, int tag, std::array<double, 3> n,
    int macro)
{
  const double length = std::hypot(n[0], n[1], n[2]);
  if (!(length > 0))
    throw std::runtime_error("multipoint constraint: the face normal is zero");
  if (macro != no_macro)
    require_macro(macro);
  for (double& c : n)
    c /= length;

  std::string error;
  for (std::int32_t node : owned_face_nodes(facet_tags, tag))
  {
    std::array<std::int64_t, 3> dofs;
    for (int c = 0; c < 3; ++c)
      dofs[c] = global_dof(problem_dof(node, c));
    // The slave: the free component best aligned with n (the best-conditioned division)
    int k = -1;
    for (int c = 0; c < 3; ++c)
      if (std::abs(n[c]) > 1e-12 && !_is_dirichlet[problem_dof(node, c)]
          && !_slaves.count(dofs[c]) && (k < 0 || std::abs(n[c]) > std::abs(n[k])))
        k = c;
    if (k < 0)
      continue; // implied by the node's Dirichlet values or earlier constraints
    Row row{dofs[k], {}, 0.0};
    for (int j = 0; j < 3; ++j)
      if (j != k && n[j] != 0)
        row.terms.emplace_back(dofs[j], -n[j] / n[k]);
    if (macro != no_macro)
      row.terms.emplace_back(encode_macro(macro), 1 / n[k]);
    if (error = try_add(std::move(row)); !error.empty())
      break;
  }
  throw_if_any(_comm, error);
}

void MultipointConstraint::plane_stays_plane(
    const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags, int tag, std::array<double, 3> normal,
    int macro)
{
  if (macro == no_macro)
    throw std::runtime_error("plane_stays_plane needs a macro unknown (use slip for u.n = 0)");
  normal_constraint(facet_tags, tag, normal, macro);
}

void MultipointConstraint::slip(const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags, int tag,
                                std::array<double, 3> normal)
{
  normal_constraint(facet_tags, tag, normal, no_macro);
}

// --- Finalize ----------------------------------------------------------------------------

std::vector<MultipointConstraint::Row> MultipointConstraint::resolved_rows() const
{
  // Every rank sees every row: a slave may depend on a slave that another rank owns. The
  // constraints live on surfaces, so this is small next to the problem.
  std::vector<std::int64_t> local_ints;
  std::vector<double> local_reals;
  for (const Row& row : _rows)
  {
    local_ints.push_back(row.slave);
    local_ints.push_back(row.terms.size());
    local_reals.push_back(row.g);
    for (const auto& [master, a] : row.terms)
    {
      local_ints.push_back(master);
      local_reals.push_back(a);
    }
  }
  const std::vector<std::int64_t> ints = all_gather(_comm, local_ints);
  const std::vector<double> reals = all_gather(_comm, local_reals);
  std::unordered_map<std::int64_t, Row> all;
  std::vector<char> macro_used(_macros.size(), 0);
  for (std::size_t i = 0, j = 0; i < ints.size();)
  {
    Row row{ints[i], {}, reals[j++]};
    const std::int64_t num_terms = ints[i + 1];
    i += 2;
    for (std::int64_t t = 0; t < num_terms; ++t)
    {
      if (is_macro(ints[i]))
        macro_used[decode_macro(ints[i])] = 1;
      row.terms.emplace_back(ints[i++], reals[j++]);
    }
    all.emplace(row.slave, std::move(row));
  }
  for (std::size_t k = 0; k < _macros.size(); ++k)
    if (!macro_used[k]) // its row and column of P^T K P would be empty
      throw std::runtime_error("multipoint constraint: macro unknown " + std::to_string(k)
                               + " is used by no constraint");

  // Substitute slaves of slaves until only true masters and macros remain
  std::unordered_map<std::int64_t, Row> resolved;
  std::unordered_set<std::int64_t> visiting;
  std::function<const Row&(std::int64_t)> resolve = [&](std::int64_t slave) -> const Row&
  {
    if (auto it = resolved.find(slave); it != resolved.end())
      return it->second;
    if (!visiting.insert(slave).second)
      throw std::runtime_error("multipoint constraint: the constraints of dof "
                               + std::to_string(slave) + " form a cycle");
    const Row& row = all.at(slave);
    std::map<std::int64_t, double> terms;
    double g = row.g;
    for (const auto& [master, a] : row.terms)
    {
      if (is_macro(master) || !all.count(master))
      {
        terms[master] += a;
        continue;
      }
      const Row& sub = resolve(master);
      for (const auto& [m, b] : sub.terms)
        terms[m] += a * b;
      g += a * sub.g;
    }
    visiting.erase(slave);
    Row result{slave, {}, g};
    for (const auto& [m, a] : terms)
      if (a != 0)
        result.terms.emplace_back(m, a);
    return resolved[slave] = std::move(result);
  };
  std::vector<Row> rows;
  std::string error;
  try
  {
    for (const Row& row : _rows)
      rows.push_back(resolve(row.slave));
  }
  catch (const std::runtime_error& e)
  {
    error = e.what();
  }
  throw_if_any(_comm, error);
  std::sort(rows.begin(), rows.end(),
            [](const Row& a, const Row& b) { return a.slave < b.slave; });
  return rows;
}

std::vector<std::pair<std::int64_t, PetscInt>>
MultipointConstraint::reduced_indices_of_masters(const std::vector<Row>& rows) const
{
  // Each rank knows the reduced index of its own dofs; a PETSc scatter fetches the others'.
  std::vector<std::int64_t> needed;
  for (const Row& row : rows)
    for (const auto& [master, a] : row.terms)
      if (!is_macro(master))
        needed.push_back(master);
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());

  Vec index;
  GELX_PETSC(VecCreateMPI(_comm, _num_owned, PETSC_DETERMINE, &index));
  PetscScalar* values;
  GELX_PETSC(VecGetArray(index, &values));
  std::unordered_set<std::int64_t> slaves;
  for (const Row& row : rows)
    slaves.insert(row.slave);
  for (std::int32_t i = 0, next = 0; i < _num_owned; ++i)
    values[i] = slaves.count(_first_dof + i) ? -1.0 : double(_first_reduced + next++);
  GELX_PETSC(VecRestoreArray(index, &values));

  const std::vector<PetscInt> from(needed.begin(), needed.end());
  IS is;
  Vec fetched;
  VecScatter scatter;
  GELX_PETSC(ISCreateGeneral(PETSC_COMM_SELF, from.size(), from.data(), PETSC_COPY_VALUES, &is));
  GELX_PETSC(VecCreateSeq(PETSC_COMM_SELF, from.size(), &fetched));
  GELX_PETSC(VecScatterCreate(index, is, fetched, nullptr, &scatter));
  GELX_PETSC(VecScatterBegin(scatter, index, fetched, INSERT_VALUES, SCATTER_FORWARD));
  GELX_PETSC(VecScatterEnd(scatter, index, fetched, INSERT_VALUES, SCATTER_FORWARD));
  std::vector<std::pair<std::int64_t, PetscInt>> result;
  const PetscScalar* got;
  GELX_PETSC(VecGetArrayRead(fetched, &got));
  for (std::size_t i = 0; i < needed.size(); ++i)
    result.emplace_back(needed[i], PetscInt(got[i]));
  GELX_PETSC(VecRestoreArrayRead(fetched, &got));
  VecScatterDestroy(&scatter);
  VecDestroy(&fetched);
  ISDestroy(&is);
  VecDestroy(&index);
  for (const auto& [dof, reduced] : result)
    if (reduced < 0) // resolved_rows() leaves no slave as a master
      throw std::logic_error("multipoint constraint: dof " + std::to_string(dof)
                             + " is a slave and a master after resolution");
  return result;
}

void MultipointConstraint::build_prolongation(const std::vector<Row>& rows)
{
  const bool root = dolfinx::MPI::rank(_comm) == 0;
  _num_masters_local = _num_owned - PetscInt(rows.size());
  const PetscInt num_reduced_local = _num_masters_local + (root ? PetscInt(_macros.size()) : 0);
  PetscInt first = 0;
  MPI_Exscan(&num_reduced_local, &first, 1, MPIU_INT, MPI_SUM, _comm);
  _first_reduced = root ? 0 : first;
  PetscInt first_macro = _first_reduced + _num_masters_local;
  MPI_Bcast(&first_macro, 1, MPIU_INT, 0, _comm);

  const auto master_index = reduced_indices_of_masters(rows);
  auto reduced_column = [&](std::int64_t master)
  {
    if (is_macro(master))
      return first_macro + decode_macro(master);
    auto it = std::lower_bound(master_index.begin(), master_index.end(),
                               std::pair<std::int64_t, PetscInt>{master, -1});
    return it->second;
  };

  // Rows of P: the resolved coefficients for a slave, an identity for every other dof
  std::vector<std::vector<std::pair<PetscInt, double>>> entries(_num_owned);
  std::vector<double> g(_num_owned, 0.0);
  std::vector<char> is_slave(_num_owned, 0);
  for (const Row& row : rows)
  {
    const std::int32_t i = row.slave - _first_dof;
    is_slave[i] = 1;
    g[i] = row.g;
    for (const auto& [master, a] : row.terms)
      entries[i].emplace_back(reduced_column(master), a);
  }
  _dirichlet_masters.clear();
  _unknown_of_problem_dof.assign(_num_owned, -1);
  for (std::int32_t i = 0, next = 0; i < _num_owned; ++i)
    if (!is_slave[i])
    {
      if (_is_dirichlet[i])
        _dirichlet_masters.emplace_back(i, next);
      _unknown_of_problem_dof[i] = next;
      entries[i].emplace_back(_first_reduced + next++, 1.0);
    }

  const PetscInt last_reduced = _first_reduced + num_reduced_local;
  std::vector<PetscInt> diagonal_nnz(_num_owned, 0), off_diagonal_nnz(_num_owned, 0);
  for (std::int32_t i = 0; i < _num_owned; ++i)
    for (const auto& [col, a] : entries[i])
      ++(col >= _first_reduced && col < last_reduced ? diagonal_nnz : off_diagonal_nnz)[i];
  GELX_PETSC(MatCreate(_comm, &_P));
  GELX_PETSC(MatSetSizes(_P, _num_owned, num_reduced_local, PETSC_DETERMINE, PETSC_DETERMINE));
  GELX_PETSC(MatSetType(_P, MATAIJ));
  GELX_PETSC(MatSeqAIJSetPreallocation(_P, 0, diagonal_nnz.data()));
  GELX_PETSC(MatMPIAIJSetPreallocation(_P, 0, diagonal_nnz.data(), 0, off_diagonal_nnz.data()));
  for (std::int32_t i = 0; i < _num_owned; ++i)
  {
    const PetscInt row = _first_dof + i;
    for (const auto& [col, a] : entries[i])
      GELX_PETSC(MatSetValues(_P, 1, &row, 1, &col, &a, INSERT_VALUES));
  }
  GELX_PETSC(MatAssemblyBegin(_P, MAT_FINAL_ASSEMBLY));
  GELX_PETSC(MatAssemblyEnd(_P, MAT_FINAL_ASSEMBLY));

  _g = _problem.create_vector();
  _full = _problem.create_vector();
  PetscScalar* values;
  GELX_PETSC(VecGetArray(_g, &values));
  std::copy(g.begin(), g.end(), values);
  GELX_PETSC(VecRestoreArray(_g, &values));

  // The reduced unknowns start from the problem's u at the masters and the macro values
  GELX_PETSC(VecCreateMPI(_comm, num_reduced_local, PETSC_DETERMINE, &_x));
  const auto& u = _problem.u()->x()->array();
  GELX_PETSC(VecGetArray(_x, &values));
  for (std::int32_t i = 0, next = 0; i < _num_owned; ++i)
    if (!is_slave[i])
      values[next++] = u[i];
  if (root)
    for (std::size_t k = 0; k < _macros.size(); ++k)
      values[macro_local_index(k)] = _macros[k].prescribed ? _macros[k].value : 0.0;
  GELX_PETSC(VecRestoreArray(_x, &values));
}

void MultipointConstraint::finalize()
{
  if (_finalized)
    throw std::runtime_error("MultipointConstraint: finalize called twice");
  const std::vector<Row> rows = resolved_rows();
  build_prolongation(rows);
  std::int64_t num_slaves = rows.size();
  MPI_Allreduce(&num_slaves, &_num_slaves, 1, MPI_INT64_T, MPI_SUM, _comm);
  _finalized = true;
  unknowns_changed();
}

void MultipointConstraint::require_finalized(const char* what) const
{
  if (!_finalized)
    throw std::runtime_error(std::string("MultipointConstraint: ") + what
                             + " before finalize()");
}

// --- The reduced system ------------------------------------------------------------------

void MultipointConstraint::unknowns_changed()
{
  require_finalized("unknowns_changed");
  Vec u = _problem.unknowns();
  GELX_PETSC(MatMult(_P, _x, u));
  GELX_PETSC(VecAXPY(u, 1.0, _g));
  _problem.unknowns_changed();
}

void MultipointConstraint::residual(Vec r)
{
  require_finalized("residual");
  _problem.residual(_full);
  GELX_PETSC(MatMultTranspose(_P, _full, r));
  const PetscScalar *R, *x;
  PetscScalar* values;
  GELX_PETSC(VecGetArrayRead(_full, &R));
  GELX_PETSC(VecGetArrayRead(_x, &x));
  GELX_PETSC(VecGetArray(r, &values));
  // A Dirichlet master keeps its lifted row u_D - g_D, not summed with its slaves' rows
  for (const auto& [dof, reduced] : _dirichlet_masters)
    values[reduced] = R[dof];
  if (dolfinx::MPI::rank(_comm) == 0)
    for (std::size_t k = 0; k < _macros.size(); ++k)
    {
      const PetscInt i = macro_local_index(k);
      values[i] = _macros[k].prescribed ? x[i] - _macros[k].value : values[i] - _macros[k].value;
    }
  GELX_PETSC(VecRestoreArray(r, &values));
  GELX_PETSC(VecRestoreArrayRead(_x, &x));
  GELX_PETSC(VecRestoreArrayRead(_full, &R));
}

Mat MultipointConstraint::create_matrix() const
{
  require_finalized("create_matrix");
  if (!_K)
  {
    _K = _problem.create_matrix();
    _problem.tangent(_K); // MatPtAP needs an assembled operator for its symbolic phase
  }
  Mat A;
  GELX_PETSC(MatPtAP(_K, _P, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &A));
  // The identity rows of tangent() must keep the structure that MAT_REUSE_MATRIX fills
  GELX_PETSC(MatSetOption(A, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));
  return A;
}

Mat MultipointConstraint::restrict_operator(Mat A) const
{
  require_finalized("restrict_operator");
  Mat reduced;
  GELX_PETSC(MatPtAP(A, _P, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &reduced));
  return reduced;
}

void MultipointConstraint::restrict_vector(Vec f, Vec r) const
{
  require_finalized("restrict_vector");
  GELX_PETSC(MatMultTranspose(_P, f, r));
}

void MultipointConstraint::prolong_vector(Vec x, Vec u) const
{
  require_finalized("prolong_vector");
  GELX_PETSC(MatMult(_P, x, u));
}

std::vector<PetscInt> MultipointConstraint::prescribed_rows() const
{
  require_finalized("prescribed_rows");
  std::vector<PetscInt> rows;
  for (const auto& [dof, reduced] : _dirichlet_masters)
    rows.push_back(reduced);
  if (dolfinx::MPI::rank(_comm) == 0)
    for (std::size_t k = 0; k < _macros.size(); ++k)
      if (_macros[k].prescribed)
        rows.push_back(macro_local_index(k));
  return rows;
}

void MultipointConstraint::tangent(Mat A)
{
  require_finalized("tangent");
  if (!_K)
    throw std::logic_error("MultipointConstraint::tangent needs a matrix from create_matrix()");
  _problem.tangent(_K);
  GELX_PETSC(MatPtAP(_K, _P, MAT_REUSE_MATRIX, PETSC_DEFAULT, &A));
  std::vector<PetscInt> rows = prescribed_rows();
  for (PetscInt& row : rows)
    row += _first_reduced;
  GELX_PETSC(MatZeroRows(A, rows.size(), rows.data(), 1.0, nullptr, nullptr));
}

Vec MultipointConstraint::create_vector() const
{
  require_finalized("create_vector");
  Vec v;
  GELX_PETSC(VecDuplicate(_x, &v));
  return v;
}

} // namespace gelx
