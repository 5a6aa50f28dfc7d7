// Verification: a periodic homogeneous cell with macro unknowns (gelx::MultipointConstraint,
// thesis Eq. 4.21-4.22).
//
// A box L0 x L1 x L2 of compressible neo-Hookean material (Eq. 3.1, G = 1, K = 10), periodic on
// its three pairs of opposite faces: u(X + L_j e_j) = u(X) + U_.j, with nine macro unknowns
// U_ij = (F - I)_ij L_j, and the corner X = 0 pinned (Dirichlet). The lower macro unknowns
// (i > j) are held at zero, which removes the rigid rotations. Every state below is homogeneous,
// u = (F - I) X + c, which P1 and P2 contain exactly, so it must come out to solver round-off:
//  0. the pinned corner moved by c (a rigid translation, in one Newton iteration per step);
//  1. triaxial stretch F = diag(1.2, 0.9, 1.1), every U prescribed: u, and the macro forces
//     (the face resultants P_kk A_k, P = J sigma F^-T) against sigma_kk = G J^(-5/3)
//     (lambda_k^2 - I1/3) + K (J - 1);
//  2. uniaxial stress: U_zz prescribed (lambda = 1.3), U_xx, U_yy and the upper shear macros
//     free with no load (zero macro stress): the lateral stretch 1 + U_xx / L0 against the
//     closed-form mu of sigma_xx(mu) = 0 (bisection, as tests/uniaxial_stretch.cpp);
//  3. the same uniaxial state reached by a macro force on a free U_zz (a load on a dummy node);
//  4. every non-lower macro free and unloaded: u and U stay zero.
// For P2-P1, state 2 again by the fieldsplit linear solver, whose u block holds the macro
// unknowns.
// For P1, P2 and mixed P2-P1 (u-p with bulk compliance 1/K, whose energy is Eq. 3.1 once
// p = K (J - 1) is eliminated; its pressure is checked too), at 1 and 2 ranks; the 2-rank mesh
// puts slaves and masters of a pair on different ranks (counted and required).
//
// Cost (the COST line): one reduced residual + tangent (with MatPtAP) + MUMPS solve against one
// assembly + solve of the unconstrained problem on the same space (the face x = 0 clamped
// instead). Measured in 10 runs, P2 6x6x6 (6591 dofs, 1407 slaves), medians of 5, 1 and 2
// ranks, on two cores shared with another job: the reduced assembly took 0.9-1.5 times the
// plain one (0.043-0.117 s; the triple product and P^T R are within that noise), the solve
// 1.3-2.7 times (0.08-0.27 s plain). The solve is dearer because the periodic cell's graph
// wraps around: its LU factors hold 6.3-6.8e6 entries against 3.8-4.2e6, although the reduced
// matrix has fewer nonzeros (470529 against 493137). Assembly + solve: 1.3-2.3 times.

#include "block.h"
#include "common.h"
#include "mixed_tet.h"

#include <algorithm>
#include <cmath>
#include <dolfinx/fem/utils.h>
#include <gelx/systems/constraints.h>
#include <gelx/solvers/load_stepping.h>
#include <gelx/systems/problem.h>
#include <gelx/systems/mixed.h>
#include <gelx/common/petsc_utils.h>
#include <petscsys.h>
#include <xtensor/xmath.hpp>
#include <xtensor/xtensor.hpp>

using namespace dolfinx;

namespace
{
constexpr double G = 1.0, K = 10.0;
const std::array<double, 3> L = {1.0, 1.5, 2.0};

/// Cauchy stress of Eq. 3.1 under F = diag(lambda).
std::array<double, 3> principal_stress(const std::array<double, 3>& lambda)
{
  const double J = lambda[0] * lambda[1] * lambda[2];
  const double I1 = lambda[0] * lambda[0] + lambda[1] * lambda[1] + lambda[2] * lambda[2];
  std::array<double, 3> sigma;
  for (int k = 0; k < 3; ++k)
    sigma[k] = G * std::pow(J, -5.0 / 3.0) * (lambda[k] * lambda[k] - I1 / 3) + K * (J - 1);
  return sigma;
}

/// Resultant on the reference face normal to k: P_kk A_k = sigma_kk J / lambda_k A_k.
double face_force(const std::array<double, 3>& lambda, int k)
{
  const double J = lambda[0] * lambda[1] * lambda[2];
  return principal_stress(lambda)[k] * J / lambda[k] * (L[0] * L[1] * L[2] / L[k]);
}

/// Lateral stretch mu of uniaxial stress at axial stretch lambda: sigma_xx(mu) = 0.
double lateral_stretch(double lambda)
{
  double lo = 0.1, hi = 10;
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (principal_stress({mid, mid, lambda})[0] > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

/// P1, P2 displacement (forms/block.py) or mixed P2-P1 displacement-pressure with bulk
/// compliance 1/K (forms/mixed_tet.py), whose energy after eliminating p = K (J - 1) is Eq. 3.1
enum class Element
{
  p1,
  p2,
  p2_p1
};

std::string name(Element e)
{
  return e == Element::p1 ? "P1" : e == Element::p2 ? "P2" : "P2-P1";
}

/// The periodic cell: problem, constraints and the nine macro unknowns U[i][j].
struct Cell
{
  Element element;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> facets;
  std::shared_ptr<fem::FunctionSpace> V;                  ///< the problem's space
  std::shared_ptr<const fem::FunctionSpace> displacement; ///< V or its sub-space 0
  std::shared_ptr<fem::Function<double>> u;
  gelx::test::Forms forms;
  std::unique_ptr<gelx::NonlinearProblem> problem;
  std::unique_ptr<gelx::MultipointConstraint> mpc;
  std::array<std::array<int, 3>, 3> U;
  std::array<std::shared_ptr<fem::Function<double>>, 3> pin; ///< the corner's prescribed u
};

/// The corner X = 0 pinned, component by component (works on a sub-space too), to the values
/// of cell.pin (zero until changed).
gelx::NonlinearProblem::BCs pin_origin(Cell& cell)
{
  gelx::NonlinearProblem::BCs bcs;
  for (int c = 0; c < 3; ++c)
  {
    auto sub = cell.displacement->sub({c});
    auto collapsed = std::make_shared<fem::FunctionSpace>(sub->collapse().first);
    auto dofs = fem::locate_dofs_geometrical(
        {*sub, *collapsed}, [](const xt::xtensor<double, 2>& x)
        { return xt::eval(xt::sqrt(xt::sum(x * x, {0})) < 1e-10); });
    cell.pin[c] = std::make_shared<fem::Function<double>>(collapsed);
    bcs.push_back(std::make_shared<fem::DirichletBC<double>>(cell.pin[c], std::move(dofs), sub));
  }
  return bcs;
}

/// The cell's problem with the corner X = 0 pinned, no constraints yet.
Cell pinned_cell(MPI_Comm comm, Element element, std::size_t n)
{
  using namespace gelx::test;
  auto box = tagged_box(comm, L, {n, n, n});
  Cell cell;
  cell.element = element;
  cell.facets = box.facets;
  if (element == Element::p2_p1)
  {
    cell.V = std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(functionspace_form_mixed_tet_residual_nh, "w", box.mesh));
    cell.u = std::make_shared<fem::Function<double>>(cell.V);
    const auto material = make_constants({{"G", G}, {"bulk_compliance", 1 / K}});
    cell.forms = make_forms(form_mixed_tet_residual_nh, form_mixed_tet_tangent_nh, cell.V,
                            {{"w", cell.u}}, const_constants(material));
    cell.displacement = cell.V->sub({0});
  }
  else
  {
    const bool p1 = element == Element::p1;
    const std::string name = p1 ? "u_p1" : "u_p2";
    cell.V = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(
        p1 ? functionspace_form_block_residual_nh_p1 : functionspace_form_block_residual_nh_p2, name,
        box.mesh));
    cell.u = std::make_shared<fem::Function<double>>(cell.V);
    const auto material = make_constants({{"G", G}, {"K", K}});
    cell.forms = make_forms(p1 ? form_block_residual_nh_p1 : form_block_residual_nh_p2,
                            p1 ? form_block_tangent_nh_p1 : form_block_tangent_nh_p2, cell.V,
                            {{name, cell.u}}, const_constants(material));
    cell.displacement = cell.V;
  }
  cell.problem = std::make_unique<gelx::NonlinearProblem>(
      cell.u, cell.forms.residual, cell.forms.tangent, pin_origin(cell));
  cell.mpc = std::make_unique<gelx::MultipointConstraint>(*cell.problem, cell.displacement);
  return cell;
}

using gelx::test::x_min, gelx::test::x_max, gelx::test::y_min, gelx::test::y_max,
    gelx::test::z_min, gelx::test::z_max;
const std::array<std::pair<int, int>, 3> face_pairs
    = {{{x_min, x_max}, {y_min, y_max}, {z_min, z_max}}};

/// The periodic cell with its nine macro unknowns, finalised.
Cell periodic_cell(MPI_Comm comm, Element element, std::size_t n)
{
  Cell cell = pinned_cell(comm, element, n);
  for (auto& row : cell.U)
    for (int& k : row)
      k = cell.mpc->add_macro();
  for (int j = 0; j < 3; ++j)
  {
    std::array<double, 3> offset = {0, 0, 0};
    offset[j] = L[j];
    cell.mpc->periodic(*cell.facets, face_pairs[j].first, face_pairs[j].second, offset,
                       {cell.U[0][j], cell.U[1][j], cell.U[2][j]});
  }
  cell.mpc->finalize();
  return cell;
}

/// Entries of P in columns owned by another rank (all ranks): slaves whose masters live there.
std::int64_t off_rank_entries(Mat P)
{
  PetscInt first_row, last_row, first_col, last_col;
  GELX_PETSC(MatGetOwnershipRange(P, &first_row, &last_row));
  GELX_PETSC(MatGetOwnershipRangeColumn(P, &first_col, &last_col));
  std::int64_t count = 0;
  for (PetscInt row = first_row; row < last_row; ++row)
  {
    PetscInt n;
    const PetscInt* cols;
    GELX_PETSC(MatGetRow(P, row, &n, &cols, nullptr));
    count += std::count_if(cols, cols + n,
                           [&](PetscInt c) { return c < first_col || c >= last_col; });
    GELX_PETSC(MatRestoreRow(P, row, &n, &cols, nullptr));
  }
  MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPI_INT64_T, MPI_SUM, PetscObjectComm((PetscObject)P));
  return count;
}

/// Largest |u - (F - I) X - c| over all displacement dofs (all ranks), F = diag(lambda).
double homogeneous_error(const Cell& cell, const std::array<double, 3>& lambda,
                         const std::array<double, 3>& c = {0, 0, 0})
{
  auto u = cell.element == Element::p2_p1 ? gelx::collapse_sub_function(*cell.u, 0) : cell.u;
  const std::vector<double> X = u->function_space()->tabulate_dof_coordinates(false);
  double error = 0;
  for (std::size_t i = 0; i < u->x()->array().size(); ++i)
    error = std::max(error, std::abs(u->x()->array()[i] - (lambda[i % 3] - 1) * X[i] - c[i % 3]));
  MPI_Allreduce(MPI_IN_PLACE, &error, 1, MPI_DOUBLE, MPI_MAX, cell.V->mesh()->comm());
  return error;
}

/// The iterations of a solve: the most Newton iterations of a step, and the totals
struct Iterations
{
  int most_per_step = 0, newton = 0, linear = 0;
};

/// Restart from u = 0 with the macro unknowns as `load` sets them, and follow the load in two
/// steps by a Newton solver of options prefix `prefix`.
Iterations solve(Cell& cell, const std::function<void(double)>& load,
                 const std::string& prefix = "newton_")
{
  GELX_PETSC(VecSet(cell.mpc->unknowns(), 0.0));
  load(0);
  cell.mpc->unknowns_changed();
  gelx::NewtonSolver newton(cell.V->mesh()->comm(), prefix);
  gelx::LoadSteppingOptions steps;
  steps.dt = 0.5;
  steps.dt_max = 0.5;
  Iterations iterations;
  gelx::LoadStepper(*cell.mpc, newton, steps, load)
      .run(
          [&](const gelx::StepRecord& s, gelx::PathState&)
          {
            iterations.most_per_step = std::max(iterations.most_per_step, s.newton.iterations);
            iterations.newton += s.newton.iterations;
            iterations.linear += s.newton.linear_iterations;
          });
  return iterations;
}

/// The lower macro unknowns (i > j) at zero, the others free and unloaded.
void release_upper(Cell& cell)
{
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      i > j ? cell.mpc->prescribe_macro(cell.U[i][j], 0) : cell.mpc->load_macro(cell.U[i][j], 0);
}

void check_cell(gelx::test::Checks& checks, MPI_Comm comm, Element element)
{
  Cell cell = periodic_cell(comm, element, 2);
  const std::string p = name(element) + ": ";
  const int degree = element == Element::p1 ? 1 : 2;
  // 1e-8: Newton stops at |R| <= 1e-10 |R0|, so the homogeneous state is exact to ~1e-11;
  // the margin covers the round-off of the assembly (as tests/uniaxial_stretch.cpp)
  constexpr double tol = 1e-8;
  // Every node on a face X_j = L_j is a slave: m^3 - (m - 1)^3 nodes, m per edge
  const std::int64_t m = 2 * degree + 1, slaves = 3 * (m * m * m - (m - 1) * (m - 1) * (m - 1));
  checks.require(p + "periodic slaves: " + std::to_string(cell.mpc->num_slaves()) + " (expected "
                     + std::to_string(slaves) + ")",
                 cell.mpc->num_slaves() == slaves);
  if (dolfinx::MPI::size(comm) > 1)
  {
    const std::int64_t across = off_rank_entries(cell.mpc->prolongation());
    checks.require(p + "entries of P coupling a slave to a master on another rank: "
                       + std::to_string(across),
                   across > 0);
  }

  // 0. The pinned corner, on which every slave depends, moved by c with every U at zero: a
  // rigid translation. Its first Newton correction must carry c through the slaves' columns
  // of the reduced tangent (the lifting of a Dirichlet master), so each step converges in one
  // iteration; without that coupling it would move the corner node alone.
  const std::array<double, 3> c = {0.1, -0.2, 0.3};
  auto move_corner = [&](double t)
  {
    for (int k = 0; k < 3; ++k)
      cell.pin[k]->x()->set(t * c[k]);
  };
  const int iterations = solve(cell,
                               [&](double t)
                               {
                                 move_corner(t);
                                 for (const auto& row : cell.U)
                                   for (int k : row)
                                     cell.mpc->prescribe_macro(k, 0);
                               })
                             .most_per_step;
  checks.require(p + "translated corner: Newton iterations per step " + std::to_string(iterations)
                     + " (at most 1)",
                 iterations <= 1);
  checks.absolute(p + "translated corner: max |u - c|", homogeneous_error(cell, {1, 1, 1}, c), 0,
                  tol);
  move_corner(0);

  // 1. Triaxial stretch, every macro prescribed
  const std::array<double, 3> triaxial = {1.2, 0.9, 1.1};
  solve(cell,
        [&](double t)
        {
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              cell.mpc->prescribe_macro(cell.U[i][j], i == j ? t * (triaxial[i] - 1) * L[i] : 0);
        });
  checks.absolute(p + "triaxial: max |u - (F - I) X|", homogeneous_error(cell, triaxial), 0, tol);
  if (element == Element::p2_p1)
  {
    const double J = triaxial[0] * triaxial[1] * triaxial[2];
    auto [p_min, p_max] = gelx::test::value_range(*gelx::collapse_sub_function(*cell.u, 1));
    checks.relative(p + "triaxial: smallest pressure against K (J - 1)", p_min, K * (J - 1), tol);
    checks.relative(p + "triaxial: largest pressure against K (J - 1)", p_max, K * (J - 1), tol);
  }
  for (int k = 0; k < 3; ++k)
    checks.relative(p + "triaxial: macro force of U_" + std::to_string(k) + std::to_string(k)
                        + " (face resultant P_kk A_k)",
                    cell.mpc->macro_force(cell.U[k][k]), face_force(triaxial, k), tol);

  // 2. Uniaxial stress by a prescribed U_zz, the rest free with no load
  const double lambda = 1.3, mu = lateral_stretch(lambda);
  const std::array<double, 3> uniaxial = {mu, mu, lambda};
  auto check_uniaxial = [&](const std::string& how)
  {
    auto stretch = [&](int k) { return 1 + cell.mpc->macro_value(cell.U[k][k]) / L[k]; };
    checks.relative(p + how + ": lateral stretch 1 + U_xx / L0", stretch(0), mu, tol);
    checks.relative(p + how + ": lateral stretch 1 + U_yy / L1", stretch(1), mu, tol);
    checks.relative(p + how + ": axial stretch 1 + U_zz / L2", stretch(2), lambda, tol);
    double shear = 0;
    for (auto [i, j] : {std::pair{0, 1}, {0, 2}, {1, 2}})
      shear = std::max(shear, std::abs(cell.mpc->macro_value(cell.U[i][j])));
    checks.absolute(p + how + ": largest free shear macro |U_ij|, i < j", shear, 0, tol);
    checks.absolute(p + how + ": max |u - (F - I) X|", homogeneous_error(cell, uniaxial), 0, tol);
    checks.relative(p + how + ": macro force of U_zz against P_zz A_z",
                    cell.mpc->macro_force(cell.U[2][2]), face_force(uniaxial, 2), tol);
  };
  const auto stretch_zz = [&](double t)
  {
    release_upper(cell);
    cell.mpc->prescribe_macro(cell.U[2][2], t * (lambda - 1) * L[2]);
  };
  solve(cell, stretch_zz);
  check_uniaxial("uniaxial, prescribed U_zz");
  if (element == Element::p2_p1)
  {
    // 2b. The same by the fieldsplit linear solver (Schur complement of p; LU on u, so that
    // it is exact up to FGMRES's 1e-10): the free macro unknowns are neither displacement
    // nor pressure dofs, and belong to u's block. (Not state 3: with U_zz free too, a uniform
    // dilation costs no deviatoric energy, and u's block is singular)
    gelx::set_default_options("split_", {{"linear_solver", "fieldsplit"},
                                         {"fieldsplit_u_pc_type", "lu"}});
    const Iterations split = solve(cell, stretch_zz, "split_");
    check_uniaxial("uniaxial, prescribed U_zz, fieldsplit");
    checks.require(p + "fieldsplit: " + std::to_string(split.linear)
                       + " Krylov iterations for " + std::to_string(split.newton)
                       + " Newton iterations (at least two each: the split, not LU, solved)",
                   split.newton > 0 && split.linear >= 2 * split.newton);
  }

  // 3. The same state from a macro force on a free U_zz
  const double force = face_force(uniaxial, 2);
  solve(cell,
        [&](double t)
        {
          release_upper(cell);
          cell.mpc->load_macro(cell.U[2][2], t * force);
        });
  check_uniaxial("uniaxial, macro force on U_zz");

  // 4. No macro stretch, no load: nothing moves
  solve(cell, [&](double) { release_upper(cell); });
  double largest = 0;
  for (const auto& row : cell.U)
    for (int k : row)
      largest = std::max(largest, std::abs(cell.mpc->macro_value(k)));
  checks.absolute(p + "unloaded: largest |U|", largest, 0, 1e-14);
  checks.absolute(p + "unloaded: max |u|", homogeneous_error(cell, {1, 1, 1}), 0, 1e-14);
}

/// `f` must throw std::runtime_error with `expected` in its message (on every rank).
void expect_error(gelx::test::Checks& checks, const std::string& what,
                  const std::function<void()>& f, const std::string& expected)
{
  try
  {
    f();
    checks.require(what + ": no error", false);
  }
  catch (const std::runtime_error& e)
  {
    checks.require(what + ": \"" + e.what() + "\"",
                   std::string(e.what()).find(expected) != std::string::npos);
  }
}

void check_bad_input(gelx::test::Checks& checks, MPI_Comm comm)
{
  expect_error(
      checks, "periodic pair with a wrong offset",
      [&]
      {
        Cell cell = pinned_cell(comm, Element::p1, 2);
        constexpr int none = gelx::MultipointConstraint::no_macro;
        cell.mpc->periodic(*cell.facets, x_min, x_max, {1.1 * L[0], 0, 0}, {none, none, none});
      },
      "has no partner");
  expect_error(
      checks, "the pinned corner made a slave",
      [&]
      {
        Cell cell = pinned_cell(comm, Element::p1, 2);
        const int k = cell.mpc->add_macro();
        cell.mpc->periodic(*cell.facets, x_max, x_min, {-L[0], 0, 0}, {k, k, k});
      },
      "is both a slave and a Dirichlet dof");
  expect_error(
      checks, "two dofs constrained to each other",
      [&]
      {
        Cell cell = pinned_cell(comm, Element::p1, 2);
        // Two owned dofs that are not pinned: components x and y of an owned node off X = 0
        const std::vector<double> X = cell.V->tabulate_dof_coordinates(false);
        std::int32_t node = cell.V->dofmap()->index_map->size_local() - 1;
        while (std::hypot(X[3 * node], X[3 * node + 1], X[3 * node + 2]) < 1e-10)
          --node;
        const std::int64_t a = cell.mpc->global_dof(3 * node);
        const std::int64_t b = cell.mpc->global_dof(3 * node + 1);
        cell.mpc->add_constraint(a, {{b, 1.0}}, {});
        cell.mpc->add_constraint(b, {{a, 2.0}}, {});
        cell.mpc->finalize();
      },
      "form a cycle");
}

/// Median wall time of `repeats` calls of f.
double median_time(MPI_Comm comm, int repeats, const std::function<void()>& f)
{
  std::vector<double> times;
  for (int i = 0; i < repeats; ++i)
  {
    MPI_Barrier(comm);
    const double start = MPI_Wtime();
    f();
    MPI_Barrier(comm);
    times.push_back(MPI_Wtime() - start);
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

/// One assembly (residual + tangent) and one direct solve, reduced against unconstrained.
void measure_cost(MPI_Comm comm)
{
  Cell cell = periodic_cell(comm, Element::p2, 6);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      cell.mpc->prescribe_macro(cell.U[i][j], i == j ? 0.01 * L[i] : 0);
  // The unconstrained problem on the same space: the face x = 0 clamped instead
  gelx::DirichletConditions clamp(cell.V, cell.facets);
  clamp.clamp(gelx::test::x_min);
  gelx::NonlinearProblem plain(cell.u, cell.forms.residual, cell.forms.tangent, clamp.bcs());

  // A Newton iteration refactors the tangent: time assembly alone and assembly + solve
  // (KSPSolve after a new tangent redoes the numeric factorisation), the solve is the rest
  auto time = [&](gelx::NonlinearSystem& system, const std::string& prefix)
  {
    KSP ksp = gelx::create_linear_solver(comm, prefix);
    Mat A = system.create_matrix();
    Vec r = system.create_vector(), du = system.create_vector();
    auto assemble = [&]
    {
      system.residual(r);
      system.tangent(A);
    };
    const double assembly = median_time(comm, 5, assemble);
    const double iteration = median_time(comm, 5,
                                         [&]
                                         {
                                           assemble();
                                           GELX_PETSC(KSPSetOperators(ksp, A, A));
                                           GELX_PETSC(KSPSolve(ksp, r, du));
                                         });
    MatInfo info;
    GELX_PETSC(MatGetInfo(A, MAT_GLOBAL_SUM, &info));
    // Entries in the LU factors (MUMPS INFOG(29)): the solve's cost follows the fill
    PC pc;
    Mat factor;
    PetscInt factor_entries;
    GELX_PETSC(KSPGetPC(ksp, &pc));
    GELX_PETSC(PCFactorGetMatrix(pc, &factor));
    GELX_PETSC(MatMumpsGetInfog(factor, 29, &factor_entries));
    KSPDestroy(&ksp);
    MatDestroy(&A);
    VecDestroy(&r);
    VecDestroy(&du);
    return std::tuple{assembly, iteration - assembly, info.nz_used, factor_entries};
  };
  const auto [plain_assembly, plain_solve, plain_nz, plain_lu] = time(plain, "cost_plain_");
  const auto [reduced_assembly, reduced_solve, reduced_nz, reduced_lu]
      = time(*cell.mpc, "cost_reduced_");
  if (dolfinx::MPI::rank(comm) == 0)
    std::printf("COST P2 6x6x6 (%lld dofs, %lld slaves, %d ranks): unconstrained assembly "
                "%.4f s + solve %.4f s = %.4f s (%.0f nonzeros, %lld in LU); reduced assembly "
                "(incl. MatPtAP) %.4f s + solve %.4f s = %.4f s (%.0f nonzeros, %lld in LU); "
                "ratio %.2f\n",
                (long long)(3 * cell.V->dofmap()->index_map->size_global()),
                (long long)cell.mpc->num_slaves(), dolfinx::MPI::size(comm), plain_assembly,
                plain_solve, plain_assembly + plain_solve, plain_nz, (long long)plain_lu,
                reduced_assembly, reduced_solve, reduced_assembly + reduced_solve, reduced_nz,
                (long long)reduced_lu,
                (reduced_assembly + reduced_solve) / (plain_assembly + plain_solve));
}
} // namespace

int main(int argc, char* argv[])
{
  return gelx::test::run_checks(argc, argv, [](MPI_Comm comm, gelx::test::Checks& checks)
  {
    for (Element element : {Element::p1, Element::p2, Element::p2_p1})
      check_cell(checks, comm, element);
    check_bad_input(checks, comm);
    measure_cost(comm);
  });
}
