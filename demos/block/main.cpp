// gelx scene: block — a compressible neo-Hookean block stretched and twisted
//
// Sample runs:
//   ./gelx run block
//   ./gelx run block --stretch 2 --twist 180 --h 0.15 --degree 1
//   mpirun -np 2 build/demos/block/gelx-block --output results/block-np2
//   ./gelx run block -newton_ksp_type gmres -newton_pc_type gamg    (iterative linear solver)
//
// A W x W x H block of the compressible neo-Hookean solid of thesis Eq. 3.1,
//   U = G/2 (J^(-2/3) tr C - 3) + K/2 (J - 1)^2,
// discretised with P1 or P2 tetrahedra (forms/block.py), stands clamped on z = 0. Its top face is moved
// rigidly: lifted to the axial stretch `stretch` and turned by `twist` degrees about the block's
// axis, both in proportion to the load factor t in [0, 1]. Adaptive load stepping follows t to 1.
// At every step the run records the axial force and the torque on the top face and the stored
// energy, and writes displacement, Cauchy stress and energy density to fields.xdmf.

#include "block.h"

#include <cmath>
#include <dolfinx/fem/utils.h>
#include <gelx/boundary.h>
#include <gelx/load_stepping.h>
#include <gelx/mesh.h>
#include <gelx/output.h>
#include <gelx/program.h>

using namespace dolfinx;

namespace
{
/// The generated forms and expressions of forms/block.py for one displacement degree.
struct BlockForms
{
  ufcx_function_space* (*space)(const char*);
  const char* u;
  ufcx_form *residual, *tangent, *energy;
  ufcx_expression *stress, *psi, *det_F;
};
const BlockForms block_p1{functionspace_form_block_residual_p1, "u_p1", form_block_residual_p1,
                          form_block_tangent_p1, form_block_energy_p1,
                          expression_block_stress_p1, expression_block_psi_p1,
                          expression_block_det_F_p1};
const BlockForms block_p2{functionspace_form_block_residual_p2, "u_p2", form_block_residual_p2,
                          form_block_tangent_p2, form_block_energy_p2,
                          expression_block_stress_p2, expression_block_psi_p2,
                          expression_block_det_F_p2};
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters, with their defaults and validity checks
  gelx::Parameters prm;
  prm.add("geometry", "width", 1.0, "block width W [mm]", gelx::Parameters::positive);
  prm.add("geometry", "height", 2.0, "block height H [mm]", gelx::Parameters::positive);
  prm.add("geometry", "h", 0.25, "mesh size [mm]", gelx::Parameters::positive);
  prm.add("geometry", "mesh", GELX_MESHES "/block.geo", "gmsh geometry file");
  prm.add("discretisation", "degree", 2, "polynomial degree of the displacement (1 or 2)",
          [](int p) { return p == 1 || p == 2 ? "" : "must be 1 or 2"; });
  prm.add("material", "G", 1.0, "shear modulus [MPa]", gelx::Parameters::positive);
  prm.add("material", "K", 10.0, "bulk modulus [MPa]", gelx::Parameters::positive);
  prm.add("load", "stretch", 1.5, "final axial stretch of the block",
          gelx::Parameters::positive);
  prm.add("load", "twist", 90.0, "final rotation of the top face [degrees]");
  gelx::LoadSteppingOptions::declare(prm);

  return gelx::run_program(argc, argv, "gelx-block", prm, [&](MPI_Comm comm)
  {
    const auto stepping = gelx::LoadSteppingOptions::from(prm);
    const double H = prm.real("height"), stretch = prm.real("stretch");
    const double twist = prm.real("twist") * M_PI / 180.0;

    // 2. Mesh from the gmsh geometry, with the physical groups "bottom" and "top"
    const gelx::TaggedMesh geo = gelx::read_geo(
        comm, prm.text("mesh"), {{"W", prm.real("width")}, {"H", H}, {"h", prm.real("h")}});

    // 3. Displacement space, material constants, residual and tangent (forms/block.py)
    const BlockForms& forms = prm.integer("degree") == 1 ? block_p1 : block_p2;
    auto V = std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(forms.space, forms.u, geo.mesh));
    auto u = std::make_shared<fem::Function<double>>(V);
    auto G = std::make_shared<fem::Constant<double>>(prm.real("G"));
    auto K = std::make_shared<fem::Constant<double>>(prm.real("K"));
    const std::map<std::string, std::shared_ptr<const fem::Constant<double>>> material
        = {{"G", G}, {"K", K}};
    auto form = [&](ufcx_form* f, std::vector<std::shared_ptr<const fem::FunctionSpace>> V_)
    {
      return std::make_shared<fem::Form<double>>(
          fem::create_form<double>(*f, V_, {{forms.u, u}}, material, {}, geo.mesh));
    };
    auto residual = form(forms.residual, {V});
    auto tangent = form(forms.tangent, {V, V});
    auto energy = form(forms.energy, {});
    auto expression = [&](ufcx_expression* e)
    {
      return std::make_shared<fem::Expression<double>>(
          fem::create_expression<double>(*e, {{forms.u, u}}, material, geo.mesh));
    };

    // 4. Boundary conditions: bottom clamped; top lifted by (stretch - 1) H t and turned by
    //    twist t about the z-axis: u = R(twist t) X - X in the plane, u_z = (stretch - 1) H t.
    const int bottom = geo.tag("bottom"), top = geo.tag("top");
    gelx::DirichletConditions bcs(V, geo.facet_tags);
    bcs.clamp(bottom);
    bcs.prescribe(top, 0, [=](double t, auto& X)
                  { return std::cos(twist * t) * X[0] - std::sin(twist * t) * X[1] - X[0]; });
    bcs.prescribe(top, 1, [=](double t, auto& X)
                  { return std::sin(twist * t) * X[0] + std::cos(twist * t) * X[1] - X[1]; });
    bcs.prescribe(top, 2, [=](double t, auto&) { return (stretch - 1) * H * t; });

    gelx::NonlinearProblem problem(u, residual, tangent, bcs.bcs(),
                                   expression(forms.det_F));
    gelx::NewtonSolver newton(comm);

    // 5. Output: displacement at the nodes, stress and energy density per cell
    gelx::ResultsWriter writer(comm, prm.text("output"), geo.mesh);
    gelx::NodalField displacement("displacement", u);
    gelx::CellField stress("cauchy_stress", expression(forms.stress));
    gelx::CellField energy_density("energy_density", expression(forms.psi));

    // 6. Follow the load path, recording each converged step
    nlohmann::json last = nlohmann::json::object();
    int newton_total = 0;
    auto on_step = [&](const gelx::StepRecord& s)
    {
      const gelx::Resultant top_load = gelx::boundary_resultant(problem, *geo.facet_tags, top);
      newton_total += s.newton.iterations;
      last = {{"step", s.step},
              {"t", s.t},
              {"axial_force", top_load.force[2]},
              {"torque", top_load.moment[2]},
              {"energy", gelx::assemble_global_scalar(*energy)},
              {"min_det_F", problem.admissibility_margin()},
              {"newton_iterations", s.newton.iterations},
              {"linear_iterations", s.newton.linear_iterations},
              {"cutbacks", s.cutbacks},
              {"wall_time", s.wall_time}};
      displacement.update();
      stress.update();
      energy_density.update();
      std::vector<std::shared_ptr<const fem::Function<double>>> fields = stress.functions();
      fields.push_back(displacement.function());
      fields.push_back(energy_density.functions()[0]);
      writer.write_fields(s.t, fields);
      writer.append_step(last);
    };
    gelx::LoadStepper stepper(problem, newton, stepping, [&](double t) { bcs.update(t); });
    const auto start = std::chrono::steady_clock::now();
    auto summary = [&](const std::string& status)
    {
      const auto dofs = V->dofmap()->index_map;
      writer.write_summary(
          "block", status, prm,
          {{"num_dofs", dofs->size_global() * V->dofmap()->index_map_bs()},
           {"num_cells", geo.mesh->topology().index_map(3)->size_global()},
           {"steps", last.value("step", 0)},
           {"newton_iterations", newton_total},
           {"cutbacks", stepper.total_cutbacks()},
           {"wall_time",
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()},
           {"axial_force", last.value("axial_force", 0.0)},
           {"torque", last.value("torque", 0.0)},
           {"energy", last.value("energy", 0.0)},
           {"min_det_F", last.value("min_det_F", 1.0)}});
    };
    try
    {
      stepper.run(on_step);
    }
    catch (const gelx::ConvergenceError& e)
    {
      summary(std::string("failed: ") + e.what()); // the completed steps stay on record
      throw;
    }

    // 7. Summary: parameters, versions, size, cost and the quantities of interest at t = 1
    summary("completed");
  });
}
