// gelx scene: swelling — a gel layer bonded to a rigid substrate takes up solvent in time
//
// Sample runs:
//   ./gelx run swelling
//   ./gelx run swelling --chi 0.2 --lambda0 1.2 --end_time 2e4
//   ./gelx run swelling --sides free --W 1 --nx 4 --nz 4 --end_time 1e8   (a free cube)
//   ./gelx run swelling --sides free --shape ellipsoid --W 1 --nx 4 --nz 4 --end_time 1e8
//                                                                  (a free sphere)
//   ./gelx run swelling --path equilibrium            (the state it tends to, without time)
//   ./gelx run swelling --chi 0.3 --dchi_dphi 0.6 --path equilibrium     (chi linear in phi)
//
// A layer of thickness H of the Flory-Rehner gel (thesis Eq. 4.28) in the coupled theory of solvent
// diffusion and large deformation of Hong, Zhao, Zhou and Suo (forms/swelling.py: unknowns the
// displacement u and the solvent's chemical potential mu, in units of kT, on Q2-Q1 hexahedra, or
// equal-order Q1-Q1 to see what an element that is not inf-sup stable does). The reference state is
// the gel swollen freely to the stretch lambda0 from dry (polymer fraction phi0 = lambda0^-3),
// stress-free at the chemical potential mu0 that holds it there (cpp/theory: mu0 = phi0^2
// (chi_bar - chi_free(phi0)), Eq. 4.7, with chi_bar of Eq. 4.20 = chi when chi does not depend on
// phi; --dchi_dphi makes it linear in phi, chi(phi) = chi + dchi_dphi phi, as gels with a volume
// phase transition are fitted); in that state it was bonded to the substrate at z = 0 (u = 0, no
// flux) and its sides held laterally (rollers, no flux): a piece of a wide layer (or, --sides free,
// the piece is an eighth of a free block, in solvent on its three outer faces, or with --shape
// ellipsoid of a free ellipsoid). At t = 0 the surface z = H meets a solvent of chemical potential
// mu (0: pure solvent), reached on the smooth step over --ramp_time, and the solvent diffuses in, D
// its diffusivity. PETSc TS (adaptive BDF2, options -swelling_ts_*) follows the transient to
// --end_time. At every step the run records the layer's thickness and its swelling ratio V/V0 (the
// solvent taken up: polymer and solvent are incompressible), and writes displacement, chemical
// potential and Cauchy stress to fields.xdmf at --outputs times spaced evenly in log t; it
// checkpoints every --checkpoint_every steps and continues exactly with --restart. With --path
// equilibrium it solves instead for the state the transient tends to: the solvent at mu throughout,
// by load steps in mu from mu0 (the cost the transient's is measured against).

#include "swelling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <dolfinx/fem/utils.h>
#include <gelx/io/mesh.h>
#include <gelx/io/probe.h>
#include <gelx/io/program.h>
#include <gelx/solvers/dynamics.h>
#include <gelx/solvers/load_stepping.h>
#include <gelx/solvers/transient.h>
#include <gelx/systems/boundary.h>
#include <gelx/systems/forms.h>
#include <gelx/systems/mixed.h>
#include <gelx/systems/problem.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/io/progress.h>
#include <gelx/io/transient_record.h>
#include <theory/swelling.h>

using namespace dolfinx;

namespace
{
/// The generated kernels of one element (forms/swelling.py)
struct Kernels
{
  const char *w, *w_dot;
  ufcx_function_space* (*space)(const char*);
  ufcx_form *residual, *tangent, *schur_preconditioner, *volume;
  ufcx_expression *stress, *swelling_ratio, *margin;
};
#define SWELLING_KERNELS(element)                                                              \
  {#element,                                                                                   \
   {"w_" #element, "w_dot_" #element, functionspace_form_swelling_residual_##element,          \
    form_swelling_residual_##element, form_swelling_tangent_##element,                         \
    form_swelling_schur_preconditioner_##element, form_swelling_volume_##element,              \
    expression_swelling_stress_##element, expression_swelling_swelling_ratio_##element,        \
    expression_swelling_margin_##element}}
const std::map<std::string, Kernels> kernels = {SWELLING_KERNELS(q2q1), SWELLING_KERNELS(q1q1)};
#undef SWELLING_KERNELS

/// The scene's parameters.
struct Layer
{
  double H = 1.0, W = 0.05; // thickness and width of the piece (mm)
  std::string sides = "held"; // held: a piece of a wide layer; free: an eighth of a block
  std::string shape = "box";  // box, or (free) an eighth of an ellipsoid W, W, H
  int nx = 1, nz = 40;      // cells across the width and through the thickness
  std::string element = "q2q1"; // Taylor-Hood, or equal-order q1q1
  double grading = 2;       // their sizes shrink towards the surface: z = H (1 - (1 - s)^grading)
  double n = 1e-3;          // N nu: the network's stiffness in kT/nu
  double chi = 0.4;         // Flory's interaction parameter (at phi = 0)
  double dchi_dphi = 0;     // its slope in the polymer fraction phi
  double lambda0 = 1.5;     // the reference state's stretch from dry
  double kT_nu = 137.0;     // kT / nu (MPa): water at 298 K, nu = 3e-29 m^3
  double D = 1e-3;          // the solvent's diffusivity (mm^2/s)
  double mu = 0.0;          // the solvent's chemical potential at the surface (kT)
  double ramp_time = 1.0;   // its smooth step from mu0 (s)
  double end_time = 3000.0; // s
  int outputs = 20;         // field outputs, evenly in log t
  std::string path = "transient"; // or the equilibrium the transient tends to
};
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters, with their defaults and validity checks
  Layer p;
  gelx::LoadSteppingOptions stepping; // of --path equilibrium
  gelx::Parameters prm;
  using P = gelx::Parameters;
  prm.bind("geometry", "H", p.H, "thickness of the layer in the reference state [mm]",
           P::positive);
  prm.bind("geometry", "W", p.W, "width of the piece modelled [mm]", P::positive);
  prm.bind("geometry", "sides", p.sides,
           "held: the piece's sides held laterally without flux (a wide layer bonded at z = 0); "
           "free: the piece is the eighth x, y, z > 0 of a free 2W x 2W x 2H block, in solvent "
           "on its faces x = W, y = W, z = H",
           P::one_of({"held", "free"}));
  prm.bind("geometry", "shape", p.shape,
           "box: the W x W x H piece; ellipsoid (with --sides free): the eighth x, y, z > 0 "
           "of a free ellipsoid of semi-axes W, W, H (a sphere when W = H), in solvent on its "
           "surface",
           P::one_of({"box", "ellipsoid"}));
  prm.bind("mesh", "element", p.element,
           "q2q1: Q2 displacements, Q1 chemical potential (Taylor-Hood, inf-sup stable); q1q1: "
           "equal order, which is not",
           P::one_of({"q2q1", "q1q1"}));
  prm.bind("mesh", "nx", p.nx, "hexahedra across the width", P::at_least_one);
  prm.bind("mesh", "nz", p.nz, "hexahedra through the thickness", P::at_least_one);
  prm.bind("mesh", "grading", p.grading,
           "cells shrink towards the faces in solvent, z = H (1 - (1 - s)^grading) for s "
           "evenly spaced in [0, 1] (1: even; 2: the surface cell H/nz^2), where a thin "
           "swollen skin forms first",
           [](double v) { return v >= 1 ? "" : "must be at least 1"; });
  prm.bind("material", "n", p.n, "N nu: the network's stiffness in units of kT/nu",
           P::positive);
  prm.bind("material", "chi", p.chi,
           "Flory's polymer-solvent interaction parameter (its value at phi = 0 when "
           "--dchi_dphi is not 0)");
  prm.bind("material", "dchi_dphi", p.dchi_dphi,
           "slope of chi in the polymer fraction phi: chi(phi) = chi + dchi_dphi phi (the form "
           "fitted to gels with a volume phase transition, PNIPAM's; 0: chi constant)");
  prm.bind("material", "lambda0", p.lambda0,
           "stretch of the stress-free reference state from dry (> 1: phi0 = lambda0^-3)",
           [](double v) { return v > 1 ? "" : "must exceed 1 (the dry state is singular)"; });
  prm.bind("material", "kT_nu", p.kT_nu, "energy scale kT/nu [MPa]", P::positive);
  prm.bind("material", "D", p.D, "diffusivity of the solvent [mm^2/s]", P::positive);
  prm.bind("load", "mu", p.mu,
           "chemical potential of the solvent at the surface, in kT (0: pure solvent)",
           [](double v) { return v <= 0 ? "" : "must be at most 0 (the pure solvent's)"; });
  prm.bind("load", "ramp_time", p.ramp_time,
           "time of the smooth step from mu0 to mu [s] (a jump at t = 0 is no transient the "
           "time steps' error estimate accepts at any size)",
           P::positive);
  prm.bind("time", "path", p.path,
           "transient: the solvent diffuses in, to --end_time; equilibrium: the state it tends "
           "to, the solvent at --mu throughout, by load steps in mu from mu0 (no time: D, "
           "--end_time and --ramp_time play no part)",
           P::one_of({"transient", "equilibrium"}));
  prm.bind("time", "end_time", p.end_time, "time the transient is followed to [s]",
           P::positive);
  prm.bind("output", "outputs", p.outputs,
           "field outputs, evenly spaced in log t from the first step to the end (1: the end)",
           P::at_least_one);
  stepping.bind(prm);

  return gelx::run_program(argc, argv, "gelx-swelling", prm, [&](gelx::Run& run)
  {
    const double phi0 = std::pow(p.lambda0, -3.0);
    const gelx::theory::LinearChi chi{p.chi, p.dchi_dphi};
    const double mu0 = gelx::theory::free_gel_mu(phi0, chi, p.n);
    if (p.mu < mu0)
      throw gelx::InputError("--mu " + std::to_string(p.mu) + " is below mu0 = "
                             + std::to_string(mu0)
                             + ", the reference state's: the layer would shrink (give a "
                               "lambda0 that holds less solvent)");
    // A large chi, or one that grows with phi, can give the gel a volume phase transition: on its
    // way to the solvent's mu it would pass states of negative drained modulus and separate into a
    // swollen and a collapsed phase, which this model, without a gradient energy, cannot follow
    // (the transient loses uniqueness there): refused rather than run into a Newton failure
    if (const double phi
        = gelx::theory::spinodal_on_swelling(phi0, chi, p.n, p.mu, p.sides == "free");
        !std::isnan(phi))
      throw gelx::InputError("on its way to mu = " + std::to_string(p.mu)
                             + " the gel enters its spinodal at phi = " + std::to_string(phi)
                             + " (drained modulus <= 0): it would phase-separate, which this "
                               "model cannot follow (a smaller --dchi_dphi or --chi)");

    const bool ellipsoid = p.shape == "ellipsoid";
    if (ellipsoid && p.sides != "free")
      throw gelx::InputError("--shape ellipsoid is a free body: give --sides free");

    // 2. The piece: W x W x H hexahedra
    const bool free = p.sides == "free";
    const gelx::TaggedMesh geo = gelx::box_mesh(
        run.comm(), {p.W, p.W, p.H}, {std::size_t(p.nx), std::size_t(p.nx), std::size_t(p.nz)},
        mesh::CellType::hexahedron);
    // Graded towards the faces in solvent: the swollen gel of the skin has a low mobility
    // ((J - phi0) C^-1 falls, and mu's slope dmu/dJ with it), so it swells in a layer of
    // thickness sqrt(D_skin t), a few micrometres in the first seconds
    const std::array<double, 3> size{p.W, p.W, p.H};
    const auto graded = [&](double s) { return 1 - std::pow(1 - s, p.grading); };
    if (!ellipsoid)
      for (int axis = free ? 0 : 2; axis < 3; ++axis)
        for (std::size_t i = axis; i < geo.mesh->geometry().x().size(); i += 3)
        {
          double& x = geo.mesh->geometry().x()[i];
          x = size[axis] * graded(x / size[axis]);
        }
    // The ellipsoid: the box's point, at q in the unit cube's coordinates, moved along q's ray,
    // first so that its shell max q_k = m becomes the graded shell 1 - (1 - m)^grading (cells
    // in layers towards the surface, as the box's towards its faces), then by a factor blending
    // from 1 at the centre to 1 / |q| on the faces max q_k = 1, which land on the surface
    // |q| = 1
    if (ellipsoid)
      for (std::size_t i = 0; i < geo.mesh->geometry().x().size(); i += 3)
      {
        double* x = &geo.mesh->geometry().x()[i];
        const std::array<double, 3> q{x[0] / size[0], x[1] / size[1], x[2] / size[2]};
        const double shell = std::max({q[0], q[1], q[2]});
        const double length = std::hypot(q[0], q[1], q[2]);
        if (shell == 0)
          continue;
        const double to_graded = graded(shell) / shell;
        const double max = shell * to_graded;
        const double factor = to_graded * (1 + max * (max / (length * to_graded) - 1));
        for (int k = 0; k < 3; ++k)
          x[k] *= factor;
      }

    // 3. The (u, mu) space, its rate, the constants, residual and tangent (forms/swelling.py)
    const Kernels& k = kernels.at(p.element);
    auto W = std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(k.space, k.w, geo.mesh));
    auto w = std::make_shared<fem::Function<double>>(W);
    auto w_dot = std::make_shared<fem::Function<double>>(W);
    gelx::FormBinding forms(geo.mesh, {{k.w, w}, {k.w_dot, w_dot}},
                            {{"n", p.n}, {"phi0", phi0}, {"chi", p.chi},
                             {"dchi_dphi", p.dchi_dphi}, {"kT_nu", p.kT_nu},
                             {"D", p.D}, {"shift", 0.0}});
    auto U = W->sub({0});
    auto M = W->sub({1});
    auto [M_collapsed, mu_dofs] = M->collapse();
    // The reference state: at rest at mu0
    for (std::int32_t dof : mu_dofs)
      w->x()->mutable_array()[dof] = mu0;

    // 4. Held: bonded at z = 0, the sides held laterally, the surface z = H in solvent. Free:
    //    the symmetry planes x, y, z = 0 (rollers), the faces x = W, y = W, z = H in solvent.
    //    No flux through any other face
    gelx::DirichletConditions supports(U, geo.facet_tags);
    std::vector<int> in_solvent{geo.tag("z_max")};
    if (free)
    {
      supports.fix(geo.tag("x_min"), 0);
      supports.fix(geo.tag("y_min"), 1);
      supports.fix(geo.tag("z_min"), 2);
      in_solvent.insert(in_solvent.end(), {geo.tag("x_max"), geo.tag("y_max")});
    }
    else
    {
      supports.clamp(geo.tag("z_min"));
      supports.fix(geo.tag("x_min"), 0);
      supports.fix(geo.tag("x_max"), 0);
      supports.fix(geo.tag("y_min"), 1);
      supports.fix(geo.tag("y_max"), 1);
    }
    auto surface_mu = std::make_shared<fem::Function<double>>(
        std::make_shared<fem::FunctionSpace>(std::move(M_collapsed)));
    auto bcs = supports.bcs();
    for (int face : in_solvent)
      bcs.push_back(gelx::prescribe_sub(M, surface_mu, geo.facet_tags->find(face)));
    const int surface = geo.tag("z_max");
    const auto set_time = [&](double t)
    {
      surface_mu->x()->set(mu0 + gelx::smooth_step(t, p.ramp_time) * (p.mu - mu0));
    };
    set_time(0);
    // --path equilibrium: mu prescribed at every node, not only where the solvent is, so
    // that the conservation rows drop out and time with them (w_dot stays 0, shift 0)
    const bool equilibrium = p.path == "equilibrium";
    if (equilibrium)
      bcs.push_back(gelx::prescribe_sub_every_node(M, surface_mu));
    gelx::NonlinearProblem problem(w, forms.form(k.residual, {W}), forms.form(k.tangent, {W, W}),
                                   bcs, forms.expression(k.margin));
    problem.set_schur_preconditioner(forms.form(k.schur_preconditioner, {W, W}), true);
    // The transient's time integrator (PETSc TS), set up here, before the output, so that a
    // solver option it refuses leaves no results folder. TS's error tolerance: 1e-4 of the
    // change of mu (a number of order 1e-2, in kT), which in mm is a finer one for the
    // displacements (of order H (lambda - 1)); the user's win
    std::optional<gelx::TransientProblem> transient;
    if (!equilibrium)
    {
      char atol[32];
      std::snprintf(atol, sizeof atol, "%.6g", 1e-4 * std::abs(p.mu - mu0));
      gelx::set_default_options("swelling_", {{"ts_rtol", "1e-4"}, {"ts_atol", atol}});
      transient.emplace(run.comm(), problem, w_dot, forms.constant("shift"), set_time,
                        p.end_time, "swelling_");
    }

    // 5. Output: displacement and chemical potential at the nodes, stress per cell
    gelx::ResultsWriter& results = run.results(geo.mesh);
    auto u = gelx::collapse_sub_function(*w, 0);
    auto mu = gelx::collapse_sub_function(*w, 1);
    gelx::FieldSet fields;
    fields.add("displacement", u);
    fields.add("chemical_potential", mu);
    fields.add("cauchy_stress", forms.expression(k.stress));
    fields.add("swelling_ratio", forms.expression(k.swelling_ratio));
    const auto volume = forms.form(k.volume);
    const double V0 = gelx::assemble_global_scalar(*volume);
    const auto thickness = [&]
    { return p.H + gelx::component_range(*u, *geo.facet_tags, surface, 2).second; };
    // The swelling front: the reference depth below the surface z = H, on the line x = y = 0,
    // at which mu is half-way from mu0 to the surface's mu (mu's nodes on the line, gathered;
    // H once the front has crossed the piece)
    const gelx::NodeProbe axis(mu, [&](const std::array<double, 3>& X)
                               { return std::hypot(X[0], X[1]) < 1e-9 * p.W; });
    const auto front_depth = [&](double t)
    {
      std::vector<gelx::NodeProbe::Sample> line = axis.samples();
      std::sort(line.begin(), line.end(), [](const auto& a, const auto& b)
                { return a.X[2] > b.X[2]; }); // from the surface down
      const double half = mu0 + 0.5 * gelx::smooth_step(t, p.ramp_time) * (p.mu - mu0);
      for (std::size_t k = 1; k < line.size(); ++k)
        if (line[k].value < half)
        {
          const auto &above = line[k - 1], &below = line[k];
          return p.H - (above.X[2] + (half - above.value) / (below.value - above.value)
                                         * (below.X[2] - above.X[2]));
        }
      return p.H;
    };
    run.summary = {{"num_dofs", W->dofmap()->index_map->size_global()},
                   {"mu0", mu0},
                   {"phi0", phi0}};

    // 6a. The equilibrium: mu from mu0 to the solvent's by load steps, mu = mu0 + s (mu - mu0)
    //     for the load factor s; fields after every step
    const auto mu_at = [&](double s) { return mu0 + s * (p.mu - mu0); };
    gelx::ProgressLine progress(
        run.comm(), {.load_name = equilibrium ? "mu" : "t",
                     .load = [&](const gelx::StepRecord& s) { return mu_at(s.load); },
                     .quantity = [&]
                     { return gelx::quantity_text("thickness", run.summary["thickness"]); }});
    if (equilibrium)
    {
      gelx::NewtonSolver newton(run.comm(), "swelling_");
      newton.bind(problem);
      gelx::PathState path = run.start_path(problem);
      gelx::LoadStepper(problem, newton, stepping,
                        [&](double s) { surface_mu->x()->set(mu_at(s)); })
          .run(path,
               {[&](const gelx::StepRecord& s, gelx::PathState& state)
                {
                  gelx::copy_sub_function(*w, 0, *u);
                  gelx::copy_sub_function(*w, 1, *mu);
                  for (const auto& [key, count] :
                       {std::pair{"newton_iterations", s.newton.iterations},
                        std::pair{"linear_iterations", s.newton.linear_iterations}})
                    state.scene[key] = state.scene.value(key, 0) + count;
                  const double mu_s = mu_at(s.load);
                  const nlohmann::json quantities
                      = {{"thickness", thickness()},
                         {"swelling_ratio", gelx::assemble_global_scalar(*volume) / V0}};
                  results.write_fields(mu_s, fields.update());
                  nlohmann::json row = gelx::step_columns(s);
                  row["mu"] = mu_s;
                  row.update(quantities);
                  results.append_step(row);
                  run.summary.update(quantities);
                  run.summary.update({{"steps", s.step},
                                      {"newton_iterations", state.scene["newton_iterations"]},
                                      {"linear_iterations", state.scene["linear_iterations"]}});
                },
                progress, run.checkpoints()});
      return;
    }

    // 6b. The transient; fields at times evenly spaced in log t (gelx::LogTimeOutputs). A
    //    checkpoint after a step (--checkpoint_every) holds w, TSBDF's history and this
    //    record's state, so that --restart continues the run as if never stopped
    gelx::TransientRecorder recorder(run, results, *transient, fields, progress, p.outputs,
                                     run.start_path(problem));
    recorder.run(
        [&](const gelx::TransientStep& s) -> gelx::TransientRecorder::Measured
        {
          gelx::copy_sub_function(*w, 0, *u);
          gelx::copy_sub_function(*w, 1, *mu);
          return {{{"thickness", thickness()},
                   {"swelling_ratio", gelx::assemble_global_scalar(*volume) / V0},
                   {"front_depth", front_depth(s.time)}}};
        });
  });
}
