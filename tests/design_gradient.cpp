// Verification: the adjoint gradient of gelx::AdjointGradient by the Taylor test.
//
// A bilayer strip 10 x 1 x 1 (Q2 hexahedra, compressible neo-Hookean G = 1, K = 10,
// forms/design_strip.py) clamped at x = 0, whose cells carry the design d = (s, a): the stretch
// of their stress-free state along the in-plane direction at angle a,
// F0 = Q(a) diag(s, s^-1/2, s^-1/2) Q(a)^T. The upper layer (z > 1/2) starts at s = 0.9 and
// a = 0.3 along smooth patterns, the lower at s = 1, so the strip curls up by about a radian
// and a half and twists: a large-rotation equilibrium. The objective is
//   J(d) = 1/2 int |u(d) - u_target|^2 dX + beta/2 int (s - 1)^2 dX,   beta = 0.1,
// with u_target a bending field lifted by 0.1 (also at the clamp), so that both dJ/du and the
// explicit dJ/ds are at work.
//
// Taylor test: for a direction ds (in both components of every cell: a hash of the cell
// midpoint and the component in [-1/2, 1/2], the same on every rank count) the remainder
//   e(h) = |J(s + h ds) - J(s) - h dJ/ds . ds|
// must fall as h^2: e(h)/e(h/2) in [3.5, 4.5] over four halvings from h = 0.02. Every J is that
// of an equilibrium solved to |R| <= 1e-12 |R0| from the base one, so its error (~1e-12 of J,
// 4e-11) stays five orders below the smallest remainder asserted (1e-5, printed). A gradient
// that drops the adjoint term -lambda^T dR/ds (the negative control below: the explicit dJ/ds
// alone) leaves a first-order error and ratios near 2, as would a wrong sign or a stale
// tangent; the test must see that.
// The Taylor test cannot see a gradient error below ~1e-4 of the slope (the remainder at the
// smallest h is ~1e-4 of h dJ.ds), so the slope is also compared with central differences
// (J(s + h ds) - J(s - h ds))/2h at h = 0.005 and 0.0025, Richardson-extrapolated: error
// O(h^4), and the two differ by ~1e-5 relative, so the extrapolation is good to ~1e-10; each J
// is good to ~1e-12 relative, 1e-10 in a difference quotient. Tolerance 1e-9 relative
// (measured 2e-11 to 1e-10). It fails when lambda's Dirichlet rows are not zeroed (measured
// 4e-8 and 1.5e-7 off), which the ratios miss.
//
// The centreline objective (DesignStrip::centreline_objective: the helix detector's curvature
// and twist against 0.3 and 0.1, a term of sampled nodal values with its dJ/du by dual
// numbers) is tested the same way on the plain strip, with the placement term off and the
// Tikhonov term on. Cases: the plain problem; and the strip's half y < 1/2 held on y = 1/2 by a
// gelx::MultipointConstraint (slip u_y = 0 there), its end x = 10 kept plane with a free macro
// unknown (u_x = U): the gradient of a reduced, constrained system, P^T on dJ/du and P on
// lambda (with the twisting design not a symmetry of the whole strip: a problem of its own).
// The elastic energy as a term of J (1000 int psi dX added to the plain strip's objective,
// weighed so that its explicit slope, dpsi/ds . ds, is about half the placement's: measured
// -25 of -79) is tested as well, and that the term is there: its explicit slope must exceed
// the Tikhonov term's alone tenfold. At 1 and 2 ranks.

#include "design_strip.h"
#include "strip.h"
#include "support.h"

#include <cmath>
#include <dolfinx/fem/utils.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/solvers/adjoint.h>
#include <gelx/solvers/newton.h>
#include <gelx/systems/constraints.h>
#include <gelx/systems/forms.h>
#include <gelx/systems/problem.h>
#include <iomanip>
#include <sstream>

using namespace dolfinx;
using namespace gelx::test;

namespace
{
constexpr double regularisation = 0.1;

/// Values of the DG0 function d (two components) from its cell midpoints and the component,
/// owned and ghost cells.
void set_cellwise(fem::Function<double>& d,
                  const std::function<double(const double*, int)>& value)
{
  const std::vector<double> X = d.function_space()->tabulate_dof_coordinates(false);
  std::span<double> values = d.x()->mutable_array();
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = value(&X[3 * (i / 2)], i % 2);
}

/// J(s) of the equilibrium, from the base equilibrium `base`, solved tightly
double objective_at(gelx::NonlinearSystem& system, gelx::NewtonSolver& newton,
                    gelx::AdjointGradient& adjoint, Vec base)
{
  system.set_state(base);
  const gelx::NewtonReport report = newton.solve(system);
  if (!report.converged)
    throw gelx::ConvergenceError("a perturbed equilibrium did not converge: " + report.reason);
  return adjoint.value();
}

struct Case
{
  std::string name;
  bool constrained;
  gelx::scenes::DesignObjective objective = gelx::scenes::DesignObjective::placement;
  double energy_weight = 0;
};

void taylor_test(MPI_Comm comm, Checks& checks, const Case& c)
{
  gelx::scenes::DesignStripGeometry geometry;
  geometry.width = c.constrained ? 0.5 : 1.0;
  geometry.cells = {10, c.constrained ? 1u : 2u, 2};
  geometry.slabs = 10;
  geometry.design_angle = true;
  gelx::scenes::DesignStrip strip(comm, geometry, 1.0, 10.0, regularisation);
  strip.target()->interpolate(
      [](auto X)
      {
        xt::xtensor<double, 2> values = xt::zeros<double>({std::size_t(3), X.shape(1)});
        for (std::size_t i = 0; i < X.shape(1); ++i)
          values(2, i) = 0.1 + 0.02 * X(0, i) * X(0, i);
        return values;
      });
  std::unique_ptr<gelx::MultipointConstraint> mpc;
  gelx::NonlinearSystem* system = &strip.problem();
  if (c.constrained)
  {
    const auto& facets = *strip.mesh().facet_tags;
    mpc = std::make_unique<gelx::MultipointConstraint>(strip.problem(),
                                                       strip.displacement()->function_space());
    mpc->slip(facets, y_max, {0, 1, 0});
    mpc->plane_stays_plane(facets, x_max, {1, 0, 0}, mpc->add_macro());
    mpc->finalize();
    system = mpc.get();
  }
  const std::unique_ptr<gelx::AdjointGradient> adjoint
      = strip.adjoint(*system, c.objective, 0.3, 0.1, c.energy_weight);

  // The base design, reached by load steps from the stress-free s = 1: the upper layer's
  // stretch and angle vary along the strip
  std::vector<double> design(geometry.num_parameters());
  for (int k = 0; k < geometry.slabs; ++k)
  {
    design[k] = 0.9 - 0.03 * std::sin(M_PI * (k + 0.5) / geometry.slabs);
    design[geometry.slabs + k] = 0.3 + 0.1 * std::cos(M_PI * (k + 0.5) / geometry.slabs);
  }
  gelx::NewtonSolver newton(comm);
  strip.solve_from_rest(*system, newton, design);
  const gelx::OwnedVec base = gelx::copy_of(system->unknowns());
  const double J0 = adjoint->value();
  const gelx::OwnedVec gradient(adjoint->create_design_vector());
  adjoint->gradient(gradient.get());
  // The negative control: the explicit dJ/ds alone, without the adjoint term
  const gelx::OwnedVec explicit_part(adjoint->create_design_vector());
  auto S = strip.prestretch()->function_space();
  gelx::assemble_global_vector(
      *strip.forms().form(form_design_strip_objective_d_prestretch, {S}), explicit_part.get());

  const std::shared_ptr<fem::Function<double>> s = strip.prestretch();
  const std::vector<double> s0(s->x()->array().begin(), s->x()->array().end());
  auto direction = [](const double* X, int component)
  {
    const double hash
        = std::sin(12.9898 * X[0] + 78.233 * X[1] + 37.719 * X[2] + 4.1 * component) * 43758.5453;
    return hash - std::floor(hash) - 0.5;
  };
  fem::Function<double> ds(S);
  set_cellwise(ds, direction);
  const gelx::OwnedVec ds_vec(adjoint->create_design_vector());
  {
    // owned entries of ds into the design layout
    PetscScalar* values;
    PetscInt n;
    GELX_PETSC(VecGetLocalSize(ds_vec.get(), &n));
    GELX_PETSC(VecGetArray(ds_vec.get(), &values));
    std::copy_n(ds.x()->array().begin(), n, values);
    GELX_PETSC(VecRestoreArray(ds_vec.get(), &values));
  }
  double slope, wrong_slope;
  GELX_PETSC(VecDot(gradient.get(), ds_vec.get(), &slope));
  GELX_PETSC(VecDot(explicit_part.get(), ds_vec.get(), &wrong_slope));
  if (c.energy_weight > 0)
  {
    // the explicit slope without the energy (the Tikhonov term's alone)
    const gelx::OwnedVec tikhonov(adjoint->create_design_vector());
    strip.forms().set("energy_weight", 0.0);
    gelx::assemble_global_vector(
        *strip.forms().form(form_design_strip_objective_d_prestretch, {S}), tikhonov.get());
    strip.forms().set("energy_weight", c.energy_weight);
    double tikhonov_slope;
    GELX_PETSC(VecDot(tikhonov.get(), ds_vec.get(), &tikhonov_slope));
    checks.require(c.name + ": the energy's explicit slope is at work ("
                       + std::to_string(wrong_slope) + " against the Tikhonov term's "
                       + std::to_string(tikhonov_slope) + ")",
                   std::abs(wrong_slope) > 10 * std::abs(tikhonov_slope));
  }

  GELX_PETSC(SNESSetTolerances(newton.snes(), PETSC_DEFAULT, 1e-12, PETSC_DEFAULT, PETSC_DEFAULT,
                               PETSC_DEFAULT));
  std::vector<double> remainder, wrong_remainder;
  std::ostringstream table;
  table << c.name << ": J = " << J0 << ", dJ.ds = " << slope
        << " (explicit part " << wrong_slope << ")\n     h        J(s+h ds)-J(s)   e(h)      "
        << "e_control(h)\n";
  double h = 0.02;
  for (int k = 0; k < 5; ++k, h /= 2)
  {
    std::span<double> values = s->x()->mutable_array();
    const std::span<const double> d = ds.x()->array();
    for (std::size_t i = 0; i < values.size(); ++i)
      values[i] = s0[i] + h * d[i];
    const double dJ = objective_at(*system, newton, *adjoint, base.get()) - J0;
    remainder.push_back(std::abs(dJ - h * slope));
    wrong_remainder.push_back(std::abs(dJ - h * wrong_slope));
    table << "  " << h << "  " << dJ << "  " << remainder.back() << "  "
          << wrong_remainder.back() << "\n";
  }
  // The slope by central differences at h and h/2, Richardson-extrapolated: error O(h^4)
  auto central = [&](double h)
  {
    double J[2];
    for (int side = 0; side < 2; ++side)
    {
      std::span<double> values = s->x()->mutable_array();
      const std::span<const double> d = ds.x()->array();
      for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = s0[i] + (side == 0 ? h : -h) * d[i];
      J[side] = objective_at(*system, newton, *adjoint, base.get());
    }
    return (J[0] - J[1]) / (2 * h);
  };
  const double D1 = central(0.005), D2 = central(0.0025), extrapolated = (4 * D2 - D1) / 3;
  table << std::setprecision(12) << "  central differences " << D1 << ", " << D2
        << ", extrapolated " << extrapolated << ", adjoint " << slope << ", relative difference "
        << std::abs(extrapolated - slope) / std::abs(slope) << "\n";
  PetscPrintf(comm, "%s", table.str().c_str());
  checks.relative(c.name + ": dJ.ds against extrapolated central differences", slope,
                  extrapolated, 1e-9);
  for (int k = 0; k < 4; ++k)
  {
    const std::string at = c.name + ": e(h)/e(h/2), halving " + std::to_string(k + 1);
    checks.absolute(at, remainder[k] / remainder[k + 1], 4.0, 0.5);
    checks.absolute(at + ", control without the adjoint term",
                    wrong_remainder[k] / wrong_remainder[k + 1], 2.0, 0.5);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  return run_checks(argc, argv,
                    [](MPI_Comm comm, Checks& checks)
                    {
                      for (const Case& c :
                           {Case{"strip", false}, Case{"half strip, constrained", true},
                            Case{"strip, centreline objective", false,
                                 gelx::scenes::DesignObjective::centreline},
                            Case{"strip, placement and energy", false,
                                 gelx::scenes::DesignObjective::placement, 1000.0}})
                        taylor_test(comm, checks, c);
                    });
}
