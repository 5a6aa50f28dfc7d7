#include "support.h"

#include <cmath>
#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <dolfinx/common/log.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/mesh/generation.h>
#include <dolfinx/mesh/utils.h>
#include <numeric>
#include <xtensor/xview.hpp>

namespace gelx::test
{

TaggedBox tagged_box(MPI_Comm comm, std::array<double, 3> L, std::array<std::size_t, 3> n)
{
  return tagged_box(comm, L, n, dolfinx::mesh::CellType::tetrahedron);
}

TaggedBox tagged_box(MPI_Comm comm, std::array<double, 3> L, std::array<std::size_t, 3> n,
                     dolfinx::mesh::CellType cell)
{
  auto mesh = std::make_shared<dolfinx::mesh::Mesh>(dolfinx::mesh::create_box(
      comm, {{{0, 0, 0}, {L[0], L[1], L[2]}}}, n, cell, dolfinx::mesh::GhostMode::shared_facet));
  const int fdim = 2;
  mesh->topology_mutable().create_entities(fdim);
  mesh->topology_mutable().create_connectivity(fdim, 3);
  std::vector<std::pair<std::int32_t, std::int32_t>> tagged;
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int side = 0; side < 2; ++side)
    {
      const double plane = side * L[axis], tol = 1e-10 * L[axis];
      auto facets = dolfinx::mesh::locate_entities_boundary(
          *mesh, fdim,
          [&](const xt::xtensor<double, 2>& x) -> xt::xtensor<bool, 1>
          { return xt::abs(xt::row(x, axis) - plane) < tol; });
      for (auto f : facets)
        tagged.push_back({f, 2 * axis + side + 1});
    }
  }
  std::sort(tagged.begin(), tagged.end()); // a boundary triangle lies on exactly one face
  std::vector<std::int32_t> indices, values;
  for (auto [f, tag] : tagged)
  {
    indices.push_back(f);
    values.push_back(tag);
  }
  auto tags = std::make_shared<dolfinx::mesh::MeshTags<std::int32_t>>(
      mesh, fdim, std::move(indices), std::move(values));
  return {mesh, tags};
}

std::pair<double, double> component_range(const dolfinx::fem::Function<double>& u,
                                          const dolfinx::mesh::MeshTags<std::int32_t>& facets,
                                          int tag, int c)
{
  const auto& V = *u.function_space();
  const int bs = V.dofmap()->index_map_bs();
  const auto nodes = dolfinx::fem::locate_dofs_topological(V, 2, facets.find(tag));
  double lo = INFINITY, hi = -INFINITY;
  for (std::int32_t node : nodes)
  {
    lo = std::min(lo, u.x()->array()[bs * node + c]);
    hi = std::max(hi, u.x()->array()[bs * node + c]);
  }
  MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_DOUBLE, MPI_MIN, V.mesh()->comm());
  MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_DOUBLE, MPI_MAX, V.mesh()->comm());
  return {lo, hi};
}

Checks::Checks(MPI_Comm comm) : _root(dolfinx::MPI::rank(comm) == 0)
{
  // dolfinx logs at INFO level by default; the checks are what a test run should show
  loguru::g_stderr_verbosity = loguru::Verbosity_WARNING;
}

void Checks::require(const std::string& what, bool ok)
{
  ok ? ++_passed : ++_failed;
  if (_root)
    std::printf("%s  %s\n", ok ? "PASS" : "FAIL", what.c_str());
}

void Checks::relative(const std::string& what, double value, double reference, double tol)
{
  const double err = std::abs(value - reference) / std::abs(reference);
  char line[512];
  std::snprintf(line, sizeof line, "%s: %.12g (reference %.12g, relative error %.2e, tol %.1e)",
                what.c_str(), value, reference, err, tol);
  require(line, err <= tol);
}

void Checks::absolute(const std::string& what, double value, double reference, double tol)
{
  const double err = std::abs(value - reference);
  char line[512];
  std::snprintf(line, sizeof line, "%s: %.12g (reference %.12g, error %.2e, tol %.1e)",
                what.c_str(), value, reference, err, tol);
  require(line, err <= tol);
}

int Checks::finish() const
{
  if (_root)
    std::printf("%d passed, %d failed\n", _passed, _failed);
  return _failed > 0 ? 1 : 0;
}

} // namespace gelx::test
