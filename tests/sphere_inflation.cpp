// Verification: arc-length continuation through the pressure maximum of an inflated
// neo-Hookean spherical shell.
//
// An incompressible neo-Hookean shell (inner radius A, outer B) under cavity pressure p has,
// with the inner and outer hoop stretches la = a/A, lb = b/B and lb^3 = 1 + (la^3 - 1)(A/B)^3,
//   p = 2G int_lb^la (l^-2 + l^-5) dl = 2G [(1/lb - 1/la) + (lb^-4 - la^-4)/4]
// (equilibrium dsigma_rr/dr = 2(sigma_rr - sigma_tt)/r integrated across the wall; for a thin
// wall it reduces to p = 2G (H/R)(l^-1 - l^-7)). p rises to a maximum and falls: a limit point
// in load control. One octant of the shell (symmetry rollers) of the compressible law of
// Eq. 3.1 with K/G = 1000 is inflated by the arc-length method past the maximum; the maximum
// pressure and the stretch where it occurs are compared with the closed form.

#include "sphere.h"
#include "support.h"

#include <cmath>
#include <cstdio>
#include <dolfinx/fem/utils.h>
#include <gelx/arclength.h>
#include <gelx/boundary.h>
#include <gelx/mesh.h>
#include <gelx/petsc_utils.h>
#include <slepcsys.h>

using namespace dolfinx;

namespace
{
constexpr double A = 1.0, B = 1.25, G = 1.0, K_bulk = 1000.0;

double closed_form_pressure(double la)
{
  const double lb = std::cbrt(1 + (la * la * la - 1) * std::pow(A / B, 3));
  return 2 * G * ((1 / lb - 1 / la) + (std::pow(lb, -4) - std::pow(la, -4)) / 4);
}

/// Maximum of the closed form by golden-section search: (stretch, pressure)
std::pair<double, double> closed_form_maximum()
{
  double lo = 1.01, hi = 3.0;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 200; ++i)
  {
    const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    if (closed_form_pressure(x1) < closed_form_pressure(x2))
      lo = x1;
    else
      hi = x2;
  }
  const double la = 0.5 * (lo + hi);
  return {la, closed_form_pressure(la)};
}
} // namespace

int main(int argc, char* argv[])
{
  SlepcInitialize(&argc, &argv, nullptr, nullptr);
  int status;
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    gelx::test::Checks checks(comm);
    auto geo = gelx::read_geo(comm, GELX_MESHES "/sphere_shell.geo",
                              {{"A", A}, {"B", B}, {"h", 0.125}});
    auto V = std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(functionspace_form_sphere_residual, "u", geo.mesh));
    auto u = std::make_shared<fem::Function<double>>(V);
    auto p = std::make_shared<fem::Constant<double>>(0.0);
    const std::map<std::string, std::shared_ptr<const fem::Constant<double>>> constants
        = {{"G", std::make_shared<fem::Constant<double>>(G)},
           {"K", std::make_shared<fem::Constant<double>>(K_bulk)},
           {"p", p}};
    auto form = [&](ufcx_form* f, std::vector<std::shared_ptr<const fem::FunctionSpace>> s)
    {
      return std::make_shared<fem::Form<double>>(fem::create_form<double>(
          *f, s, {{"u", u}}, constants,
          {{fem::IntegralType::exterior_facet, geo.facet_tags.get()}}, geo.mesh));
    };
    gelx::DirichletConditions bcs(V, geo.facet_tags);
    bcs.fix(geo.tag("sym_x"), 0);
    bcs.fix(geo.tag("sym_y"), 1);
    bcs.fix(geo.tag("sym_z"), 2);
    bcs.update(0);
    gelx::NonlinearProblem problem(
        u, form(form_sphere_residual, {V}), form(form_sphere_tangent, {V, V}), bcs.bcs(),
        std::make_shared<fem::Expression<double>>(
            fem::create_expression<double>(*expression_sphere_det_F, {{"u", u}}, constants,
                                           geo.mesh)));

    // The inner hoop stretch from the inner-surface nodes (mean of their radial stretch)
    const std::vector<double> X = V->tabulate_dof_coordinates(false);
    const auto inner_nodes = fem::locate_dofs_topological(
        *V, 2, geo.facet_tags->find(geo.tag("inner")), false);
    const std::int32_t owned = V->dofmap()->index_map->size_local();
    auto inner_stretch = [&]()
    {
      double sum[2] = {0, 0};
      for (std::int32_t n : inner_nodes)
      {
        if (n >= owned)
          continue;
        double r2 = 0;
        for (int i = 0; i < 3; ++i)
          r2 += std::pow(X[3 * n + i] + u->x()->array()[3 * n + i], 2);
        sum[0] += std::sqrt(r2) / A;
        sum[1] += 1;
      }
      MPI_Allreduce(MPI_IN_PLACE, sum, 2, MPI_DOUBLE, MPI_SUM, comm);
      return sum[0] / sum[1];
    };

    std::vector<double> s, lambda, stretch;
    bool passed_max = false;
    double lambda_peak = 0;
    // The arc length is measured in the 2-norm of the dof vector (about 1.5e4 entries here):
    // steps of 0.5 to 6 resolve the path with 2-4 corrector iterations each
    gelx::set_default_option("arclength_", "ds", "0.5");
    gelx::set_default_option("arclength_", "ds_max", "6");
    gelx::ArcLength continuation(comm, problem, [&](double l) { p->value = {l * G}; });
    continuation.run(
        0.0, 200,
        [&](const gelx::PathPoint& pt)
        {
          s.push_back(pt.arc_length);
          lambda.push_back(pt.load_factor);
          stretch.push_back(inner_stretch());
          passed_max = passed_max || pt.limit_point;
        },
        [&](const gelx::PathPoint& pt)
        {
          lambda_peak = std::max(lambda_peak, pt.load_factor);
          // stop once the falling branch is followed to 80% of the peak
          return passed_max && pt.load_factor < 0.8 * lambda_peak;
        });

    // Locate the maximum: parabola through the three points around the largest pressure
    const std::size_t k = std::max_element(lambda.begin(), lambda.end()) - lambda.begin();
    checks.require("the path passed the pressure maximum and descended to 80% of it",
                   passed_max && k > 0 && k + 1 < lambda.size());
    const double la3[3] = {stretch[k - 1], stretch[k], stretch[k + 1]};
    const double p3[3] = {lambda[k - 1], lambda[k], lambda[k + 1]};
    auto [la_max, p_max] = gelx::parabola_vertex(la3, p3);
    auto [la_ref, p_ref] = closed_form_maximum();
    // 1% (the bound): discretisation (P2 on a faceted P1 surface, h = 0.125 A) and the
    // compressibility K/G = 1000 each shift the peak by a few 1e-3.
    checks.relative("maximum pressure p_max / G", p_max * G, p_ref, 0.01);
    checks.relative("inner stretch at the maximum", la_max, la_ref, 0.01);
    // The falling branch follows the closed form too: the last point
    checks.relative("pressure on the falling branch at stretch "
                        + std::to_string(stretch.back()),
                    lambda.back() * G, closed_form_pressure(stretch.back()), 0.02);
    status = checks.finish();
  }
  SlepcFinalize();
  return status;
}
