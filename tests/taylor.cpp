// Verification: Taylor tests of every tangent (tests/taylor_remainder.h).
//
// A wrong tangent does not stop Newton's method from converging, only makes it linear, and no
// other test would notice. Here, for every system the solvers drive, at a strongly deformed
// state u (|Grad u| up to 0.5-0.7, or close to the admissibility limit of a barrier; printed
// per case) and a pseudo-random direction du (zero in the constrained rows, those where the
// tangent is an identity row), the remainder e(eps) = |R(u + eps du) - R(u) - eps K(u) du|
// must fall as eps^2: e(eps)/e(eps/2) in [3.5, 4.5] over the three smallest halvings above the
// measured round-off floor (taylor_remainder.h explains the choice). The states need not be
// equilibria, except for the contact, whose active set must be a converged one. Cases, on
// small meshes:
//  1. compressible neo-Hookean (P1, F0 = I; P2 with a non-uniform, non-symmetric prestretch
//     F0), Mooney-Rivlin (P2) and small-strain linear elasticity (P2, whose residual is linear:
//     the remainder must be at round-off), forms/compressible.py;
//  2. the mixed laws nh, mr, le of forms/mixed_tet.py (P2-P1), mixed_hex.py (Q2-Q1) and
//     mixed_hex_q1.py (Q1-P0), with bulk_compliance 0 and 0.1, the pressure perturbed too
//     (le is linear in (u, p): round-off);
//  3. the Flory-Rehner gel (forms/gel.py, tests/materials/gel_box.h) compressed to
//     J - phi0 ~ 1e-2, where its barrier ln(1 - phi0/J) is stiff;
//  4. the follower pressure on the inner surface of the shell of demos/inflation
//     (forms/sphere.py, meshes/sphere_shell.geo);
//  5. gelx::RigidPlaneContact at a converged contact state (the Hertz cap of meshes/hertz.geo,
//     mixed P2-P1, pressed to d = 0.1 R), requiring that no perturbation changed the active set;
//  6. the reduced system P^T R(P u_r + g) of gelx::MultipointConstraint on a periodic cell with
//     nine macro unknowns (six free, three prescribed), perturbing the free macro unknowns too;
//  7. the arc-length bordered system gelx::ArcLengthSystem (the load factor as one more unknown,
//     the arc-length condition as one more equation) on the inflated shell of case 4, whose
//     tangent is a shell matrix: perturbing the displacement and the pressure together.
// Negative controls prove the test can fail: the same helper with the tangent scaled by 1.001,
// and with the follower pressure's term dropped from the tangent, must give ratios near 2.

#include "common.h"
#include "compressible.h"
#include "gel_box.h"
#include "mixed_hex.h"
#include "mixed_hex_q1.h"
#include "mixed_tet.h"
#include "shell.h"
#include "taylor_remainder.h"

#include <cmath>
#include <dolfinx/fem/DofMap.h>
#include <gelx/solvers/arclength.h>
#include <gelx/systems/boundary.h>
#include <gelx/systems/constraints.h>
#include <gelx/systems/contact.h>
#include <gelx/solvers/load_stepping.h>
#include <gelx/systems/problem.h>
#include <gelx/io/mesh.h>
#include <gelx/systems/mixed.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/systems/prestretch.h>

using namespace dolfinx;
using namespace gelx::test;

namespace
{
using Point = std::array<double, 3>;
using Field = std::function<std::array<double, 3>(const Point&)>;

/// Set sub-function `sub` of w (w itself for sub < 0) to the nodal values of f, component by
/// component (a scalar sub-space takes f's first component): the interpolant of f on Lagrange
/// spaces, its midpoint value on DG0. Owned and ghost values.
void set_nodal(fem::Function<double>& w, int sub, const Field& f)
{
  std::shared_ptr<const fem::FunctionSpace> V = w.function_space();
  std::vector<std::int32_t> to_parent;
  if (sub >= 0)
  {
    auto [collapsed, map] = w.function_space()->sub({sub})->collapse();
    V = std::make_shared<fem::FunctionSpace>(std::move(collapsed));
    to_parent = std::move(map);
  }
  const std::vector<double> X = V->tabulate_dof_coordinates(false);
  const int bs = V->dofmap()->index_map_bs();
  std::span<double> values = w.x()->mutable_array();
  for (std::size_t i = 0; i < X.size() / 3 * bs; ++i)
  {
    const std::size_t node = i / bs;
    const double v = f({X[3 * node], X[3 * node + 1], X[3 * node + 2]})[i % bs];
    values[to_parent.empty() ? i : to_parent[i]] = v;
  }
}

std::string number(double v)
{
  char s[32];
  std::snprintf(s, sizeof s, "%.3g", v);
  return s;
}

/// "|Grad u| from a to b": the range of the Frobenius norm of Grad f over the nodes of V
/// (central differences; all ranks), how strongly deformed an imposed state is.
std::string gradient_range(const fem::FunctionSpace& V, const Field& f)
{
  const std::vector<double> X = V.tabulate_dof_coordinates(false);
  constexpr double h = 1e-6;
  double range[2] = {-INFINITY, 0}; // -smallest, largest: one MPI_MAX
  for (std::size_t n = 0; n < X.size() / 3; ++n)
  {
    double norm2 = 0;
    for (int j = 0; j < 3; ++j)
    {
      Point plus = {X[3 * n], X[3 * n + 1], X[3 * n + 2]}, minus = plus;
      plus[j] += h;
      minus[j] -= h;
      const auto a = f(plus), b = f(minus);
      for (int i = 0; i < 3; ++i)
        norm2 += std::pow((a[i] - b[i]) / (2 * h), 2);
    }
    range[0] = std::max(range[0], -std::sqrt(norm2));
    range[1] = std::max(range[1], std::sqrt(norm2));
  }
  MPI_Allreduce(MPI_IN_PLACE, range, 2, MPI_DOUBLE, MPI_MAX, V.mesh()->comm());
  return "|Grad u| from " + number(-range[0]) + " to " + number(range[1]);
}

void print(MPI_Comm comm, const std::string& text)
{
  if (dolfinx::MPI::rank(comm) == 0)
    std::printf("%s\n", text.c_str());
}

/// The Taylor test of `system` at its current unknowns along a pseudo-random direction that is
/// zero in the rows where `constraints`' tangent is an identity row (by default the system's
/// own).
TaylorResult taylor(gelx::NonlinearSystem& system, TaylorOptions options = {},
                    gelx::NonlinearSystem* constraints = nullptr)
{
  const std::vector<PetscInt> fixed = identity_rows(constraints ? *constraints : system);
  Vec du = random_direction(system, fixed);
  PetscInt size;
  GELX_PETSC(VecGetSize(du, &size));
  std::int64_t num_fixed = fixed.size();
  MPI_Comm comm = PetscObjectComm((PetscObject)du);
  MPI_Allreduce(MPI_IN_PLACE, &num_fixed, 1, MPI_INT64_T, MPI_SUM, comm);
  print(comm, "  du: " + std::to_string(size - num_fixed) + " of " + std::to_string(size)
                  + " unknowns perturbed (the others have identity rows in the tangent)");
  TaylorResult result = taylor_remainders(system, du, options);
  VecDestroy(&du);
  return result;
}

/// A system with its tangent replaced: the negative controls.
class WithTangent : public gelx::NonlinearSystem
{
public:
  WithTangent(gelx::NonlinearSystem& system, std::function<void(Mat)> tangent)
      : _system(system), _tangent(std::move(tangent))
  {
  }
  Vec unknowns() override { return _system.unknowns(); }
  void unknowns_changed() override { _system.unknowns_changed(); }
  void residual(Vec r) override { _system.residual(r); }
  void tangent(Mat A) override { _tangent(A); }
  Vec create_vector() const override { return _system.create_vector(); }
  Mat create_matrix() const override { return _system.create_matrix(); }
  bool admissible() const override { return _system.admissible(); }
  std::vector<PetscInt> prescribed_rows() const override { return _system.prescribed_rows(); }
  gelx::NonlinearProblem& problem() override { return _system.problem(); }
  const std::vector<PetscInt>& unknown_of_problem_dof() const override
  {
    return _system.unknown_of_problem_dof();
  }

private:
  gelx::NonlinearSystem& _system;
  std::function<void(Mat)> _tangent;
};

// --- The deformed states -----------------------------------------------------------------

/// A box state clamped on x = 0 (u = 0 there): stretch, compression and shear, non-uniform,
/// |Grad u| from 0.2 to 0.5 (printed).
std::array<double, 3> box_state(const Point& X)
{
  const auto [x, y, z] = X;
  return {x * (0.20 + 0.10 * y - 0.07 * z), x * (0.18 * z - 0.14 * y),
          x * (-0.18 + 0.07 * std::sin(M_PI * y) + 0.10 * z)};
}

/// The pressure of the mixed states, of the order of G = 1.
std::array<double, 3> pressure_state(const Point& X)
{
  return {0.3 + 0.2 * X[0] - 0.1 * X[1] * X[2], 0, 0};
}

// --- 1. Compressible laws ----------------------------------------------------------------

void compressible_laws(Checks& checks, MPI_Comm comm)
{
  auto box = tagged_box(comm, {1, 1, 1}, {2, 2, 2});
  struct Law
  {
    std::string name;
    int degree;
    ufcx_form *residual, *tangent;
    bool prestretched, linear;
  };
  const std::vector<Law> laws
      = {{"compressible neo-Hookean P1 (F0 = I)", 1, form_compressible_residual_nh_p1,
          form_compressible_tangent_nh_p1, false, false},
         {"compressible neo-Hookean P2, prestretched (F0 per cell tag)", 2,
          form_compressible_residual_nh_p2, form_compressible_tangent_nh_p2, true, false},
         {"compressible Mooney-Rivlin P2", 2, form_compressible_residual_mr_p2,
          form_compressible_tangent_mr_p2, false, false},
         {"small-strain linear elastic P2", 2, form_compressible_residual_le_p2,
          form_compressible_tangent_le_p2, false, true}};
  for (const Law& law : laws)
  {
    const std::string u_name = law.degree == 1 ? "u_p1" : "u_p2";
    auto* space = law.degree == 1 ? functionspace_form_compressible_residual_nh_p1
                                  : functionspace_form_compressible_residual_nh_p2;
    auto V
        = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(space, u_name, box.mesh));
    auto u = std::make_shared<fem::Function<double>>(V);
    auto F0 = std::make_shared<fem::Function<double>>(
        std::make_shared<fem::FunctionSpace>(fem::create_functionspace(space, "F0", box.mesh)));
    // Two prestretches with shear, on the cells left and right of x = 0.5; or the identity
    auto halves = gelx::tag_cells(box.mesh, [](const Point& x) { return x[0] < 0.5 ? 1 : 2; });
    std::map<int, gelx::Tensor3> F0_values;
    if (law.prestretched)
      F0_values = {{1, {1.2, 0.1, 0, 0, 0.9, 0.05, 0, 0, 1.1}},
                   {2, {0.85, 0, 0.1, -0.05, 1.15, 0, -0.1, 0, 1.0}}};
    gelx::set_prestretch(*F0, *halves, F0_values);
    const Coefficients coefficients = {{u_name, u}, {"F0", F0}};
    const Constants constants
        = const_constants(make_constants({{"G", 1.0}, {"K", 10.0}, {"C10", 0.3}, {"C01", 0.2}}));
    auto forms = make_forms(law.residual, law.tangent, V, coefficients, constants);
    gelx::DirichletConditions bcs(V, box.facets);
    bcs.clamp(x_min);
    auto det_F = make_expression(law.degree == 1 ? expression_compressible_det_F_p1
                                                 : expression_compressible_det_F_p2,
                                 coefficients, constants, box.mesh);
    gelx::NonlinearProblem problem(u, forms.residual, forms.tangent, bcs.bcs(), det_F);
    set_nodal(*u, -1, box_state);
    problem.unknowns_changed();
    print(comm, law.name + ": " + gradient_range(*V, box_state) + ", smallest det F "
                    + number(problem.admissibility_margin()));
    if (law.linear)
      check_linear(checks, comm, law.name, taylor(problem));
    else
      check_second_order(checks, comm, law.name, taylor(problem));

    // Negative control on the prestretched law: the tangent 0.1% too stiff
    if (law.prestretched)
    {
      WithTangent too_stiff(problem,
                            [&](Mat A)
                            {
                              problem.tangent(A);
                              GELX_PETSC(MatScale(A, 1.001));
                            });
      check_first_order(checks, comm, law.name + ", NEGATIVE CONTROL: tangent x 1.001",
                        taylor(too_stiff, {}, &problem));
    }
  }
}

// --- 2. Mixed u-p laws -------------------------------------------------------------------

void mixed_laws(Checks& checks, MPI_Comm comm)
{
  struct Element
  {
    std::string name;
    mesh::CellType cell;
    ufcx_function_space* (*space)(const char*);
    std::map<std::string, std::pair<ufcx_form*, ufcx_form*>> laws; // residual, tangent
    ufcx_expression* det_F;
  };
  const std::vector<Element> elements
      = {{"P2-P1 tet",
          mesh::CellType::tetrahedron,
          functionspace_form_mixed_tet_residual_nh,
          {{"nh", {form_mixed_tet_residual_nh, form_mixed_tet_tangent_nh}},
           {"mr", {form_mixed_tet_residual_mr, form_mixed_tet_tangent_mr}},
           {"le", {form_mixed_tet_residual_le, form_mixed_tet_tangent_le}}},
          expression_mixed_tet_det_F},
         {"Q2-Q1 hex",
          mesh::CellType::hexahedron,
          functionspace_form_mixed_hex_residual_nh,
          {{"nh", {form_mixed_hex_residual_nh, form_mixed_hex_tangent_nh}},
           {"mr", {form_mixed_hex_residual_mr, form_mixed_hex_tangent_mr}},
           {"le", {form_mixed_hex_residual_le, form_mixed_hex_tangent_le}}},
          expression_mixed_hex_det_F},
         {"Q1-P0 hex",
          mesh::CellType::hexahedron,
          functionspace_form_mixed_hex_q1_residual_nh,
          {{"nh", {form_mixed_hex_q1_residual_nh, form_mixed_hex_q1_tangent_nh}},
           {"mr", {form_mixed_hex_q1_residual_mr, form_mixed_hex_q1_tangent_mr}},
           {"le", {form_mixed_hex_q1_residual_le, form_mixed_hex_q1_tangent_le}}},
          expression_mixed_hex_q1_det_F}};
  for (const Element& element : elements)
  {
    auto box = tagged_box(comm, {1, 1, 1}, {2, 2, 2}, element.cell);
    auto W = std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(element.space, "w", box.mesh));
    auto w = std::make_shared<fem::Function<double>>(W);
    auto displacement = std::make_shared<fem::FunctionSpace>(W->sub({0})->collapse().first);
    gelx::DirichletConditions bcs(W->sub({0}), box.facets);
    bcs.clamp(x_min);
    for (const auto& [law, forms] : element.laws)
      for (double compliance : {0.0, 0.1})
      {
        const std::string name
            = element.name + " " + law + ", bulk_compliance " + number(compliance);
        const Constants constants = const_constants(make_constants(
            {{"G", 1.0}, {"C10", 0.3}, {"C01", 0.2}, {"bulk_compliance", compliance}}));
        auto [R, K] = make_forms(forms.first, forms.second, W, {{"w", w}}, constants);
        gelx::NonlinearProblem problem(w, R, K, bcs.bcs(),
                                       make_expression(element.det_F, {{"w", w}}, {}, box.mesh));
        set_nodal(*w, 0, box_state);
        set_nodal(*w, 1, pressure_state);
        problem.unknowns_changed();
        print(comm, name + ": displacement " + gradient_range(*displacement, box_state)
                        + ", smallest det F " + number(problem.admissibility_margin()));
        if (law == "le")
          check_linear(checks, comm, name, taylor(problem));
        else
          check_second_order(checks, comm, name, taylor(problem));
      }
  }
}

// --- 3. The Flory-Rehner gel near its barrier ----------------------------------------------

void gel(Checks& checks, MPI_Comm comm)
{
  GelParameters parameters;
  GelBox gel(comm, parameters, {2, 2, 2});
  gel.set_temperature(parameters.temperature(0.5));
  gelx::NonlinearProblem problem(gel.u, gel.forms.residual, gel.forms.tangent, gel.bcs->bcs(),
                                 gel.margin);
  // Compressed towards the dry state J = phi0 = 0.2, non-uniformly; u_i = 0 on X_i = 0 (the
  // box's rollers)
  auto compressed = [](const Point& X)
  {
    const auto [x, y, z] = X;
    return std::array<double, 3>{x * (-0.40 + 0.05 * y), y * (-0.38 - 0.04 * z),
                                 z * (-0.39 + 0.03 * x * y)};
  };
  set_nodal(*gel.u, -1, compressed);
  problem.unknowns_changed();
  const std::string name = "Flory-Rehner gel P1 (phi0 = 0.2, chi = 0.5)";
  print(comm, name + ": " + gradient_range(*gel.V, compressed) + ", smallest J - phi0 "
                  + number(problem.admissibility_margin()));
  check_second_order(checks, comm, name, taylor(problem));
}

// --- 4. The follower pressure --------------------------------------------------------------

void follower_pressure(Checks& checks, MPI_Comm comm)
{
  gelx::scenes::ShellParameters p;
  p.h = 0.25;
  p.K = 10; // a bulk modulus of the order of G, so that the pressure's part of K is not hidden
  gelx::scenes::InflatedShell shell(comm, GELX_MESHES "/sphere_shell.geo", p);
  // Inflated non-uniformly: u = s(X) X (u_i = 0 on the symmetry planes X_i = 0), hoop stretch
  // about 1.3 at the cavity, radial compression through the wall
  auto inflated = [](const Point& X)
  {
    const double r = std::sqrt(X[0] * X[0] + X[1] * X[1] + X[2] * X[2]);
    const double s = 0.3 - 0.4 * (r - 1) + 0.05 * (X[0] * X[1] - X[2] * X[2]);
    return std::array<double, 3>{s * X[0], s * X[1], s * X[2]};
  };
  set_nodal(*shell.displacement(), -1, inflated);
  gelx::NonlinearProblem& problem = shell.problem();
  problem.unknowns_changed();
  const double pressure = 1.0; // p = G: the closed-form maximum is 0.35 G (K -> infinity)
  shell.set_load_factor(pressure);

  // How much of K du the pressure makes: the follower term must be visible above the sensitivity
  Vec du = random_direction(problem, identity_rows(problem));
  auto K_du_norm = [&](double load, Vec Kdu)
  {
    shell.set_load_factor(load);
    Mat K = problem.create_matrix();
    problem.tangent(K);
    GELX_PETSC(MatMult(K, du, Kdu));
    MatDestroy(&K);
    double norm;
    GELX_PETSC(VecNorm(Kdu, NORM_2, &norm));
    return norm;
  };
  Vec with = problem.create_vector(), without = problem.create_vector();
  const double full = K_du_norm(pressure, with);
  K_du_norm(0.0, without);
  shell.set_load_factor(pressure);
  GELX_PETSC(VecAXPY(without, -1.0, with));
  double share;
  GELX_PETSC(VecNorm(without, NORM_2, &share));
  VecDestroy(&with);
  VecDestroy(&without);
  VecDestroy(&du);
  const std::string name = "follower pressure p = G on the sphere shell (P2, K = 10 G)";
  print(comm, name + ": " + gradient_range(*shell.displacement()->function_space(), inflated)
                  + ", smallest det F " + number(problem.admissibility_margin())
                  + ", pressure's part of |K du|: " + number(share / full));
  check_second_order(checks, comm, name, taylor(problem));

  // Negative control: the pressure's term dropped from the tangent (its residual kept)
  WithTangent without_pressure(problem,
                               [&](Mat A)
                               {
                                 shell.set_load_factor(0.0);
                                 problem.tangent(A);
                                 shell.set_load_factor(pressure);
                               });
  check_first_order(checks, comm, name + ", NEGATIVE CONTROL: pressure term dropped from K",
                    taylor(without_pressure, {}, &problem));
}

// --- 5. Contact with a rigid plane ---------------------------------------------------------

void contact(Checks& checks, MPI_Comm comm)
{
  // The Hertz cap (radius 1, on a block 3 x 3 x 1.5) of tests/contact_hertz.cpp, coarse
  auto geo = gelx::read_geo(comm, GELX_MESHES "/hertz.geo",
                            {{"R", 1.0},
                             {"L", 1.5},
                             {"h", 0.5},
                             {"h_contact", 0.12},
                             {"r_contact", 0.4},
                             {"quarters", 1}});
  auto W = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_mixed_tet_residual_nh, "w", geo.mesh));
  auto w = std::make_shared<fem::Function<double>>(W);
  const Constants constants
      = const_constants(make_constants({{"G", 1.0}, {"bulk_compliance", 0.0}}));
  auto forms
      = make_forms(form_mixed_tet_residual_nh, form_mixed_tet_tangent_nh, W, {{"w", w}}, constants);
  auto displacement = W->sub({0});
  gelx::DirichletConditions bcs(displacement, geo.facet_tags);
  bcs.clamp(geo.tag("top"));
  bcs.fix(geo.tag("sym_y"), 1);
  bcs.fix(geo.tag("sym_x"), 0);
  bcs.update(0);
  gelx::NonlinearProblem problem(
      w, forms.residual, forms.tangent, bcs.bcs(),
      make_expression(expression_mixed_tet_det_F, {{"w", w}}, {}, geo.mesh));
  gelx::RigidPlaneContact contact(problem, displacement, *geo.facet_tags, geo.tag("contact"), 2,
                                  +1);
  gelx::NewtonSolver newton(comm);
  gelx::LoadSteppingOptions steps;
  steps.dt = steps.dt_max = 0.25;
  constexpr double d = 0.1;
  gelx::LoadStepper(contact, newton, steps, [&](double t) { contact.set_position(t * d); })
      .run();
  const gelx::ContactState state = contact.state();

  // The active set at the converged state; every perturbed state must have the same one
  auto active_flags = [&]
  {
    std::vector<char> flags;
    for (const auto& node : contact.nodes())
      flags.push_back(node.active);
    return flags;
  };
  const std::vector<char> reference = active_flags();
  // The active set holds while no free node reaches the plane and no node in contact is pulled
  // off it: |level set| = lambda_i / c_i (in contact, c_i the tangent's diagonal) or gap_i
  // (free) bounds how far a node may move (|du_i| <= 1, and K du / c ~ du). Start at a tenth
  // of its smallest value: flips are persistent (a released node only re-enters when it
  // penetrates), so even the first, largest eps must keep the set.
  double slack = INFINITY;
  std::int64_t free_candidates = 0;
  for (const auto& node : contact.nodes())
  {
    slack = std::min(slack, std::abs(node.level_set));
    free_candidates += !node.active;
  }
  MPI_Allreduce(MPI_IN_PLACE, &slack, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, &free_candidates, 1, MPI_INT64_T, MPI_SUM, comm);
  int evaluations = 0;
  std::int64_t changes = 0;
  TaylorOptions options;
  options.eps0 = 0.1 * slack;
  options.at_perturbed_state = [&](double)
  {
    ++evaluations;
    const std::vector<char> now = active_flags();
    std::int64_t changed = 0;
    for (std::size_t i = 0; i < now.size(); ++i)
      changed += now[i] != reference[i];
    MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPI_INT64_T, MPI_SUM, comm);
    changes += changed;
  };
  // Perturb the nodes in contact too (their rows are u_i - u_i*, linear): fixed are only the
  // problem's Dirichlet rows
  const std::string name = "rigid-plane contact, Hertz cap at d = 0.1 R (P2-P1 nh)";
  print(comm, name + ": " + std::to_string(state.active) + " nodes in contact, force "
                  + number(state.force) + ", smallest |level set| " + number(slack)
                  + ", smallest det F " + number(problem.admissibility_margin()));
  const TaylorResult result = taylor(contact, options, &problem);
  check_second_order(checks, comm, name, result);
  checks.require(name + ": active set unchanged at all " + std::to_string(evaluations)
                     + " perturbed states (" + std::to_string(changes) + " node changes)",
                 changes == 0);
  // Both kinds of candidate rows are exercised: replaced (in contact) and plain (free)
  checks.require(name + ": " + std::to_string(state.active) + " candidate nodes in contact, "
                     + std::to_string(free_candidates) + " free (both > 0)",
                 state.active > 0 && free_candidates > 0);
}

// --- 6. Multipoint constraints: a periodic cell with macro unknowns --------------------------

void periodic_cell(Checks& checks, MPI_Comm comm)
{
  const std::array<double, 3> L = {1.0, 1.5, 2.0};
  auto box = tagged_box(comm, L, {2, 2, 2});
  auto W = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_mixed_tet_residual_nh, "w", box.mesh));
  auto w = std::make_shared<fem::Function<double>>(W);
  const Constants constants
      = const_constants(make_constants({{"G", 1.0}, {"bulk_compliance", 0.1}}));
  auto forms
      = make_forms(form_mixed_tet_residual_nh, form_mixed_tet_tangent_nh, W, {{"w", w}}, constants);
  gelx::NonlinearProblem problem(
      w, forms.residual, forms.tangent, {},
      make_expression(expression_mixed_tet_det_F, {{"w", w}}, {}, box.mesh));
  // u = (F - I) X + a periodic fluctuation; the macro unknowns U_ij = (F - I)_ij L_j
  const double H[3][3] = {{0.30, 0.10, -0.05}, {0.08, -0.20, 0.12}, {-0.10, 0.06, 0.25}};
  auto deformed = [&](const Point& X)
  {
    const double sx = std::sin(2 * M_PI * X[0] / L[0]), cy = std::cos(2 * M_PI * X[1] / L[1]),
                 sz = std::sin(2 * M_PI * X[2] / L[2]);
    std::array<double, 3> u = {0.015 * sx * cy, 0.02 * sz, 0.02 * sx * sz};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        u[i] += H[i][j] * X[j];
    return u;
  };
  set_nodal(*w, 0, deformed);
  set_nodal(*w, 1, pressure_state);
  gelx::MultipointConstraint mpc(problem, W->sub({0}));
  int U[3][3];
  for (auto& row : U)
    for (int& k : row)
      k = mpc.add_macro();
  const std::array<std::pair<int, int>, 3> pairs
      = {{{x_min, x_max}, {y_min, y_max}, {z_min, z_max}}};
  for (int j = 0; j < 3; ++j)
  {
    std::array<double, 3> offset = {0, 0, 0};
    offset[j] = L[j];
    mpc.periodic(*box.facets, pairs[j].first, pairs[j].second, offset, {U[0][j], U[1][j], U[2][j]});
  }
  // The reduced unknowns start from the prescribed macro values; then the upper and diagonal
  // ones are freed (unloaded) at those values, the lower ones stay prescribed (identity rows)
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      mpc.prescribe_macro(U[i][j], H[i][j] * L[j]);
  mpc.finalize();
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      mpc.load_macro(U[i][j], 0.0);
  const std::string name
      = "periodic cell, 9 macro unknowns (6 free), P2-P1 nh, bulk_compliance 0.1";
  print(comm, name + ": " + std::to_string(mpc.num_slaves()) + " slaves, "
                  + gradient_range(*gelx::collapse_sub_function(*w, 0)->function_space(), deformed)
                  + ", smallest det F " + number(problem.admissibility_margin()));
  check_second_order(checks, comm, name, taylor(mpc));
}
} // namespace

// --- 7. The arc-length bordering --------------------------------------------------------

void arclength_bordering(Checks& checks, MPI_Comm comm)
{
  gelx::scenes::ShellParameters p;
  p.h = 0.25;
  p.K = 10 * p.G;
  gelx::scenes::InflatedShell shell(comm, GELX_MESHES "/sphere_shell.geo", p);
  gelx::NonlinearProblem& problem = shell.problem();
  // The last point: the shell inflated uniformly by 20% at p = 0.5 G; the state: a non-uniform
  // inflation at p = G (the arc-length condition's |x - x0|^2 is then far from zero)
  set_nodal(*shell.displacement(), -1, [](const Point& X) {
    return std::array<double, 3>{0.2 * X[0], 0.2 * X[1], 0.2 * X[2]}; });
  problem.unknowns_changed();
  Vec x0 = problem.create_vector();
  GELX_PETSC(VecCopy(problem.unknowns(), x0));
  auto inflated = [](const Point& X)
  {
    const double r = std::sqrt(X[0] * X[0] + X[1] * X[1] + X[2] * X[2]);
    const double s = 0.3 - 0.4 * (r - 1) + 0.05 * (X[0] * X[1] - X[2] * X[2]);
    return std::array<double, 3>{s * X[0], s * X[1], s * X[2]};
  };
  set_nodal(*shell.displacement(), -1, inflated);
  problem.unknowns_changed();
  gelx::ArcLengthSystem bordered(problem, [&](double l) { shell.set_load_factor(l); },
                                 "taylor_arclength_");
  bordered.set_constraint(x0, 0.5, 1.0, 1.0); // ds = 1, psi = 1: both parts of the condition
  Vec state = bordered.create_vector();
  bordered.pack(problem.unknowns(), 1.0, state);
  bordered.set_state(state);
  VecDestroy(&state);
  VecDestroy(&x0);
  const std::string name = "arc-length bordered system on the sphere shell (P2, K = 10 G), "
                           "lambda = 1 and the displacement perturbed together";
  print(comm, name + ": " + gradient_range(*shell.displacement()->function_space(), inflated));
  check_second_order(checks, comm, name, taylor(bordered));
}

int main(int argc, char* argv[])
{
  return run_checks(argc, argv,
                    [](MPI_Comm comm, Checks& checks)
                    {
                      compressible_laws(checks, comm);
                      mixed_laws(checks, comm);
                      gel(checks, comm);
                      follower_pressure(checks, comm);
                      contact(checks, comm);
                      periodic_cell(checks, comm);
                      arclength_bordering(checks, comm);
                    });
}
