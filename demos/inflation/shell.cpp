#include "shell.h"
#include "sphere.h"

#include <cmath>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/utils.h>

using namespace dolfinx;

namespace gelx::scenes
{

InflatedShell::InflatedShell(MPI_Comm comm, const std::string& geo_file, ShellParameters p)
    : _p(p), _geo(read_geo(comm, geo_file, {{"A", p.A}, {"B", p.B}, {"h", p.h}}))
{
  auto V = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_sphere_residual, "u", _geo.mesh));
  _u = std::make_shared<fem::Function<double>>(V);
  _u->name = "displacement";
  // ds(1) of the form is the inner surface, physical group "inner" = 1 of the .geo
  _forms = std::make_unique<FormBinding>(_geo.mesh, FormBinding::Coefficients{{"u", _u}},
                                         std::map<std::string, double>{{"G", p.G}, {"K", p.K},
                                                                       {"p", 0.0}});
  _forms->add_subdomains(fem::IntegralType::exterior_facet, _geo.facet_tags);
  _bcs = std::make_unique<DirichletConditions>(V, _geo.facet_tags);
  const std::array<int, 3> planes = {_geo.tag("sym_x"), _geo.tag("sym_y"), _geo.tag("sym_z")};
  if (p.symmetry == "rollers")
    for (int k = 0; k < 3; ++k)
      _bcs->fix(planes[k], k);
  _bcs->update(0);
  _problem = std::make_unique<NonlinearProblem>(
      _u, _forms->form(form_sphere_residual, {V}), _forms->form(form_sphere_tangent, {V, V}),
      _bcs->bcs(), _forms->expression(expression_sphere_det_F));
  if (p.symmetry == "constraints")
  {
    _symmetry = std::make_unique<MultipointConstraint>(*_problem, V);
    for (int k = 0; k < 3; ++k)
    {
      std::array<double, 3> normal{};
      normal[k] = 1;
      _symmetry->slip(*_geo.facet_tags, planes[k], normal);
    }
    _symmetry->finalize();
  }

  _X = V->tabulate_dof_coordinates(false);
  const std::int32_t owned = V->dofmap()->index_map->size_local();
  for (std::int32_t n : fem::locate_dofs_topological(
           *V, 2, _geo.facet_tags->find(_geo.tag("inner")), true))
    if (n < owned)
      _inner_nodes.push_back(n);
}

NonlinearSystem& InflatedShell::system()
{
  return _symmetry ? static_cast<NonlinearSystem&>(*_symmetry) : *_problem;
}

void InflatedShell::set_load_factor(double lambda) { _forms->set("p", lambda * _p.G); }

double InflatedShell::inner_stretch() const
{
  double sum[2] = {0, static_cast<double>(_inner_nodes.size())};
  for (std::int32_t n : _inner_nodes)
  {
    double r2 = 0;
    for (int i = 0; i < 3; ++i)
      r2 += std::pow(_X[3 * n + i] + _u->x()->array()[3 * n + i], 2);
    sum[0] += std::sqrt(r2) / _p.A;
  }
  MPI_Allreduce(MPI_IN_PLACE, sum, 2, MPI_DOUBLE, MPI_SUM, _geo.mesh->comm());
  return sum[0] / sum[1];
}

double InflatedShell::closed_form_pressure(const ShellParameters& p, double la)
{
  const double lb = std::cbrt(1 + (la * la * la - 1) * std::pow(p.A / p.B, 3));
  return 2 * p.G * ((1 / lb - 1 / la) + (std::pow(lb, -4) - std::pow(la, -4)) / 4);
}

std::pair<double, double> InflatedShell::closed_form_maximum(const ShellParameters& p)
{
  // golden-section search; the law has a single maximum for la > 1
  double lo = 1.0, hi = 4.0;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 200; ++i)
  {
    const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    if (closed_form_pressure(p, x1) < closed_form_pressure(p, x2))
      lo = x1;
    else
      hi = x2;
  }
  const double la = 0.5 * (lo + hi);
  return {la, closed_form_pressure(p, la)};
}

} // namespace gelx::scenes
