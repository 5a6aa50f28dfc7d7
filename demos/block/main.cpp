// gelx scene: block — a compressible neo-Hookean block stretched and twisted
//
// Sample runs:
//   ./gelx run block
//   ./gelx run block --stretch 2 --twist 180 --h 0.15 --degree 1
//   ./gelx run block --law mr --mooney_share 0.3 --mesh box
//   mpirun -np 2 build/demos/block/gelx-block --output results/block-np2
//   ./gelx run block -newton_linear_solver amg    (iterative linear solver: GMRES + GAMG)
//
// A W x W x H block of the compressible neo-Hookean solid of thesis Eq. 3.1,
//   U = G/2 (J^(-2/3) tr C - 3) + K/2 (J - 1)^2,
// (or, --law, the neo-Hookean solid with a ln J volumetric term of dolfinx's hyperelasticity
// demo, Mooney-Rivlin, or small-strain linear elasticity), discretised with P1 or P2
// tetrahedra (forms/block.py) of a gmsh mesh or a structured box (--mesh box), stands clamped
// on z = 0. Its top face is
// moved rigidly: lifted to the axial stretch `stretch` and turned by `twist` degrees about the
// block's axis, both in proportion to the load factor t in [0, 1]. Adaptive load stepping
// follows t to 1. At every step the run records the axial force and the torque on the top face
// and the stored energy, and writes displacement, Cauchy stress and energy density to
// fields.xdmf.

#include "block.h"

#include <cmath>
#include <dolfinx/fem/utils.h>
#include <gelx/systems/boundary.h>
#include <gelx/systems/forms.h>
#include <gelx/solvers/load_stepping.h>
#include <gelx/io/mesh.h>
#include <gelx/systems/problem.h>
#include <gelx/io/program.h>

using namespace dolfinx;

namespace
{
/// The generated forms and expressions of forms/block.py for one law and displacement degree.
struct BlockForms
{
  ufcx_function_space* (*space)(const char*);
  const char* u;
  ufcx_form *residual, *tangent, *energy;
  ufcx_expression *stress, *psi, *det_F;
};
#define BLOCK_FORMS(law, p)                                                                    \
  {{#law, p},                                                                                  \
   {functionspace_form_block_residual_##law##_p##p, "u_p" #p,                                  \
    form_block_residual_##law##_p##p, form_block_tangent_##law##_p##p,                         \
    form_block_energy_##law##_p##p, expression_block_stress_##law##_p##p,                      \
    expression_block_psi_##law##_p##p, expression_block_det_F_p##p}}
const std::map<std::pair<std::string, int>, BlockForms> block_forms
    = {BLOCK_FORMS(nh, 1),     BLOCK_FORMS(nh, 2), BLOCK_FORMS(nh_log, 1), BLOCK_FORMS(nh_log, 2),
       BLOCK_FORMS(mr, 1),     BLOCK_FORMS(mr, 2), BLOCK_FORMS(le, 1),     BLOCK_FORMS(le, 2)};
#undef BLOCK_FORMS

/// The scene's parameters.
struct Block
{
  double width = 1.0, height = 2.0, h = 0.25; // mm
  std::string mesh = "block.geo"; // meshes/block.geo
  int degree = 2;
  std::string law = "nh";
  double G = 1.0, K = 10.0; // MPa
  double mooney_share = 0.0;
  double stretch = 1.5, twist = 90.0;
};
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters, with their defaults and validity checks
  Block b;
  gelx::LoadSteppingOptions stepping;
  gelx::Parameters prm;
  prm.bind("geometry", "width", b.width, "block width W [mm]", gelx::Parameters::positive);
  prm.bind("geometry", "height", b.height, "block height H [mm]", gelx::Parameters::positive);
  prm.bind("geometry", "h", b.h, "mesh size [mm]", gelx::Parameters::positive);
  prm.bind("geometry", "mesh", b.mesh,
           "gmsh geometry file with the physical surfaces bottom and top (a path, or a file of "
           "meshes/), or box: a structured "
           "mesh of ceil(W/h) x ceil(W/h) x ceil(H/h) boxes of six tetrahedra (dolfinx's "
           "create_box)");
  prm.bind("discretisation", "degree", b.degree, "polynomial degree of the displacement (1 or 2)",
           [](int p) { return p == 1 || p == 2 ? "" : "must be 1 or 2"; });
  prm.bind("material", "law", b.law,
           "nh neo-Hookean (thesis Eq. 3.1), nh_log neo-Hookean with G ln J and lambda/2 (ln "
           "J)^2 (dolfinx's hyperelasticity demo), mr Mooney-Rivlin, le small-strain linear "
           "elastic",
           [](const std::string& v)
           {
             const bool known = v == "nh" || v == "nh_log" || v == "mr" || v == "le";
             return known ? "" : "must be nh, nh_log, mr or le";
           });
  prm.bind("material", "G", b.G, "shear modulus [MPa]", gelx::Parameters::positive);
  prm.bind("material", "K", b.K, "bulk modulus [MPa]", gelx::Parameters::positive);
  prm.bind("material", "mooney_share", b.mooney_share,
           "Mooney-Rivlin C01 / (C10 + C01), with C10 + C01 = G/2 (law mr)",
           [](double v) { return v >= 0 && v < 1 ? "" : "must be in [0, 1)"; });
  prm.bind("load", "stretch", b.stretch, "final axial stretch of the block",
           gelx::Parameters::positive);
  prm.bind("load", "twist", b.twist, "final rotation of the top face [degrees]");
  stepping.bind(prm);

  return gelx::run_program(argc, argv, "gelx-block", prm, [&](gelx::Run& run)
  {
    stepping.check();
    const double twist = b.twist * M_PI / 180.0;

    // 2. Mesh from the gmsh geometry, with the physical groups "bottom" and "top", or a
    //    structured box (its faces z_min and z_max)
    const bool structured = b.mesh == "box";
    const auto cells = [&](double length) { return std::size_t(std::ceil(length / b.h)); };
    const gelx::TaggedMesh geo
        = structured
              ? gelx::box_mesh(run.comm(), {b.width, b.width, b.height},
                               {cells(b.width), cells(b.width), cells(b.height)},
                               mesh::CellType::tetrahedron, {-b.width / 2, -b.width / 2, 0})
              : gelx::read_geo(run.comm(), b.mesh, {{"W", b.width}, {"H", b.height}, {"h", b.h}});
    // the conditions below stretch by the height and twist about the axis x = y = 0
    const auto box = gelx::bounding_box(*geo.mesh);
    gelx::require_span(box, 0, -b.width / 2, b.width / 2, "--width");
    gelx::require_span(box, 1, -b.width / 2, b.width / 2, "--width");
    gelx::require_span(box, 2, 0, b.height, "--height");

    // 3. Displacement space, material constants, residual and tangent (forms/block.py)
    const BlockForms& kernels = block_forms.at({b.law, b.degree});
    auto V = std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(kernels.space, kernels.u, geo.mesh));
    auto u = std::make_shared<fem::Function<double>>(V);
    const gelx::FormBinding forms(geo.mesh, {{kernels.u, u}},
                                  {{"G", b.G}, {"K", b.K}, {"mooney_share", b.mooney_share}});

    // 4. Boundary conditions: bottom clamped; top lifted by (stretch - 1) H t and turned by
    //    twist t about the z-axis: u = R(twist t) X - X in the plane, u_z = (stretch - 1) H t.
    const int bottom = geo.tag(structured ? "z_min" : "bottom");
    const int top = geo.tag(structured ? "z_max" : "top");
    gelx::DirichletConditions bcs(V, geo.facet_tags);
    bcs.clamp(bottom);
    bcs.prescribe(top, 0, [=](double t, auto& X)
                  { return std::cos(twist * t) * X[0] - std::sin(twist * t) * X[1] - X[0]; });
    bcs.prescribe(top, 1, [=](double t, auto& X)
                  { return std::sin(twist * t) * X[0] + std::cos(twist * t) * X[1] - X[1]; });
    bcs.prescribe(top, 2, [=](double t, auto&) { return (b.stretch - 1) * b.height * t; });
    gelx::NonlinearProblem problem(u, forms.form(kernels.residual, {V}),
                                   forms.form(kernels.tangent, {V, V}), bcs.bcs(),
                                   forms.expression(kernels.det_F));
    // Its Newton solver, bound now so that a bad solver option ends the run before any output
    gelx::NewtonSolver newton(run.comm());
    newton.bind(problem);

    // 5. Output: displacement at the nodes, stress and energy density per cell
    gelx::ResultsWriter& results = run.results(geo.mesh);
    gelx::FieldSet fields;
    fields.add("displacement", u);
    fields.add("cauchy_stress", forms.expression(kernels.stress));
    fields.add("energy_density", forms.expression(kernels.psi));
    const auto energy = forms.form(kernels.energy);
    run.summary = {{"num_dofs", V->dofmap()->index_map->size_global() * 3},
                   {"num_cells", geo.mesh->topology().index_map(3)->size_global()}};

    // 6. Follow the load path; each completed step updates the quantities of interest
    gelx::PathState path = run.start_path(problem);
    gelx::LoadStepper(problem, newton, stepping, [&](double t) { bcs.update(t); })
        .run(path,
             {[&](const gelx::StepRecord& s, gelx::PathState& state)
              {
                const auto load = gelx::boundary_resultant(problem, *geo.facet_tags, top);
                state.scene["newton_iterations"]
                    = state.scene.value("newton_iterations", 0) + s.newton.iterations;
                const nlohmann::json quantities = {
                    {"axial_force", load.force[2]},
                    {"torque", load.moment[2]},
                    {"strain_energy", gelx::assemble_global_scalar(*energy)},
                    {"min_det_F", problem.admissibility_margin()}};
                results.write_fields(s.load, fields.update());
                nlohmann::json row = gelx::step_columns(s);
                row["t"] = s.load;
                row.update(quantities);
                results.append_step(row);
                run.summary.update(quantities);
                run.summary.update({{"steps", s.step},
                                    {"newton_iterations", state.scene["newton_iterations"]},
                                    {"cutbacks", state.cutbacks}});
              },
              gelx::ProgressLine(run.comm(),
                                 {.quantity = [&] {
                                   return gelx::quantity_text("axial force",
                                                              run.summary["axial_force"]);
                                 }}),
              run.checkpoints()});
  });
}
