// Verification: slip on an inclined plane and "plane stays plane" (gelx::MultipointConstraint)
// against the axis-aligned Dirichlet conditions of the same problem.
//
// A unit cube of compressible neo-Hookean material (G = 1, K = 10), clamped at z = 0, its top
// z = 1 pushed down by d = 0.1 (u = (0, 0, -d) there), with a symmetry plane on x = 0. The
// state is not homogeneous (the block barrels between its clamped ends). Solved three ways:
//  a. reference: the symmetry plane as the Dirichlet condition u_x = 0;
//  b. the mesh rotated by 30 degrees about z, the symmetry plane as slip u.n = 0 with
//     n = (cos 30, sin 30, 0) (slave u_x, master u_y); the clamps are rotation-invariant.
//     Its displacement at every node must be the reference's rotated, u_b = R u_a, and its
//     top force R F_a;
//  c. the axis-aligned mesh with the top's u_z as a "plane stays plane" macro unknown U
//     prescribed to -d (u_x = u_y = 0 there stay Dirichlet): u_c = u_a, and U's macro force
//     equals the top reaction F_a,z.
// The nodes where the symmetry plane meets the clamped faces have all components prescribed;
// the slip builder skips them (their zero values satisfy u.n = 0).
// For P1, P2 and mixed P2-P1 (u-p, bulk compliance 1/K), at 1 and 2 ranks.
// Tolerance 1e-8 relative: each run converges Newton to |R| <= 1e-10 |R0| with a direct
// solver, so the three agree to that level and round-off.

#include "block.h"
#include "common.h"
#include "mixed_tet.h"

#include <cmath>
#include <dolfinx/fem/utils.h>
#include <gelx/systems/constraints.h>
#include <gelx/solvers/load_stepping.h>
#include <gelx/systems/problem.h>
#include <gelx/systems/mixed.h>
#include <gelx/common/petsc_utils.h>
#include <petscsys.h>

using namespace dolfinx;

namespace
{
constexpr double G = 1.0, K = 10.0, d = 0.1;
const double angle = M_PI / 6, c30 = std::cos(angle), s30 = std::sin(angle);

enum class Element
{
  p1,
  p2,
  p2_p1
};

/// Rotation by 30 degrees about z.
std::array<double, 3> rotate(const double* v)
{
  return {c30 * v[0] - s30 * v[1], s30 * v[0] + c30 * v[1], v[2]};
}

struct Solution
{
  std::vector<double> X;        ///< displacement dof coordinates (collapsed space, blocked)
  std::vector<double> u;        ///< displacement at those dofs
  std::vector<double> pressure; ///< mixed only
  std::array<double, 3> top_force;
  double macro_force = NAN;
  std::int64_t slaves = 0;
  gelx::test::NewtonTolerance tolerance; ///< what the 1e-8 below rests on
};

enum class Variant
{
  dirichlet,
  rotated_slip,
  plane_stays_plane
};

Solution solve(MPI_Comm comm, Element element, Variant variant)
{
  using namespace gelx::test;
  auto box = tagged_box(comm, {1, 1, 1}, {2, 2, 2});
  if (variant == Variant::rotated_slip)
  {
    std::span<double> x = box.mesh->geometry().x();
    for (std::size_t i = 0; i < x.size(); i += 3)
    {
      const auto r = rotate(&x[i]);
      std::copy(r.begin(), r.end(), x.begin() + i);
    }
  }

  // The discretisation
  std::shared_ptr<fem::FunctionSpace> W;
  std::shared_ptr<fem::Function<double>> w;
  Forms forms;
  if (element == Element::p2_p1)
  {
    W = std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(functionspace_form_mixed_tet_residual_nh, "w", box.mesh));
    w = std::make_shared<fem::Function<double>>(W);
    forms = make_forms(form_mixed_tet_residual_nh, form_mixed_tet_tangent_nh, W, {{"w", w}},
                       const_constants(make_constants({{"G", G}, {"bulk_compliance", 1 / K}})));
  }
  else
  {
    const bool p1 = element == Element::p1;
    const std::string name = p1 ? "u_p1" : "u_p2";
    W = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(
        p1 ? functionspace_form_block_residual_nh_p1 : functionspace_form_block_residual_nh_p2, name,
        box.mesh));
    w = std::make_shared<fem::Function<double>>(W);
    forms = make_forms(p1 ? form_block_residual_nh_p1 : form_block_residual_nh_p2,
                       p1 ? form_block_tangent_nh_p1 : form_block_tangent_nh_p2, W, {{name, w}},
                       const_constants(make_constants({{"G", G}, {"K", K}})));
  }
  std::shared_ptr<const fem::FunctionSpace> displacement
      = element == Element::p2_p1 ? W->sub({0}) : W;

  gelx::DirichletConditions bcs(displacement, box.facets);
  bcs.clamp(z_min);
  bcs.fix(z_max, 0);
  bcs.fix(z_max, 1);
  if (variant != Variant::plane_stays_plane)
    bcs.prescribe(z_max, 2, [](double t, auto&) { return -t * d; });
  if (variant != Variant::rotated_slip)
    bcs.fix(x_min, 0);
  bcs.update(0);
  gelx::NonlinearProblem problem(w, forms.residual, forms.tangent, bcs.bcs());

  gelx::MultipointConstraint mpc(problem, displacement);
  int top = -1;
  if (variant == Variant::rotated_slip)
    mpc.slip(*box.facets, x_min, {c30, s30, 0});
  if (variant == Variant::plane_stays_plane)
  {
    top = mpc.add_macro();
    mpc.plane_stays_plane(*box.facets, z_max, {0, 0, 1}, top);
  }
  mpc.finalize();

  gelx::NewtonSolver newton(comm);
  gelx::LoadSteppingOptions steps;
  steps.dt = 0.5;
  steps.dt_max = 0.5;
  Solution s;
  gelx::LoadStepper(mpc, newton, steps,
                    [&](double t)
                    {
                      bcs.update(t);
                      if (top >= 0)
                        mpc.prescribe_macro(top, -t * d);
                    })
      .run(s.tolerance.observer());

  auto u = element == Element::p2_p1 ? gelx::collapse_sub_function(*w, 0) : w;
  s.X = u->function_space()->tabulate_dof_coordinates(false);
  const std::int32_t owned = u->function_space()->dofmap()->index_map->size_local();
  s.X.resize(3 * owned);
  s.u.assign(u->x()->array().begin(), u->x()->array().begin() + 3 * owned);
  if (element == Element::p2_p1)
  {
    auto p = gelx::collapse_sub_function(*w, 1);
    const std::int32_t owned_p = p->function_space()->dofmap()->index_map->size_local();
    s.pressure.assign(p->x()->array().begin(), p->x()->array().begin() + owned_p);
  }
  s.top_force = gelx::reaction_force(problem, *displacement, *box.facets, z_max);
  if (top >= 0)
    s.macro_force = mpc.macro_force(top);
  s.slaves = mpc.num_slaves();
  return s;
}

/// Largest |a_i - b_i| over the owned entries of all ranks.
double max_difference(MPI_Comm comm, const std::vector<double>& a, const std::vector<double>& b)
{
  double local = a.size() == b.size() ? 0 : INFINITY;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    local = std::max(local, std::abs(a[i] - b[i]));
  double global;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, comm);
  return global;
}

double max_abs(MPI_Comm comm, const std::vector<double>& a)
{
  return max_difference(comm, a, std::vector<double>(a.size(), 0.0));
}

/// Every 3-vector of `v` rotated.
std::vector<double> rotated(const std::vector<double>& v)
{
  std::vector<double> r(v.size());
  for (std::size_t i = 0; i < v.size(); i += 3)
  {
    const auto ri = rotate(&v[i]);
    std::copy(ri.begin(), ri.end(), r.begin() + i);
  }
  return r;
}

void check(gelx::test::Checks& checks, MPI_Comm comm, Element element, const std::string& name)
{
  constexpr double tol = 1e-8;
  const Solution a = solve(comm, element, Variant::dirichlet);
  const Solution b = solve(comm, element, Variant::rotated_slip);
  const Solution c = solve(comm, element, Variant::plane_stays_plane);
  a.tolerance.check(checks, name + ": roller path");
  b.tolerance.check(checks, name + ": rotated slip path");
  c.tolerance.check(checks, name + ": plane-stays-plane path");
  const double u_scale = max_abs(comm, a.u), f = std::abs(a.top_force[2]);
  checks.require(name + ": reference top force " + std::to_string(a.top_force[2])
                     + ", max |u| " + std::to_string(u_scale) + "; slip slaves "
                     + std::to_string(b.slaves) + ", plane slaves " + std::to_string(c.slaves),
                 f > 0 && b.slaves > 0 && c.slaves > 0);
  // The rotated mesh is the same mesh (same partition and numbering), rotated
  checks.absolute(name + ": rotated dof coordinates = R X", max_difference(comm, b.X, rotated(a.X)),
                  0, 1e-14);

  checks.absolute(name + ": slip: max |u_b - R u_a| / max |u_a|",
                  max_difference(comm, b.u, rotated(a.u)) / u_scale, 0, tol);
  const std::vector<double> Fa(a.top_force.begin(), a.top_force.end()),
      Fb(b.top_force.begin(), b.top_force.end());
  checks.absolute(name + ": slip: |F_b - R F_a| / |F_a,z|",
                  max_difference(MPI_COMM_SELF, Fb, rotated(Fa)) / f, 0, tol);
  if (!a.pressure.empty())
    checks.absolute(name + ": slip: max |p_b - p_a| / G",
                    max_difference(comm, b.pressure, a.pressure) / G, 0, tol);

  checks.absolute(name + ": plane stays plane: max |u_c - u_a| / max |u_a|",
                  max_difference(comm, c.u, a.u) / u_scale, 0, tol);
  checks.relative(name + ": plane stays plane: macro force of U against the top reaction",
                  c.macro_force, a.top_force[2], tol);
}
} // namespace

int main(int argc, char* argv[])
{
  return gelx::test::run_checks(argc, argv, [](MPI_Comm comm, gelx::test::Checks& checks)
  {
    check(checks, comm, Element::p1, "P1");
    check(checks, comm, Element::p2, "P2");
    check(checks, comm, Element::p2_p1, "P2-P1");
  });
}
