// gelx scene: pyramid — an elastomeric pyramid pen pressed onto a rigid substrate (thesis ch. 2)
//
// Sample runs:
//   ./gelx run pyramid
//   ./gelx run pyramid --order 2 --cells 2
//   ./gelx run pyramid --W 12 --t 8 --np 2
//   ./gelx run pyramid --law le
//
// A pyramid of base width L and height H = L/sqrt(2) (semi-apex angle arctan(1/sqrt(2)), the
// {111} facets of a silicon mould) stands on a base of thickness t in a square array of period
// W; the base is bonded to a rigid backing. A rigid, frictionless substrate first touches the
// apex and then moves toward the base by d. The elastomer is incompressible neo-Hookean
// (Eq. 1.10; or Mooney-Rivlin or linear elastic, --law) in mixed u-p form on Q1-P0 hexahedra,
// the thesis' hybrid bricks, or Q2-Q1 (--order 2).
// By symmetry one quarter of the unit cell is modelled (pyramid_mesh.h: a structured hexahedral
// tip graded toward the apex, after thesis Fig. 2.2b). The contact is an exact active set on
// the nodes of the lateral faces (gelx::RigidPlaneContact). Per step we record the force f,
// the contact width l_c (the patch's extent along a base edge) and area A_c; the thesis finds
// l_c/L = 0.86 d/H (Fig. 2.3b) and l_c ∝ f^(1/2) (Fig. 2.4a). The deformed lateral faces are
// written as STL per step (surface/), for optics codes.

#include "pyramid.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <gelx/load_stepping.h>
#include <gelx/newton.h>
#include <gelx/output.h>
#include <gelx/petsc_utils.h>
#include <gelx/program.h>

namespace
{
/// Least-squares line y = a x + b and its coefficient of determination R^2.
struct Fit
{
  double slope, intercept, r2;
};

Fit fit_line(const std::vector<double>& x, const std::vector<double>& y)
{
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

/// The contact width l_c/L against d/H over the steps of a run, and its fits.
struct WidthCurve
{
  std::vector<double> d, width, sqrt_force; ///< steps with a patch (width > 0)
  /// Least-squares lines of the width against d and against f^(1/2) (NaN: under 3 points)
  Fit by_d() const { return d.size() > 2 ? fit_line(d, width) : Fit{NAN, NAN, NAN}; }
  Fit by_sqrt_force() const
  {
    return d.size() > 2 ? fit_line(sqrt_force, width) : Fit{NAN, NAN, NAN};
  }
};

/// Press the pyramid: the substrate moves by d = s d_max H as the load factor s goes from 0
/// to 1 or, with `unload`, to d_max H and back to 0 (d = (1 - |1 - 2 s|) d_max H). After each
/// converged step `record(step, d/H, measures)` is called and the curve extended with the
/// loading steps. Returns "completed" or "failed: why" (the completed steps stay recorded).
std::string press(gelx::scenes::PressedPyramid& pyramid, const gelx::Parameters& prm,
                  WidthCurve& curve,
                  const std::function<void(const gelx::StepRecord&, double,
                                           const gelx::scenes::ContactMeasures&)>& record)
{
  const double d_max = prm.real("d_max"), H = pyramid.height(), L = prm.real("L");
  const bool unload = prm.flag("unload");
  auto d_over_H = [&](double s) { return (unload ? 1 - std::abs(1 - 2 * s) : s) * d_max; };
  gelx::NewtonSolver newton(pyramid.mesh().mesh->comm());
  try
  {
    gelx::LoadStepper(pyramid.system(), newton, gelx::LoadSteppingOptions::from(prm),
                      [&](double s) { pyramid.set_indentation(d_over_H(s) * H); })
        .run(
            [&](const gelx::StepRecord& step)
            {
              const auto measures = pyramid.measure(); // also refreshes the displacement
              const double d = d_over_H(step.t);
              if (measures.width > 0 && !(unload && step.t > 0.5))
              {
                curve.d.push_back(d);
                curve.width.push_back(measures.width / L);
                curve.sqrt_force.push_back(std::sqrt(measures.force));
              }
              record(step, d, measures);
            });
  }
  catch (const gelx::ConvergenceError& e)
  {
    return std::string("failed: ") + e.what();
  }
  return "completed";
}
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters (lengths in um, moduli in MPa, forces in uN)
  gelx::Parameters prm;
  const gelx::scenes::PyramidGeometry g0;
  prm.add("geometry", "L", g0.L, "pyramid base width (um)", gelx::Parameters::positive);
  prm.add("geometry", "W", g0.W, "array period, unit cell width (um, > L)",
          gelx::Parameters::positive);
  prm.add("geometry", "t", g0.t, "base thickness (um)", gelx::Parameters::positive);
  prm.add("mesh", "cells", g0.cells, "hexahedra along each edge of a pyramid block",
          gelx::Parameters::at_least_one);
  prm.add("mesh", "tip_levels", g0.tip_levels, "apex refinement levels (cuts at H/2, H/4, ...)",
          [](int v) { return v >= 0 ? "" : "must not be negative"; });
  prm.add("mesh", "growth", g0.growth, "cell size ratio in the base, away from the pyramid",
          [](double v) { return v >= 1 ? "" : "must be at least 1"; });
  const gelx::scenes::PyramidMaterial m0;
  prm.add("material", "law", m0.law.c_str(),
          "nh neo-Hookean, mr Mooney-Rivlin, le small-strain linear elastic (all incompressible)",
          [](const std::string& v)
          { return v == "nh" || v == "mr" || v == "le" ? "" : "must be nh, mr or le"; });
  prm.add("material", "G", m0.G, "initial shear modulus (MPa)", gelx::Parameters::positive);
  prm.add("material", "mooney_share", m0.mooney_share,
          "Mooney-Rivlin C01 / (C10 + C01), with C10 + C01 = G/2 (law mr)",
          [](double v) { return v >= 0 && v < 1 ? "" : "must be in [0, 1)"; });
  prm.add("mesh", "domain", "quarter",
          "quarter: the quarter cell with mirror planes x = 0, y = 0; half: the half x >= 0",
          [](const std::string& v)
          { return v == "quarter" || v == "half" ? "" : "must be quarter or half"; });
  prm.add("mesh", "order", m0.order, "displacement degree: 2 (Q2-Q1) or 1 (Q1-P0)",
          [](int v) { return v == 1 || v == 2 ? "" : "must be 1 or 2"; });
  prm.add("output", "extrapolate", true,
          "also run the next coarser mesh for the Richardson limit of the slope");
  prm.add("loading", "unload", false,
          "after reaching d_max, move the substrate back to d = 0 (the fits use the loading half)");
  prm.add("loading", "d_max", 0.8, "final indentation d/H",
          [](double v) { return v > 0 && v < 1 ? "" : "must be in (0, 1)"; });
  // Steps of 0.0125 H growing to 0.025 H (at d_max = 0.8): the patch gains a ring of nodes in
  // a few steps, and each change of the active set costs Newton iterations
  gelx::LoadSteppingOptions stepping_defaults;
  stepping_defaults.dt = 1.0 / 64;
  stepping_defaults.dt_max = 1.0 / 32;
  gelx::LoadSteppingOptions::declare(prm, stepping_defaults);

  return gelx::run_program(argc, argv, "gelx-pyramid", prm, [&](MPI_Comm comm)
  {
    // Full Newton steps (still rejected if an element inverts): when nodes enter or leave the
    // active set the residual norm jumps, and a decrease test then stalls the semismooth
    // Newton method in tiny steps (measured: 22 iterations at d/H = 0.1 against 5-7)
    gelx::set_default_option("newton_", "linesearch", "basic");
    gelx::set_default_option("newton_", "max_it", "40");
    gelx::scenes::PyramidGeometry g;
    g.L = prm.real("L");
    g.W = prm.real("W");
    g.t = prm.real("t");
    g.cells = prm.integer("cells");
    g.tip_levels = prm.integer("tip_levels");
    g.growth = prm.real("growth");
    g.half_cell = prm.text("domain") == "half";
    if (g.W <= g.L)
      throw gelx::InputError("the array period W must exceed the pyramid width L");
    gelx::scenes::PyramidMaterial material;
    material.law = prm.text("law");
    material.G = prm.real("G");
    material.mooney_share = prm.real("mooney_share");
    material.order = prm.integer("order");

    // 2. The quarter cell: mesh, material, symmetry, contact
    gelx::scenes::PressedPyramid pyramid(comm, g, material);

    // 3. Press, writing every step's fields, STL surface and measures
    gelx::ResultsWriter writer(comm, prm.text("output"), pyramid.mesh().mesh);
    gelx::NodalField displacement("displacement", pyramid.displacement());
    gelx::CellField stress("sigma", pyramid.stress());
    WidthCurve curve;
    gelx::scenes::ContactMeasures last;
    double last_d = 0;
    const auto start = std::chrono::steady_clock::now();
    const std::string status = press(
        pyramid, prm, curve,
        [&](const gelx::StepRecord& step, double d, const gelx::scenes::ContactMeasures& m)
        {
          last = m;
          last_d = d;
          displacement.update();
          stress.update();
          auto fields = stress.functions();
          fields.push_back(displacement.function());
          writer.write_fields(d, fields);
          char stl[32];
          std::snprintf(stl, sizeof(stl), "surface/step_%03d.stl", step.step);
          writer.write_stl(stl, pyramid.contact_side_surface(*displacement.function()));
          writer.append_step({{"step", step.step},
                              {"d_over_H", d},
                              {"force", m.force},
                              {"contact_width_over_L", m.width / g.L},
                              {"contact_area", m.area},
                              {"area_over_width_squared",
                               m.width > 0 ? m.area / (m.width * m.width) : 0},
                              {"active_nodes", m.active},
                              {"max_penetration", m.penetration},
                              {"newton_iterations", step.newton.iterations},
                              {"cutbacks", step.cutbacks},
                              {"wall_time", step.wall_time}});
        });
    const double wall_time
        = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    // 4. The patch at the last step (x, y, nodal contact force, in contact), for the pressure
    //    map
    const auto patch = pyramid.patch(); // collective; the nodes are on rank 0
    if (dolfinx::MPI::rank(comm) == 0)
    {
      std::ofstream out(writer.folder() / "patch.csv");
      out << "x,y,force,in_contact\n";
      for (const auto& [x, y, f, in_contact] : patch)
        out << x << "," << y << "," << f << "," << in_contact << "\n";
    }
    const Fit by_d = curve.by_d(), by_f = curve.by_sqrt_force();

    // 5. The slope's discretisation error: the width is resolved to a fraction of the node
    //    spacing at the patch's corner, so the slope converges at first order in the cell
    //    size h ~ 1/cells (measured: order 0.91 on 3, 4, 5 cells, and the limit predicted
    //    from them met by 6 cells to 1e-4; demos/pyramid/README.md). The same run on the
    //    next coarser mesh gives the Richardson limit cells s_c - (cells - 1) s_(cells-1).
    double slope_extrapolated = NAN;
    if (prm.flag("extrapolate") && g.cells > 1 && status == "completed")
    {
      gelx::scenes::PyramidGeometry coarse = g;
      coarse.cells = g.cells - 1;
      gelx::scenes::PressedPyramid coarse_pyramid(comm, coarse, material);
      WidthCurve coarse_curve;
      if (press(coarse_pyramid, prm, coarse_curve, [](auto&&...) {}) == "completed")
        slope_extrapolated
            = g.cells * by_d.slope - (g.cells - 1) * coarse_curve.by_d().slope;
    }
    writer.write_summary(
        "pyramid", status, prm,
        {{"num_dofs", pyramid.state()->function_space()->dofmap()->index_map->size_global()},
         {"num_cells", pyramid.mesh().mesh->topology().index_map(3)->size_global()},
         {"final_d_over_H", last_d},
         {"final_force", last.force},
         {"final_contact_width_over_L", last.width / g.L},
         {"area_ratio", last.width > 0 ? last.area / (last.width * last.width) : NAN},
         {"slope_lc_vs_d", by_d.slope},
         {"slope_lc_vs_d_extrapolated", slope_extrapolated},
         {"intercept_lc_vs_d", by_d.intercept},
         {"r2_lc_vs_d", by_d.r2},
         {"slope_lc_vs_sqrtf", by_f.slope},
         {"r2_lc_vs_sqrtf", by_f.r2},
         {"max_penetration", last.penetration},
         {"wall_time", wall_time},
         {"wall_time_with_extrapolation",
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}});
    if (status != "completed")
      throw gelx::ConvergenceError(status.substr(8));
  });
}
