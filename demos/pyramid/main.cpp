// gelx scene: pyramid — an elastomeric pyramid pen pressed onto a rigid substrate (thesis ch. 2)
//
// Sample runs:
//   ./gelx run pyramid
//   ./gelx run pyramid --order 2 --cells 2
//   ./gelx run pyramid --W 12 --t 8 --np 2
//   ./gelx run pyramid --law le
//   ./gelx run pyramid --domain eighth
//
// A pyramid of base width L and height H = L/sqrt(2) (semi-apex angle arctan(1/sqrt(2)), the
// {111} facets of a silicon mould) stands on a base of thickness t in a square array of period
// W; the base is bonded to a rigid backing. A rigid, frictionless substrate first touches the
// apex and then moves toward the base by d. The elastomer is incompressible neo-Hookean
// (Eq. 1.10; or Mooney-Rivlin or linear elastic, --law) in mixed u-p form on Q1-P0 hexahedra,
// the thesis' hybrid bricks, or Q2-Q1 (--order 2).
// By symmetry one quarter of the unit cell is modelled (pyramid_mesh.h: a structured hexahedral
// tip graded toward the apex, after thesis Fig. 2.2b), or the eighth, the wedge between the
// quarter's mirror plane y = 0 and its diagonal mirror plane x = y (--domain eighth: slip on
// the diagonal by a multipoint constraint, gelx::MultipointConstraint). The contact is an
// exact active set on the nodes of the lateral faces (gelx::RigidPlaneContact). Per step we
// record the force f, the contact width l_c (the patch's extent along a base edge) and area
// A_c; the thesis finds l_c/L = 0.86 d/H (Fig. 2.3b) and l_c ∝ f^(1/2) (Fig. 2.4a). The
// deformed lateral faces are written as STL per step (surface/), for optics codes.

#include "pyramid.h"

#include <cstdio>
#include <gelx/solvers/load_stepping.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/systems/problem.h>
#include <gelx/io/program.h>

namespace
{
/// Least-squares line y = a x + b and its coefficient of determination R^2.
struct Fit
{
  double slope, intercept, r2;
};

Fit fit_line(const std::vector<double>& x, const std::vector<double>& y)
{
  if (x.size() < 3)
    return {NAN, NAN, NAN};
  const double n = x.size();
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
    syy += y[i] * y[i];
  }
  const double cxx = sxx - sx * sx / n, cxy = sxy - sx * sy / n, cyy = syy - sy * sy / n;
  const double slope = cxy / cxx;
  return {slope, (sy - slope * sx) / n, cxy * cxy / (cxx * cyy)};
}

/// The contact width l_c/L against d/H over the loading steps with a patch (width > 0), with
/// the corner located by the level set and by the gap's 3/2 law (ContactMeasures). It is kept
/// in the path's state, so that a restarted run continues it.
struct WidthCurve
{
  std::vector<double> d, width, width_gap_law, sqrt_force;
  Fit by_d() const { return fit_line(d, width); }
  Fit by_d_gap_law() const { return fit_line(d, width_gap_law); }
  Fit by_sqrt_force() const { return fit_line(sqrt_force, width); }
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(WidthCurve, d, width, width_gap_law, sqrt_force)

/// How the substrate moves.
struct Loading
{
  double d_max = 0.8;  ///< final indentation d/H
  bool unload = false; ///< back to d = 0 after d_max
  /// Also run the next coarser mesh for the Richardson limit of the slope
  bool extrapolate = true;
  /// d/H at load factor s: s d_max, or (1 - |1 - 2 s|) d_max when unloading
  double d_over_H(double s) const { return (unload ? 1 - std::abs(1 - 2 * s) : s) * d_max; }
};

/// Press the pyramid as `loading` says, in the steps of `stepping`, from `path` (a new one, or
/// a restarted run's): after each completed step the width curve in the path's state is
/// extended (loading steps), `record(step, d/H, measures)` is called, then `checkpoints`.
/// Returns the curve; throws ConvergenceError when a step fails.
WidthCurve press(gelx::scenes::PressedPyramid& pyramid, const Loading& loading,
                 const gelx::LoadSteppingOptions& stepping, double L,
                 const std::function<void(const gelx::StepRecord&, double,
                                          const gelx::scenes::ContactMeasures&)>& record,
                 gelx::PathState path = {}, const gelx::StepObserver& checkpoints = nullptr)
{
  gelx::NewtonSolver newton(pyramid.mesh().mesh->comm());
  double width = 0; // the last step's l_c/L (gap law), for the progress line
  gelx::ProgressLine progress(
      pyramid.mesh().mesh->comm(),
      {.load_name = "d/H",
       .load = [&](const gelx::StepRecord& r) { return loading.d_over_H(r.load); },
       .quantity = [&] { return gelx::quantity_text("l_c/L", width); }});
  gelx::LoadStepper(pyramid.system(), newton, stepping,
                    [&](double s) { pyramid.set_indentation(loading.d_over_H(s) * pyramid.height()); })
      .run(path,
           {[&](const gelx::StepRecord& step, gelx::PathState& state)
            {
              const auto measures = pyramid.measure(); // also refreshes the displacement
              const double d = loading.d_over_H(step.load);
              auto curve = state.scene.value("width_curve", WidthCurve{});
              if (measures.width > 0 && !(loading.unload && step.load > 0.5))
              {
                curve.d.push_back(d);
                curve.width.push_back(measures.width / L);
                curve.width_gap_law.push_back(measures.width_gap_law / L);
                curve.sqrt_force.push_back(std::sqrt(measures.force));
              }
              state.scene["width_curve"] = curve;
              record(step, d, measures);
              width = measures.width_gap_law / L;
              progress(step, state);
              if (checkpoints)
                checkpoints(step, state);
            }});
  return path.scene.value("width_curve", WidthCurve{});
}
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters (lengths in um, moduli in MPa, forces in uN)
  gelx::scenes::PyramidGeometry g;
  gelx::scenes::PyramidMaterial m;
  Loading loading;
  gelx::LoadSteppingOptions stepping;
  // Steps of 0.0125 H growing to 0.025 H (at d_max = 0.8): the patch gains a ring of nodes in
  // a few steps, and each change of the active set costs Newton iterations
  stepping.dt = 1.0 / 64;
  stepping.dt_max = 1.0 / 32;
  gelx::Parameters prm;
  prm.bind("geometry", "L", g.L, "pyramid base width (um)", gelx::Parameters::positive);
  prm.bind("geometry", "W", g.W, "array period, unit cell width (um, > L)",
           gelx::Parameters::positive);
  prm.bind("geometry", "t", g.t, "base thickness (um)", gelx::Parameters::positive);
  prm.bind("mesh", "cells", g.cells, "hexahedra along each edge of a pyramid block",
           gelx::Parameters::at_least_one);
  prm.bind("mesh", "tip_levels", g.tip_levels, "apex refinement levels (cuts at H/2, H/4, ...)",
           [](int v) { return v >= 0 ? "" : "must not be negative"; });
  prm.bind("mesh", "growth", g.growth, "cell size ratio in the base, away from the pyramid",
           [](double v) { return v >= 1 ? "" : "must be at least 1"; });
  prm.bind("mesh", "domain", g.domain,
           "quarter: the quarter cell with mirror planes x = 0, y = 0; eighth: the wedge "
           "0 <= y <= x with slip on the diagonal plane x = y; half: the half x >= 0",
           [](const std::string& v)
           {
             const bool known = v == "quarter" || v == "eighth" || v == "half";
             return known ? "" : "must be quarter, eighth or half";
           });
  prm.bind("mesh", "base", g.base,
           "corner: the base's top meshed with a block at the cell corner; diagonal: with the "
           "diagonal x = y as a mesh line (needed by the eighth)",
           [](const std::string& v)
           { return v == "corner" || v == "diagonal" ? "" : "must be corner or diagonal"; });
  prm.bind("mesh", "order", m.order, "displacement degree: 2 (Q2-Q1) or 1 (Q1-P0)",
           [](int v) { return v == 1 || v == 2 ? "" : "must be 1 or 2"; });
  prm.bind("material", "law", m.law,
           "nh neo-Hookean, mr Mooney-Rivlin, le small-strain linear elastic (all incompressible)",
           [](const std::string& v)
           { return v == "nh" || v == "mr" || v == "le" ? "" : "must be nh, mr or le"; });
  prm.bind("material", "G", m.G, "initial shear modulus (MPa)", gelx::Parameters::positive);
  prm.bind("material", "mooney_share", m.mooney_share,
           "Mooney-Rivlin C01 / (C10 + C01), with C10 + C01 = G/2 (law mr)",
           [](double v) { return v >= 0 && v < 1 ? "" : "must be in [0, 1)"; });
  prm.bind("output", "extrapolate", loading.extrapolate,
           "also run the next coarser mesh for the Richardson limit of the slope");
  prm.bind("loading", "unload", loading.unload,
           "after reaching d_max, move the substrate back to d = 0 (the fits use the loading half)");
  prm.bind("loading", "d_max", loading.d_max, "final indentation d/H",
           [](double v) { return v > 0 && v < 1 ? "" : "must be in (0, 1)"; });
  stepping.bind(prm);

  return gelx::run_program(argc, argv, "gelx-pyramid", prm, [&](gelx::Run& run)
  {
    if (g.W <= g.L)
      throw gelx::InputError("the array period W must exceed the pyramid width L");
    if (g.domain == "eighth" && g.base != "diagonal")
      throw gelx::InputError("the eighth needs the base meshed along the diagonal "
                             "(--base diagonal)");
    stepping.check();
    // Full Newton steps (still halved if an element inverts): when nodes enter or leave the
    // active set the residual norm jumps, and a decrease test then stalls the semismooth
    // Newton method in tiny steps (measured: 22 iterations at d/H = 0.1 against 5-7)
    gelx::set_default_option("newton_", "snes_linesearch_type", "basic");
    gelx::set_default_option("newton_", "snes_max_it", "40");

    // 2. The modelled part of the cell: mesh, material, symmetry, contact
    gelx::scenes::PressedPyramid pyramid(run.comm(), g, m);

    // 3. Press, writing every step's fields, STL surface and measures
    gelx::ResultsWriter& results = run.results(pyramid.mesh().mesh, gelx::micrometre);
    gelx::FieldSet fields;
    fields.add("cauchy_stress", pyramid.stress());
    fields.add("energy_density", pyramid.energy_density());
    fields.add("displacement", pyramid.displacement());
    for (const auto& f : pyramid.contact_fields())
      fields.add(f->name, f);
    PetscInt num_unknowns; // the dofs less the eighth's slip-constrained ones
    GELX_PETSC(VecGetSize(pyramid.system().unknowns(), &num_unknowns));
    run.summary = {{"num_dofs", pyramid.state()->function_space()->dofmap()->index_map->size_global()},
                   {"num_unknowns", num_unknowns},
                   {"num_cells", pyramid.mesh().mesh->topology().index_map(3)->size_global()}};
    const WidthCurve curve = press(
        pyramid, loading, stepping, g.L,
        [&](const gelx::StepRecord& step, double d, const gelx::scenes::ContactMeasures& c)
        {
          results.write_fields(d, fields.update());
          char stl[32];
          std::snprintf(stl, sizeof(stl), "surface/step_%03d.stl", step.step);
          results.write_stl(stl, pyramid.contact_side_surface(*fields.nodal("displacement")));
          const double area_ratio = c.width > 0 ? c.area / (c.width * c.width) : 0;
          nlohmann::json row = gelx::step_columns(step);
          row.update({{"d_over_H", d},
                               {"force", c.force},
                               {"strain_energy", pyramid.strain_energy()},
                               {"contact_width_over_L", c.width / g.L},
                               {"contact_width_over_L_gap_law", c.width_gap_law / g.L},
                               {"contact_area", c.area},
                               {"area_over_width_squared", area_ratio},
                               {"active_nodes", c.active},
                               {"max_penetration", c.penetration},
                               {"elapsed", run.elapsed()}});
          results.append_step(row);
          run.summary.update({{"final_d_over_H", d},
                              {"final_force", c.force},
                              {"final_contact_width_over_L", c.width / g.L},
                              {"final_contact_width_over_L_gap_law", c.width_gap_law / g.L},
                              {"area_ratio", c.width > 0 ? area_ratio : NAN},
                              {"max_penetration", c.penetration},
                              {"newton_snes_type", step.newton.snes_type}});
        },
        run.start_path(pyramid.system()), run.checkpoints());
    const Fit by_d = curve.by_d(), by_d_gap_law = curve.by_d_gap_law(),
              by_f = curve.by_sqrt_force();
    run.summary.update({{"slope_lc_vs_d", by_d.slope},
                        {"intercept_lc_vs_d", by_d.intercept},
                        {"slope_lc_vs_d_gap_law", by_d_gap_law.slope},
                        {"intercept_lc_vs_d_gap_law", by_d_gap_law.intercept},
                        {"r2_lc_vs_d", by_d.r2},
                        {"slope_lc_vs_sqrtf", by_f.slope},
                        {"r2_lc_vs_sqrtf", by_f.r2},
                        {"wall_time", run.elapsed()}});

    // 4. The patch at the last step (x, y, nodal contact force, in contact), for the pressure
    //    map; measured here, as a run restarted from its last checkpoint took no step
    pyramid.measure();
    std::vector<nlohmann::json> patch; // collective; the nodes are on rank 0
    for (const auto& [x, y, f, in_contact] : pyramid.patch())
      patch.push_back({{"x", x}, {"y", y}, {"force", f}, {"in_contact", in_contact}});
    results.write_table("patch.csv", patch);

    // 5. The slope's discretisation error: the level set's corner is resolved to a fraction of
    //    the node spacing, so its slope converges at first order in the cell size h ~ 1/cells
    //    at best (measured: order 0.6-1; demos/pyramid/README.md). The same run on the next
    //    coarser mesh gives its Richardson limit cells s_c - (cells - 1) s_(cells-1). (The gap
    //    law's corner is located inside the element; its slope, reported beside, is not
    //    extrapolated.)
    double slope_extrapolated = NAN;
    if (loading.extrapolate && g.cells > 1)
    {
      gelx::scenes::PyramidGeometry coarse = g;
      coarse.cells = g.cells - 1;
      gelx::scenes::PressedPyramid coarse_pyramid(run.comm(), coarse, m);
      const WidthCurve coarse_curve = press(coarse_pyramid, loading, stepping, g.L, [](auto&&...) {});
      slope_extrapolated = g.cells * by_d.slope - (g.cells - 1) * coarse_curve.by_d().slope;
    }
    run.summary.update({{"slope_lc_vs_d_extrapolated", slope_extrapolated},
                        {"wall_time_with_extrapolation", run.elapsed()}});
  });
}
