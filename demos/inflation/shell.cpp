#include "shell.h"
#include "sphere.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/utils.h>

using namespace dolfinx;

namespace gelx::scenes
{

namespace
{
/// The .geo parameters of the shell's domain
std::map<std::string, double> geometry_parameters(const ShellParameters& p)
{
  std::map<std::string, double> geo = {{"A", p.A}, {"B", p.B}, {"h", p.h}};
  if (p.domain == "sector")
    geo["t"] = p.t;
  else
    geo["lower"] = p.domain == "quarter" ? 1 : 0;
  return geo;
}
} // namespace

InflatedShell::InflatedShell(MPI_Comm comm, const std::string& geo_file, ShellParameters p)
    : _p(p), _geo(read_geo(comm, geo_file, geometry_parameters(p)))
{
  auto V = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_sphere_residual, "u", _geo.mesh));
  _u = std::make_shared<fem::Function<double>>(V);
  _u->name = "displacement";
  // ds(1) of the form is the inner surface, physical group "inner" = 1 of the .geo
  _forms = std::make_unique<FormBinding>(_geo.mesh, FormBinding::Coefficients{{"u", _u}},
                                         std::map<std::string, double>{{"C10", p.C10()},
                                                                       {"C01", p.C01()},
                                                                       {"K", p.K},
                                                                       {"p", 0.0},
                                                                       {"rho", p.rho}});
  _forms->add_subdomains(fem::IntegralType::exterior_facet, _geo.facet_tags);
  _bcs = std::make_unique<DirichletConditions>(V, _geo.facet_tags);
  // The planes and their normals: x = 0, y = 0, then z = 0 (octant), none (quarter) or the
  // sides x = t z, y = t z (sector)
  std::vector<std::pair<int, std::array<double, 3>>> planes
      = {{_geo.tag("sym_x"), {1, 0, 0}}, {_geo.tag("sym_y"), {0, 1, 0}}};
  if (p.domain == "sector")
  {
    const double n = std::sqrt(1 + p.t * p.t);
    planes.push_back({_geo.tag("side_x"), {1 / n, 0, -p.t / n}});
    planes.push_back({_geo.tag("side_y"), {0, 1 / n, -p.t / n}});
  }
  else if (p.domain == "octant")
    planes.push_back({_geo.tag("sym_z"), {0, 0, 1}});
  // Axis-aligned planes as rollers, unless asked for as constraints; inclined ones always
  // constrained
  std::vector<std::pair<int, std::array<double, 3>>> constrained;
  for (const auto& [tag, normal] : planes)
  {
    const auto axis = std::find(normal.begin(), normal.end(), 1.0);
    if (p.symmetry == "rollers" && axis != normal.end())
      _bcs->fix(tag, int(axis - normal.begin()));
    else
      constrained.push_back({tag, normal});
  }
  // The quarter is free to translate along z: its one rigid motion, pinned at the inner
  // surface's nodes on the plane y = 0 within h/2 of the equator (one or two vertices and
  // their edge nodes: the mesh need not have a node at z = 0 exactly)
  if (p.domain == "quarter")
    _bcs->fix(_geo.tag("sym_y"), 2,
              [&](const std::array<double, 3>& X)
              {
                return std::abs(std::hypot(X[0], X[1], X[2]) - p.A) < 1e-6 * p.A
                       && std::abs(X[2]) < 0.5 * p.h;
              });
  _bcs->update(0);
  _problem = std::make_unique<NonlinearProblem>(
      _u, _forms->form(form_sphere_residual, {V}), _forms->form(form_sphere_tangent, {V, V}),
      _bcs->bcs(), _forms->expression(expression_sphere_det_F));
  if (!constrained.empty())
  {
    _symmetry = std::make_unique<MultipointConstraint>(*_problem, V);
    for (const auto& [tag, normal] : constrained)
      _symmetry->slip(*_geo.facet_tags, tag, normal);
    _symmetry->finalize();
  }

  _strain_energy = _forms->form(form_sphere_strain_energy, {});

  _X = V->tabulate_dof_coordinates(false);
  const std::int32_t owned = V->dofmap()->index_map->size_local();
  // The inner surface's owned nodes that lie on the sphere r = A: its vertices. The P2
  // edge-midpoint nodes lie on the facets' chords, inside the sphere by O(h^2): their |x|/A
  // would bias the stretch low by about 1e-3 at h = 0.125 (and the pressure at a stretch by
  // its slope times that)
  for (std::int32_t n : fem::locate_dofs_topological(
           *V, 2, _geo.facet_tags->find(_geo.tag("inner")), true))
  {
    const double R = std::hypot(_X[3 * n], _X[3 * n + 1], _X[3 * n + 2]);
    if (n < owned && std::abs(R - p.A) < 1e-6 * p.A)
      _inner_nodes.push_back(n);
  }
}

NonlinearSystem& InflatedShell::system()
{
  return _symmetry ? static_cast<NonlinearSystem&>(*_symmetry) : *_problem;
}

void InflatedShell::set_load_factor(double lambda) { _forms->set("p", lambda * _p.G); }

InflatedShell::InnerRadii InflatedShell::inner_radii() const
{
  double range[2] = {-INFINITY, -INFINITY}; // -smallest, largest
  double sum[2] = {0, static_cast<double>(_inner_nodes.size())};
  for (std::int32_t n : _inner_nodes)
  {
    const double r = std::hypot(_X[3 * n] + _u->x()->array()[3 * n],
                                _X[3 * n + 1] + _u->x()->array()[3 * n + 1],
                                _X[3 * n + 2] + _u->x()->array()[3 * n + 2]);
    range[0] = std::max(range[0], -r);
    range[1] = std::max(range[1], r);
    sum[0] += r;
  }
  MPI_Allreduce(MPI_IN_PLACE, range, 2, MPI_DOUBLE, MPI_MAX, _geo.mesh->comm());
  MPI_Allreduce(MPI_IN_PLACE, sum, 2, MPI_DOUBLE, MPI_SUM, _geo.mesh->comm());
  return {-range[0], range[1], sum[0] / sum[1]};
}

std::shared_ptr<const fem::Expression<double>> InflatedShell::stress() const
{
  return _forms->expression(expression_sphere_stress);
}

std::shared_ptr<const fem::Expression<double>> InflatedShell::energy_density() const
{
  return _forms->expression(expression_sphere_psi);
}

double InflatedShell::inner_stretch() const { return inner_radii().mean / _p.A; }

double InflatedShell::asphericity() const
{
  const InnerRadii r = inner_radii();
  return (r.largest - r.smallest) / r.mean;
}

std::shared_ptr<fem::Form<double>> InflatedShell::mass_form() const
{
  auto V = _u->function_space();
  return _forms->form(form_sphere_mass, {V, V});
}

double InflatedShell::strain_energy() const
{
  return assemble_global_scalar(*_strain_energy);
}

double InflatedShell::closed_form_pressure(const ShellParameters& p, double la)
{
  const double lb = std::cbrt(1 + (la * la * la - 1) * std::pow(p.A / p.B, 3));
  return 4 * p.C10() * ((1 / lb - 1 / la) + (std::pow(lb, -4) - std::pow(la, -4)) / 4)
         + 4 * p.C01() * ((la - lb) + (std::pow(lb, -2) - std::pow(la, -2)) / 2);
}

namespace
{
/// The extremum of the shell's pressure in [lo, hi] (golden-section search; `sign` +1 for a
/// maximum, -1 for a minimum).
std::pair<double, double> extremum(const ShellParameters& p, double lo, double hi, double sign)
{
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 200; ++i)
  {
    const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    if (sign * InflatedShell::closed_form_pressure(p, x1)
        < sign * InflatedShell::closed_form_pressure(p, x2))
      lo = x1;
    else
      hi = x2;
  }
  const double la = 0.5 * (lo + hi);
  return {la, InflatedShell::closed_form_pressure(p, la)};
}

/// The closed form's stationary points on (1, 50]: the brackets [la_k-1, la_k+1] of a scan
/// with steps of 1e-3 where the pressure's differences change sign (the laws here have at most
/// a maximum and a minimum, both far wider than the scan's step).
std::vector<std::pair<double, double>> stationary_brackets(const ShellParameters& p)
{
  std::vector<std::pair<double, double>> brackets;
  const double step = 1e-3;
  double previous = InflatedShell::closed_form_pressure(p, 1.0);
  double current = InflatedShell::closed_form_pressure(p, 1.0 + step);
  for (double la = 1.0 + step; la < 50 && brackets.size() < 2; la += step)
  {
    const double next = InflatedShell::closed_form_pressure(p, la + step);
    if ((current - previous) * (next - current) <= 0)
      brackets.emplace_back(la - step, la + step);
    previous = current;
    current = next;
  }
  return brackets;
}
} // namespace

std::pair<double, double> InflatedShell::closed_form_maximum(const ShellParameters& p)
{
  const auto brackets = stationary_brackets(p);
  if (brackets.empty())
    throw std::runtime_error("the shell's pressure has no maximum below a stretch of 50");
  return extremum(p, brackets[0].first, brackets[0].second, 1);
}

std::pair<double, double> InflatedShell::closed_form_minimum(const ShellParameters& p)
{
  const auto brackets = stationary_brackets(p);
  if (brackets.size() < 2)
    return {NAN, NAN};
  return extremum(p, brackets[1].first, brackets[1].second, -1);
}

double InflatedShell::closed_form_far_stretch(const ShellParameters& p, double pressure)
{
  // Past the minimum the pressure rises monotonically (like 4 C01 la for large la): bisection
  // on [la_min, la_min * 2^k] once the upper end exceeds the pressure
  const auto [la_min, p_min] = closed_form_minimum(p);
  if (std::isnan(la_min) || pressure <= p_min)
    throw std::invalid_argument("no far branch at that pressure");
  double lo = la_min, hi = 2 * la_min;
  while (closed_form_pressure(p, hi) < pressure)
    hi *= 2;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (closed_form_pressure(p, mid) < pressure ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

} // namespace gelx::scenes
