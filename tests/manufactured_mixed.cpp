// Verification: convergence rates for a manufactured solution of the nearly incompressible
// mixed neo-Hookean solid (Eq. 1.10 in u-p form, K/G = 1e4) on the three mixed elements of
// the project: P2-P1 tetrahedra, Q2-Q1 and Q1-P0 hexahedra.
//
// forms/manufactured_mixed.py adds to the residual and tangent of forms/_mixed.py (the kernels
// the scenes run) the body force, boundary traction and volumetric source that make
// (u_exact, p_exact) the solution; u_exact is volume preserving (det F = 1), p_exact an
// independent smooth field. On the unit cube the faces x = 0, y = 0, z = 0 carry the Dirichlet
// values u_exact, the others the traction. Over three refinements the observed rates
// log(e_1 / e_2) / log(n_2 / n_1) must be within 0.15 of the element's: u in L2 k + 1, u in H1
// k, p in L2 k for Taylor-Hood (k = 2) and 1 for Q1-P0, whose pressure is one constant per
// cell.
//
// The meshes start where the rates are asymptotic. The Taylor-Hood pressure error carries an
// O(h^3) term of relative size ~0.7 h (fitted on n = 5, 8), so its rate approaches 2 from above
// (P2-P1, measured: 2.18 from n = 3 to 5, 2.13 from 5 to 6, 2.07 from 7 to 8): the P2-P1 meshes
// start at n = 5, the Q2-Q1 ones (rate 2.23 from 2 to 3, 2.10 from 4 to 5) at n = 4. Q1-P0 is
// asymptotic from n = 4. On this box (three faces free) Q1-P0 shows no checkerboard: its
// pressure converges at rate 1 like its displacement gradient. Clamped on all six faces it
// does not (measured: p L2 errors 9.4, 0.64, 0.51, 0.23 on n = 2 ... 5 against |p| <= 0.25,
// and MUMPS fails at n = 6, 7): there the 3n - 2 checkerboard modes of Q1-P0 are held only by
// bulk_compliance (tests/q1p0_pressure_modes.cpp counts them).

#include "manufactured_mixed.h"
#include "support.h"

#include <cmath>
#include <cstdio>
#include <dolfinx/fem/utils.h>
#include <gelx/solvers/newton.h>
#include <gelx/systems/problem.h>
#include <stdexcept>
#include <string>
#include <vector>
#include <xtensor/xarray.hpp>
#include <xtensor/xtensor.hpp>

using namespace dolfinx;

namespace
{
/// The displacement of forms/manufactured_mixed.py: shears along z (by x, y), then x (by y, z),
/// then y (by x, z).
std::array<double, 3> u_exact(const std::array<double, 3>& X)
{
  const double a = 0.05;
  std::array<double, 3> y = X;
  y[2] += a * std::sin(M_PI * y[0]) * (1 + y[1]);
  y[0] += a * std::sin(M_PI * y[1]) * (1 + y[2]);
  y[1] += a * std::sin(M_PI * y[2]) * (1 + y[0]);
  return {y[0] - X[0], y[1] - X[1], y[2] - X[2]};
}

/// The pressure of forms/manufactured_mixed.py.
double p_exact(const std::array<double, 3>& X)
{
  return 0.1 * std::cos(M_PI * X[0]) * std::sin(M_PI * X[1]) * (1 + X[2]) + 0.05;
}

/// Set sub-function i of the mixed function w to the interpolant of f (values at a point X).
template <typename Values>
void set_sub_function(fem::Function<double>& w, int i, Values f)
{
  constexpr std::size_t N = std::tuple_size_v<decltype(f(std::array<double, 3>{}))>;
  auto [V, map] = w.function_space()->sub({i})->collapse();
  fem::Function<double> sub(std::make_shared<fem::FunctionSpace>(std::move(V)));
  sub.interpolate(
      [&](const xt::xtensor<double, 2>& x) -> xt::xarray<double>
      {
        xt::xarray<double> values = xt::zeros<double>({N, x.shape(1)});
        for (std::size_t p = 0; p < x.shape(1); ++p)
        {
          const auto v = f({x(0, p), x(1, p), x(2, p)});
          for (std::size_t c = 0; c < N; ++c)
            values(c, p) = v[c];
        }
        return values;
      });
  // map: the index in w of each dof (block size included) of the collapsed space
  std::span<const double> from = sub.x()->array();
  std::span<double> to = w.x()->mutable_array();
  for (std::size_t k = 0; k < map.size(); ++k)
    to[map[k]] = from[k];
}

/// The generated kernels of one element and what it should achieve.
struct Element
{
  const char* name;
  mesh::CellType cell;
  ufcx_function_space* (*space)(const char*);
  ufcx_form *residual, *tangent, *error_u_l2, *error_u_h1, *error_p_l2;
  ufcx_expression* det_F;
  const char *w, *G, *bulk_compliance; ///< the names of the coefficient and the constants
  std::vector<std::size_t> sizes;      ///< cells along an edge of the cube
  double rate_u_l2, rate_u_h1, rate_p_l2;
};

const std::vector<Element> elements = {
    {"P2-P1", mesh::CellType::tetrahedron, functionspace_form_manufactured_mixed_residual_p2p1,
     form_manufactured_mixed_residual_p2p1, form_manufactured_mixed_tangent_p2p1,
     form_manufactured_mixed_error_u_l2_p2p1, form_manufactured_mixed_error_u_h1_p2p1,
     form_manufactured_mixed_error_p_l2_p2p1, expression_manufactured_mixed_det_F_p2p1,
     "w_p2p1", "G_p2p1", "bulk_compliance_p2p1",
     {5, 6, 7, 8}, 3, 2, 2},
    {"Q2-Q1", mesh::CellType::hexahedron, functionspace_form_manufactured_mixed_residual_q2q1,
     form_manufactured_mixed_residual_q2q1, form_manufactured_mixed_tangent_q2q1,
     form_manufactured_mixed_error_u_l2_q2q1, form_manufactured_mixed_error_u_h1_q2q1,
     form_manufactured_mixed_error_p_l2_q2q1, expression_manufactured_mixed_det_F_q2q1,
     "w_q2q1", "G_q2q1", "bulk_compliance_q2q1",
     {4, 5, 6, 7}, 3, 2, 2},
    {"Q1-P0", mesh::CellType::hexahedron, functionspace_form_manufactured_mixed_residual_q1p0,
     form_manufactured_mixed_residual_q1p0, form_manufactured_mixed_tangent_q1p0,
     form_manufactured_mixed_error_u_l2_q1p0, form_manufactured_mixed_error_u_h1_q1p0,
     form_manufactured_mixed_error_p_l2_q1p0, expression_manufactured_mixed_det_F_q1p0,
     "w_q1p0", "G_q1p0", "bulk_compliance_q1p0",
     {4, 6, 9, 14}, 2, 1, 1}};

struct Errors
{
  double u_l2, u_h1, p_l2;
};

Errors solve(MPI_Comm comm, const Element& e, std::size_t n)
{
  auto box = gelx::test::tagged_box(comm, {1, 1, 1}, {n, n, n}, e.cell);
  auto W = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(e.space, e.w, box.mesh));
  auto w = std::make_shared<fem::Function<double>>(W);
  const std::map<std::string, std::shared_ptr<const fem::Function<double>>> coefficients
      = {{e.w, w}};
  // G = 1, K = 1e4 G: nearly incompressible (nu = 0.49995)
  const std::map<std::string, std::shared_ptr<const fem::Constant<double>>> constants
      = {{e.G, std::make_shared<fem::Constant<double>>(1.0)},
         {e.bulk_compliance, std::make_shared<fem::Constant<double>>(1e-4)}};
  auto form = [&](ufcx_form* f, std::vector<std::shared_ptr<const fem::FunctionSpace>> spaces)
  {
    return std::make_shared<fem::Form<double>>(
        fem::create_form<double>(*f, spaces, coefficients, constants, {}, box.mesh));
  };
  gelx::DirichletConditions bcs(W->sub({0}), box.facets);
  for (int face : {gelx::test::x_min, gelx::test::y_min, gelx::test::z_min})
    for (int c = 0; c < 3; ++c)
      bcs.prescribe(face, c, [c](double, auto& X) { return u_exact(X)[c]; });
  // Newton from the interpolant of the exact solution, next to the discrete solution sought (4
  // to 5 iterations): the sources are no physical load path to follow from the reference state
  set_sub_function(*w, 0, [](const std::array<double, 3>& X) { return u_exact(X); });
  set_sub_function(*w, 1, [](const std::array<double, 3>& X) { return std::array{p_exact(X)}; });
  bcs.update(1);
  auto det_F = std::make_shared<fem::Expression<double>>(
      fem::create_expression<double>(*e.det_F, coefficients, {}, box.mesh));
  gelx::NonlinearProblem problem(w, form(e.residual, {W}), form(e.tangent, {W, W}), bcs.bcs(),
                                 det_F);
  const gelx::NewtonReport report = gelx::NewtonSolver(comm).solve(problem);
  if (!report.converged)
    throw std::runtime_error(std::string(e.name) + " n = " + std::to_string(n)
                             + ": Newton did not converge (" + report.reason + ")");
  auto error = [&](ufcx_form* f) { return std::sqrt(gelx::assemble_global_scalar(*form(f, {}))); };
  return {error(e.error_u_l2), error(e.error_u_h1), error(e.error_p_l2)};
}
} // namespace

int main(int argc, char* argv[])
{
  return gelx::test::run_checks(argc, argv, [](MPI_Comm comm, gelx::test::Checks& checks)
  {
    int rank;
    MPI_Comm_rank(comm, &rank);
    for (const Element& element : elements)
    {
      const auto& n = element.sizes;
      std::vector<Errors> e;
      for (std::size_t size : n)
        e.push_back(solve(comm, element, size));
      auto rate = [&](double Errors::*norm, std::size_t i)
      { return std::log(e[i - 1].*norm / e[i].*norm) / std::log(double(n[i]) / n[i - 1]); };
      if (rank == 0)
      {
        std::printf("%s    n   u L2 error  rate   u H1 error  rate   p L2 error  rate\n",
                    element.name);
        for (std::size_t i = 0; i < e.size(); ++i)
          std::printf("%s %4zu   %.4e  %5.2f   %.4e  %5.2f   %.4e  %5.2f\n", element.name, n[i],
                      e[i].u_l2, i ? rate(&Errors::u_l2, i) : NAN, e[i].u_h1,
                      i ? rate(&Errors::u_h1, i) : NAN, e[i].p_l2,
                      i ? rate(&Errors::p_l2, i) : NAN);
      }
      // Tolerance 0.15 on the rates (as tests/manufactured.cpp): the solution is smooth and the
      // meshes in the asymptotic range, so the rates differ from the element's only by
      // higher-order terms
      for (std::size_t i = 1; i < e.size(); ++i)
      {
        const std::string level = std::string(element.name) + " n = " + std::to_string(n[i - 1])
                                  + " -> " + std::to_string(n[i]);
        checks.absolute(level + ": u L2 rate", rate(&Errors::u_l2, i), element.rate_u_l2, 0.15);
        checks.absolute(level + ": u H1 rate", rate(&Errors::u_h1, i), element.rate_u_h1, 0.15);
        checks.absolute(level + ": p L2 rate", rate(&Errors::p_l2, i), element.rate_p_l2, 0.15);
      }
    }
  });
}
