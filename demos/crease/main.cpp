// gelx scene: crease — a gel layer bonded to a rigid substrate swells until its surface folds
//
// Sample runs:
//   ./gelx run crease
//   ./gelx run crease --nx 30 --nz 15          # finer (40 x 20 stalls: README.md)
//   ./gelx run crease --chi_end 0.3 -arclength_ds_max 2
//
// The Flory-Rehner gel of forms/crease.py (thesis Eq. 4.28) in a plane-strain slab
// 0 <= x <= W, 0 <= z <= H of a wide layer, one Q2 hexahedron thick in y between rollers.
// The reference state is the gel swollen freely to the stretch lambda0 from dry, in pure
// solvent (mu = 0) at chi = chi_free(phi0), stress-free; in that state it was bonded to the
// substrate at z = 0. Lowering chi (a temperature change through chi(T)) makes the gel take
// up more solvent, slowly: the solvent is at equilibrium, mu = 0 throughout, at every chi (the
// drained limit, no time). The substrate holds the layer laterally, so it swells in thickness
// only and its surface is compressed: flat at first, it folds into a crease at a swelling
// ratio h/H that Hong, Zhao and Suo (APL 95, 111901, 2009) put at 2.4 for an incompressible
// network (Biot's wrinkling instability of the flat surface: 3.4).
//
// A crease is a subcritical instability: the flat state stays stable past the threshold, and
// the fold nucleates at a defect. The slab's surface has one: a dip of depth imperfection H
// and width imperfection_width H at x = 0, a plane of symmetry (the slab is half of a period
// 2W of creases). chi is the load of an arc-length continuation (gelx::ArcLength), which
// follows the path through the limit point where the fold snaps in, and the inertia of each
// tangent counts the unstable modes. The run records per point the far-field swelling ratio
// h/H (at x = W), the valley's depth below it, and the gap between the surface and the plane
// x = 0, which closes when the fold's flanks meet. The surface's frictionless contact with
// that plane (gelx::RigidPlaneContact) keeps the path off it, and the path stops where the
// flanks touch (what going on needs: demos/crease/README.md).

#include "crease.h"

#include <gelx/common/collectives.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/io/mesh.h>
#include <gelx/io/program.h>
#include <gelx/io/progress.h>
#include <gelx/solvers/arclength.h>
#include <gelx/systems/boundary.h>
#include <gelx/systems/contact.h>
#include <gelx/systems/forms.h>
#include <gelx/systems/problem.h>
#include <theory/flory_rehner.h>

#include <cmath>
#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <dolfinx/fem/utils.h>

using namespace dolfinx;

namespace
{
/// The scene's parameters.
struct Slab
{
  double H = 1.0, W = 1.0; // thickness of the layer and width of the slab (mm)
  double imperfection = 1e-3;      // the dip's depth at x = 0, a fraction of H
  double imperfection_width = 0.1; // its Gaussian half-width, a fraction of H
  int nx = 20, nz = 10;            // hexahedra across the width and through the thickness
  double grading = 2; // cells shrink towards the fold (x = 0) and the surface (z = H)
  double n = 1e-3;    // N nu: the network's stiffness in kT/nu
  double lambda0 = 1.2;  // the reference state's stretch from dry
  double chi_end = 0.4;  // chi lowered to this
  double kT_nu = 137.0;  // kT / nu (MPa): water at 298 K, nu = 3e-29 m^3
  int max_steps = 300;
};

/// Where the surface z = H is, from its nodes (all ranks): the far field's height (at x = W),
/// the valley's (at x = 0) and the smallest x of a surface node off the plane x = 0.
struct Surface
{
  double far = 0, valley = 0, gap = 0;
};
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters, with their defaults and validity checks
  Slab p;
  gelx::Parameters prm;
  using P = gelx::Parameters;
  prm.bind("geometry", "H", p.H, "thickness of the layer in the reference state [mm]",
           P::positive);
  prm.bind("geometry", "W", p.W, "width of the slab, half the creases' period [mm]",
           P::positive);
  prm.bind("geometry", "imperfection", p.imperfection,
           "depth of the surface's dip at x = 0, a fraction of H (the defect the crease "
           "nucleates at)",
           [](double v) { return v >= 0 && v < 0.5 ? "" : "must be in [0, 0.5)"; });
  prm.bind("geometry", "imperfection_width", p.imperfection_width,
           "the dip's Gaussian half-width, a fraction of H", P::positive);
  prm.bind("mesh", "nx", p.nx, "hexahedra across the width", P::at_least_one);
  prm.bind("mesh", "nz", p.nz, "hexahedra through the thickness", P::at_least_one);
  prm.bind("mesh", "grading", p.grading,
           "cells shrink towards x = 0 and z = H: x = W s^grading, z = H (1 - (1 - s)^grading) "
           "for s evenly spaced in [0, 1] (1: even)",
           [](double v) { return v >= 1 ? "" : "must be at least 1"; });
  prm.bind("material", "n", p.n, "N nu: the network's stiffness in units of kT/nu",
           P::positive);
  prm.bind("material", "lambda0", p.lambda0,
           "stretch of the stress-free reference state from dry (> 1: phi0 = lambda0^-3)",
           [](double v) { return v > 1 ? "" : "must exceed 1 (the dry state is singular)"; });
  prm.bind("material", "kT_nu", p.kT_nu, "energy scale kT/nu [MPa]", P::positive);
  prm.bind("load", "chi_end", p.chi_end,
           "Flory's chi is lowered from chi_free(phi0), the reference state's, to this");
  prm.bind("continuation", "max_steps", p.max_steps, "largest number of arc-length steps",
           P::at_least_one);

  return gelx::run_program(argc, argv, "gelx-crease", prm, [&](gelx::Run& run)
  {
    const double phi0 = std::pow(p.lambda0, -3.0);
    const double chi0 = gelx::theory::chi_free(phi0, p.n);
    if (!(p.chi_end < chi0))
      throw gelx::InputError("--chi_end " + std::to_string(p.chi_end)
                             + " is not below chi_free(phi0) = " + std::to_string(chi0)
                             + ", the reference state's: the layer would not swell");

    // 2. The slab W x (one cell) x H, graded towards the fold and the surface, with the dip
    const gelx::TaggedMesh geo = gelx::box_mesh(
        run.comm(), {p.W, p.W / p.nx, p.H}, {std::size_t(p.nx), 1, std::size_t(p.nz)},
        mesh::CellType::hexahedron);
    std::span<double> X = geo.mesh->geometry().x();
    for (std::size_t i = 0; i < X.size(); i += 3)
    {
      const double s = X[i] / p.W, z = X[i + 2] / p.H;
      X[i] = p.W * std::pow(s, p.grading);
      const double dip = p.imperfection * std::exp(-std::pow(X[i] / (p.imperfection_width * p.H), 2));
      X[i + 2] = p.H * (1 - std::pow(1 - z, p.grading)) * (1 - dip);
    }

    // 3. The displacement from the reference state, where the gel is at rest in pure solvent.
    //    The solvent stays in equilibrium with the bath (mu = 0) at every point and every chi:
    //    no chemical potential is solved for (forms/crease.py)
    auto V = std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(functionspace_form_crease_residual, "u", geo.mesh));
    auto u = std::make_shared<fem::Function<double>>(V);
    gelx::FormBinding forms(geo.mesh, {{"u", u}},
                            {{"n", p.n}, {"phi0", phi0}, {"chi", chi0}, {"kT_nu", p.kT_nu}});

    // 4. Bonded at z = 0, rollers on x = 0 (the fold's plane of symmetry), x = W and the faces
    //    of y
    gelx::DirichletConditions supports(V, geo.facet_tags);
    supports.clamp(geo.tag("z_min"));
    supports.fix(geo.tag("x_min"), 0);
    supports.fix(geo.tag("x_max"), 0);
    supports.fix(geo.tag("y_min"), 1);
    supports.fix(geo.tag("y_max"), 1);
    gelx::NonlinearProblem problem(u, forms.form(form_crease_residual, {V}),
                                   forms.form(form_crease_tangent, {V, V}), supports.bcs(),
                                   forms.expression(expression_crease_margin));
    const auto chi_at = [&](double l) { return chi0 + l * (p.chi_end - chi0); };
    const auto set_load = [&](double l) { forms.set("chi", chi_at(l)); };

    // 5. The surface's nodes: reference coordinates of the displacement's dofs on z = H
    const std::vector<double> nodes = V->tabulate_dof_coordinates(false);
    const std::vector<std::int32_t> surface_nodes
        = fem::locate_dofs_topological(*V, 2, geo.facet_tags->find(geo.tag("z_max")));
    const double tolerance = 1e-9 * p.W;
    const auto surface = [&]
    {
      const std::span<const double> d = u->x()->array();
      const std::int32_t owned = V->dofmap()->index_map->size_local();
      double far = -INFINITY, valley = -INFINITY, gap = INFINITY;
      for (std::int32_t i : surface_nodes)
      {
        if (i >= owned)
          continue;
        const double x = nodes[3 * i] + d[3 * i], z = nodes[3 * i + 2] + d[3 * i + 2];
        if (nodes[3 * i] > p.W - tolerance)
          far = z;
        else if (nodes[3 * i] < tolerance)
          valley = z;
        else
          gap = std::min(gap, x);
      }
      double local[3] = {far, valley, -gap}, global[3];
      MPI_Allreduce(local, global, 3, MPI_DOUBLE, MPI_MAX, run.comm());
      return Surface{global[0], global[1], -global[2]};
    };

    // 6. Output: displacement per node, stress and local swelling ratio J per cell
    gelx::ResultsWriter& results = run.results(geo.mesh);
    gelx::FieldSet fields;
    fields.add("displacement", u);
    fields.add("cauchy_stress", forms.expression(expression_crease_stress));
    fields.add("swelling_ratio", forms.expression(expression_crease_swelling_ratio));
    run.summary = {{"num_dofs", V->dofmap()->index_map->size_global()
                                    * V->dofmap()->index_map_bs()},
                   {"phi0", phi0},
                   {"chi0", chi0}};

    // 7. The path: chi lowered by arc-length continuation. The arc length is measured in the
    //    2-norm of the dofs, where a displacement H at every dof has the length
    //    scale = H sqrt(dofs), and chi's load factor (0 to 1) weighted by psi = scale: steps
    //    from scale / 200 to scale / 20 (the whole path, h from H to about 4 H, is a few
    //    scales long). The corrector's tolerance |R| <= 1e-7 |dR/dlambda| (the residual of a
    //    change of chi by 1e-7 of its range): on 40 x 20 cells, at a critical point where
    //    both the tangent's eigenvalue nearest zero and its mode's load component vanish,
    //    Newton diverges even from predictors 1e-9 |dR/dlambda| off the path, so that only a
    //    tolerance above that lets the path creep on (1e-9 stopped it there; it stalls all
    //    the same: demos/crease/README.md). Every point's unstable modes from the tangent's
    //    inertia (its LDL^T factorisation, which the predictor makes anyway)
    const double scale = p.H * std::sqrt(double(run.summary["num_dofs"]));
    const auto text = [](double v) { return std::to_string(v); };
    gelx::set_default_options("arclength_", {{"ds", text(scale / 200)},
                                             {"ds_max", text(scale / 20)},
                                             {"psi", text(scale)},
                                             {"rtol", "1e-7"},
                                             {"stability", "inertia"}});
    // The fold's flanks meet at x = 0, where the surface meets its mirror image: the surface's
    // contact with that plane keeps every point of the path off it, so the path approaches
    // the touch (its arc length cut back at the plane) instead of stepping through it
    gelx::RigidPlaneContact fold(problem, V, *geo.facet_tags, geo.tag("z_max"), 0, +1);
    constexpr double touching = 1e-6; // a gap below this fraction of H: the flanks touch
    gelx::ArcLength continuation(run.comm(), fold, set_load);
    gelx::PathState path = run.start_path(fold);
    Surface last = surface(); // a restarted run's last point, for the stop test
    continuation.run(
        path, p.max_steps,
        {[&](const gelx::StepRecord& pt, gelx::PathState& state)
         {
           last = surface();
           nlohmann::json quantities = {{"chi", chi_at(pt.load)},
                                        {"swelling_ratio", last.far / p.H},
                                        {"valley_depth", last.far - last.valley},
                                        {"fold_gap", last.gap}};
           quantities.update(gelx::stability_columns(pt));
           results.write_fields(pt.step, fields.update());
           nlohmann::json row = gelx::step_columns(pt);
           row.update({{"arc_length", pt.arc_length}, {"limit_point", pt.limit_point}});
           row.update(quantities);
           results.append_step(row);
           // The fold: where the path first turns back in chi (the snap), and where the
           // tangent first has a negative eigenvalue
           if (pt.limit_point && !state.scene.contains("fold"))
             state.scene["fold"] = quantities;
           if (pt.negative_eigenvalues > 0 && !state.scene.contains("unstable"))
             state.scene["unstable"] = quantities;
           for (const char* event : {"fold", "unstable"})
             if (state.scene.contains(event))
               run.summary[event] = state.scene[event];
           run.summary.update(quantities);
           run.summary["steps"] = pt.step;
         },
         gelx::ProgressLine(run.comm(),
                            {.load_name = "chi",
                             .load = [&](const gelx::StepRecord& s) { return chi_at(s.load); },
                             .quantity = [&] {
                               return gelx::quantity_text("h/H", last.far / p.H);
                             },
                             // chi turns back at the fold: no estimate of the time left
                             .fraction = [](const gelx::StepRecord&) { return NAN; }}),
         run.checkpoints()},
        [&](const gelx::StepRecord& pt)
        {
          if (last.gap > touching * p.H)
            return pt.load >= 1;
          if (dolfinx::MPI::rank(run.comm()) == 0)
            std::printf("gelx-crease: the fold's flanks meet the plane x = 0 at step %d "
                        "(chi = %.6g, h/H = %.6g); the path stops here (what going on needs: "
                        "demos/crease/README.md)\n",
                        pt.step, chi_at(pt.load), last.far / p.H);
          run.summary["self_contact"] = {{"chi", chi_at(pt.load)},
                                         {"swelling_ratio", last.far / p.H}};
          return true;
        });
  });
}
