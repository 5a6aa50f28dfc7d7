// Verification: frictionless contact with a rigid plane (gelx::RigidPlaneContact) against Hertz.
//
// A spherical cap of radius R = 1 on a block of width 4R clamped at its top (meshes/hertz.geo),
// incompressible neo-Hookean (G = 1, mixed P2-P1), is pressed onto the plane z = d, which moves
// up from the apex to d = 0.02 R. The block makes the body look like Hertz's half-space from
// the contact: a hemisphere clamped (or sliding) at its equator is stiffer by the half-space's
// displacement at distance R, measured +10% (+4.5%) on the force at this d/R, whereas the finite
// body's error here is O(a/L) with L = 4R. At small indentation the patch is a disc of radius
// a = sqrt(R d) and the force F = (4/3) E* R^(1/2) d^(3/2) with E* = E/(1 - nu^2) = 4G for an
// incompressible solid: F = (16/3) G R^(1/2) d^(3/2).
//
// Checked: force and contact radius within 3% of Hertz on the finest mesh, with the force error
// shrinking under refinement of the contact zone; the patch's edge located inside the element
// by the gap's 3/2 law within 2% of Hertz's radius on every mesh; no node behind the plane;
// the quarter model (two symmetry planes) against the half model (one) on meshes of the same
// size; PETSc's bound-constrained Newton (ContactMethod::vi) against gelx's active set (the
// default): they solve the same discrete complementarity problem.
//
// usage: test_contact_hertz [SUMMARY.json [finest]] [PETSc options]: writes the finest quarter's
// force and radius to SUMMARY.json (for the comparison of rank counts). With `finest`, only the
// finest quarter and its checks against Hertz (the 2-rank run: what the comparison reads, at a
// third of the whole test's cost; the meshes' sequence, vi and the half model run at 1 rank).

#include "common.h"
#include "contact.h"
#include "mixed_tet.h"

#include <fstream>
#include <map>
#include <gelx/systems/boundary.h>
#include <gelx/systems/contact.h>
#include <gelx/solvers/load_stepping.h>
#include <gelx/systems/problem.h>
#include <gelx/io/mesh.h>
#include <gelx/systems/mixed.h>
#include <gelx/common/petsc_utils.h>
#include <nlohmann/json.hpp>
#include <slepcsys.h>

using namespace dolfinx;

namespace
{
constexpr double R = 1.0, G = 1.0, d_max = 0.02 * R;

struct Pressed
{
  double force = 0, radius = 0, penetration = 0;
  /// The patch's edge along the trace of the symmetry plane y = 0 (from the axis outward), by
  /// the level set's sign change and by the gap's 3/2 law (gelx::patch_edge_by_*)
  double radius_level_set = 0, radius_gap_law = 0;
  std::int64_t active_nodes = 0;
  int steps = 0, iterations = 0, cutbacks = 0;
  std::int64_t dofs = 0;
  double wall_time = 0;
};

/// What a run did, for the check labels.
std::string describe(const Pressed& p)
{
  return std::to_string(p.dofs) + " dofs, " + std::to_string(p.steps) + " steps, "
         + std::to_string(p.iterations) + " Newton iterations, " + std::to_string(p.cutbacks)
         + " cut-backs, " + std::to_string(p.active_nodes) + " nodes in contact, "
         + std::to_string(p.wall_time) + " s";
}

/// Press the quarter model (quarters = 1) or the half model (quarters = 2: the quarter's mesh
/// and its mirror image in x = 0, so that both models share their discrete solution).
Pressed press(MPI_Comm comm, double h_contact, int quarters, gelx::ContactMethod method)
{
  const double start = MPI_Wtime();
  auto geo = gelx::read_geo(comm, GELX_MESHES "/hertz.geo",
                            {{"R", R}, {"h_contact", h_contact}, {"quarters", 1}},
                            quarters == 2 ? std::vector<int>{0} : std::vector<int>{});
  auto W = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_mixed_tet_residual_nh, "w", geo.mesh));
  auto w = std::make_shared<fem::Function<double>>(W);
  const gelx::test::Constants constants
      = {{"G", std::make_shared<fem::Constant<double>>(G)},
         {"bulk_compliance", std::make_shared<fem::Constant<double>>(0.0)}};
  auto forms = gelx::test::make_forms(form_mixed_tet_residual_nh, form_mixed_tet_tangent_nh, W,
                                      {{"w", w}}, constants);
  auto displacement = W->sub({0});
  gelx::DirichletConditions bcs(displacement, geo.facet_tags);
  bcs.clamp(geo.tag("top"));
  if (quarters <= 2)
    bcs.fix(geo.tag("sym_y"), 1);
  if (quarters == 1)
    bcs.fix(geo.tag("sym_x"), 0);
  bcs.update(0);
  gelx::NonlinearProblem problem(
      w, forms.residual, forms.tangent, bcs.bcs(),
      gelx::test::make_expression(expression_mixed_tet_det_F, {{"w", w}}, {}, geo.mesh));
  gelx::RigidPlaneContact contact(problem, displacement, *geo.facet_tags, geo.tag("contact"), 2,
                                  +1, method);

  gelx::NewtonSolver newton(comm);
  gelx::LoadSteppingOptions steps;
  steps.dt = 0.25;
  steps.dt_max = 0.5;
  Pressed p;
  gelx::LoadStepper(contact, newton, steps, [&](double t) { contact.set_position(t * d_max); })
      .run(
          [&](const gelx::StepRecord& s, gelx::PathState&)
          {
            ++p.steps;
            p.iterations += s.newton.iterations;
            p.cutbacks += s.cutbacks;
          });

  const gelx::ContactState state = contact.state();
  const double copies = 4.0 / quarters; // of the modelled part in the whole hemisphere
  p.force = copies * state.force;
  p.penetration = state.max_penetration;
  p.active_nodes = state.active;
  p.dofs = W->dofmap()->index_map->size_global();

  // The patch area: where the contact level set is positive, on the current surface
  auto u = gelx::collapse_sub_function(*w, 0);
  contact.contact_level_set();
  auto area_form = contact.area_form(*form_contact_contact_area, u);
  p.radius = std::sqrt(copies * gelx::assemble_global_scalar(*area_form) / M_PI);
  const auto trace = contact.nodes_on_line(
      [](const gelx::RigidPlaneContact::Node& n) -> std::optional<std::pair<double, double>>
      {
        if (std::abs(n.X[1]) < 1e-10 * R)
          return std::make_pair(n.X[0], n.x[0]);
        return std::nullopt;
      });
  p.radius_level_set = gelx::patch_edge_by_level_set(trace);
  p.radius_gap_law = gelx::patch_edge_by_gap_law(trace);
  p.wall_time = MPI_Wtime() - start;
  return p;
}

/// The quarter's force error shrinks from the coarsest mesh to the finest, and the patch's edge
/// by the gap law stays on Hertz's radius on every mesh.
void check_refinement(gelx::test::Checks& checks, const std::map<double, Pressed>& quarter,
                      const std::vector<double>& force_errors, double a_hertz)
{
  checks.require("the force error shrinks under refinement ("
                     + std::to_string(force_errors.front()) + " -> "
                     + std::to_string(force_errors.back()) + ")",
                 force_errors.back() < force_errors.front());

  // The patch's edge inside the element (gelx::patch_edge_by_gap_law): Hertz's gap opens
  // like (r - a)^(3/2) outside the patch, the law the estimator assumes, so along the trace
  // of the plane y = 0 it must find Hertz's radius on every mesh, to within the 2 % by which
  // the finite neo-Hookean body's patch differs from Hertz's (the area's radius above: +1.9 %
  // on the finest mesh, +1.4 % on h_contact = 0.014), and vary across the meshes by under
  // 1 % of a, where the node spacing is a/3.5 to a/7. The level set's sign change on the
  // same nodes (patch_edge_by_level_set), resolved to the spacing, misses both (measured:
  // +2.8 %, -0.6 %, +0.1 %, a spread of 3.4 %; the gap law: +1.05 %, +0.94 %, +1.66 %).
  double lowest = INFINITY, highest = -INFINITY;
  for (const auto& [h, p] : quarter)
  {
    checks.relative("h_contact = " + std::to_string(h)
                        + ": the patch's edge on y = 0 by the gap's 3/2 law against Hertz",
                    p.radius_gap_law, a_hertz, 0.02);
    lowest = std::min(lowest, p.radius_gap_law);
    highest = std::max(highest, p.radius_gap_law);
  }
  checks.absolute("the gap law's edge: spread over the three meshes / a",
                  (highest - lowest) / a_hertz, 0, 0.01);
}

/// PETSc's bound-constrained Newton (SNES VI) against the active set, on the coarsest mesh.
void check_vi_against_active_set(MPI_Comm comm, gelx::test::Checks& checks,
                                 const Pressed& coarsest)
{
  // The comparison holds on any mesh; the finest would double the test's time. Both solve
  // the same discrete complementarity problem, each to |R| <= 1e-10 |R0| on the rows off the
  // plane (the VI's norm leaves out the rows held at the bound, the active set's rows there
  // are u_i - u_i* = 0): 1e-8 as for the half model (check_half_against_quarter). Only the same active set gives
  // agreement at that level; a node in tension left on the plane, or a node held off it,
  // changes the solution at the order of its force.
  const Pressed vi = press(comm, 0.04, 1, gelx::ContactMethod::vi);
  checks.absolute("coarsest mesh, vi (" + describe(vi) + "): largest penetration / d",
                  vi.penetration / d_max, 0, 1e-10);
  checks.relative("vi against the active set: force", vi.force, coarsest.force, 1e-8);
  checks.relative("vi against the active set: radius", vi.radius, coarsest.radius, 1e-8);
}

/// The quarter model against the half model (one symmetry plane instead of two) on the
/// coarsest mesh.
void check_half_against_quarter(MPI_Comm comm, gelx::test::Checks& checks,
                                const Pressed& same_size)
{
  // The half model's mesh is the quarter's and its mirror image, so the two share their discrete
  // solution: they agree to the Newton tolerance (|R| <= 1e-10 |R0| at every step), and 1e-8
  // relative leaves two digits for round-off, independently of either model's error against
  // Hertz. A wrong symmetry condition or copy count changes the force at O(1).
  const Pressed half = press(comm, 0.04, 2, gelx::ContactMethod::active_set);
  checks.relative("half model (" + std::to_string(half.dofs) + " dofs): force against the "
                      + "quarter's",
                  half.force, same_size.force, 1e-8);
  checks.relative("half model: radius against the quarter's", half.radius, same_size.radius,
                  1e-8);
  checks.require("half model: nodes in contact " + std::to_string(half.active_nodes)
                     + " between one and two quarters' ("
                     + std::to_string(same_size.active_nodes)
                     + "; the nodes on the mirror plane count once)",
                 half.active_nodes < 2 * same_size.active_nodes
                     && half.active_nodes > same_size.active_nodes);
}
} // namespace

int main(int argc, char* argv[])
{
  SlepcInitialize(&argc, &argv, nullptr, nullptr);
  int status;
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    gelx::test::Checks checks(comm);
    const double F_hertz = 16.0 / 3.0 * G * std::sqrt(R) * std::pow(d_max, 1.5);
    const double a_hertz = std::sqrt(R * d_max);

    // The contact zone (radius 0.25 R, 1.8 a) refined from 0.04 R (a / 3.5) to 0.02 R (a / 7)
    const bool finest_only = argc > 2 && std::string(argv[2]) == "finest";
    const std::vector<double> sizes
        = finest_only ? std::vector<double>{0.02} : std::vector<double>{0.04, 0.028, 0.02};
    std::vector<double> force_errors;
    std::map<double, Pressed> quarter;
    for (double h : sizes)
    {
      const Pressed& p = quarter[h] = press(comm, h, 1, gelx::ContactMethod::active_set);
      const std::string level
          = "quarter, h_contact = " + std::to_string(h) + " (" + describe(p) + ")";
      force_errors.push_back(std::abs(p.force / F_hertz - 1));
      checks.require(level + ": force " + std::to_string(p.force) + " vs Hertz "
                         + std::to_string(F_hertz) + ", radius " + std::to_string(p.radius)
                         + " (level set on y = 0: " + std::to_string(p.radius_level_set)
                         + ", gap law: " + std::to_string(p.radius_gap_law) + ") vs "
                         + std::to_string(a_hertz),
                     std::isfinite(p.force) && std::isfinite(p.radius));
      // An exact active set: every candidate node is on or in front of the plane
      checks.absolute(level + ": largest penetration / d", p.penetration / d_max, 0, 1e-10);
    }
    // 3% (the issue's bound): beyond the discretisation, the body's finite size (O(a/L),
    // L = 4R) and the neo-Hookean nonlinearity at a/R = 0.14 separate it from Hertz's linear
    // half-space; measured on h_contact = 0.014: force -0.86%, radius +1.4%.
    const Pressed& finest = quarter.at(0.02);
    checks.relative("finest mesh: contact force against Hertz", finest.force, F_hertz, 0.03);
    checks.relative("finest mesh: contact radius against Hertz", finest.radius, a_hertz, 0.03);
    if (!finest_only)
    {
      check_refinement(checks, quarter, force_errors, a_hertz);
      check_vi_against_active_set(comm, checks, quarter.at(0.04));
      check_half_against_quarter(comm, checks, quarter.at(0.04));
    }
    if (argc > 1 && argv[1][0] != '-' && dolfinx::MPI::rank(comm) == 0)
      std::ofstream(argv[1]) << nlohmann::json{{"status", "completed"},
                                               {"mpi_ranks", dolfinx::MPI::size(comm)},
                                               {"force", finest.force},
                                               {"radius", finest.radius}}
                                        .dump(2);
    status = checks.finish();
  }
  SlepcFinalize();
  return status;
}
