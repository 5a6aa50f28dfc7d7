// gelx scene: fiber_gel — anisotropic contraction of a fiber-reinforced hydrogel (thesis §4.4)
//
// Sample runs:
//   ./gelx run fiber_gel                                   # L = l = 30 nm, D = 50 nm (Fig. 4.6)
//   ./gelx run fiber_gel --l 200 --L 300 --D 40 --np 2     # L/l = 1.5 (Fig. 4.7)
//   ./gelx sweep fiber_gel                                 # Figs. 4.6, 4.7, 4.9, 4.10
//
// A periodic array of rigid fibers (diameter d, length l, hemispherical caps; a rod through the
// cell when l = L) in a Flory-Rehner gel (Eq. 4.28), unit cell D x D x L (Fig. 4.4), the fibers
// bonded to the gel. The gel is stress free in its swollen reference state phi_i at T_i; as the
// temperature rises to T_f, chi = chi_A + chi_B T grows so that a free gel would contract by
// alpha0 in every direction (§4.4.2 steps (1)-(5)); the fibers hinder the contraction along
// them. By symmetry 1/8 of the cell is modelled (Fig. 4.8): rollers on the three mirror planes,
// the three outer faces plane with a free normal displacement each (zero macro stress), which is
// what the periodic conditions of Eq. 4.21-4.22 reduce to; `--cell full` solves the whole cell
// with them instead. Outputs the contraction ratios alpha_par (along the fibers), alpha_perp
// (across) and the anisotropy A = alpha_par / alpha_perp.

#include "fiber_gel_cell.h"

#include <chrono>
#include <gelx/load_stepping.h>
#include <gelx/newton.h>
#include <gelx/output.h>
#include <gelx/petsc_utils.h>
#include <gelx/program.h>

namespace
{
std::string unit_interval(double v) { return v > 0 && v < 1 ? "" : "must lie in (0, 1)"; }
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters (lengths in nm, temperatures in K, stresses in MPa)
  gelx::Parameters prm;
  const gelx::scenes::FiberCellGeometry g0;
  prm.add("geometry", "d", g0.d, "fiber diameter (nm)", gelx::Parameters::positive);
  prm.add("geometry", "l", g0.l, "fiber length, caps included (nm, d <= l <= L)",
          gelx::Parameters::positive);
  prm.add("geometry", "L", g0.L, "cell length along the fiber (nm)", gelx::Parameters::positive);
  prm.add("geometry", "D", g0.D, "cell width across the fiber (nm, > d)",
          gelx::Parameters::positive);
  prm.add("geometry", "cell", "eighth", "eighth: 1/8 cell with mirror planes; full: periodic",
          [](const std::string& v)
          { return v == "eighth" || v == "full" ? "" : "must be eighth or full"; });
  prm.add("mesh", "h_fiber", g0.h_fiber, "mesh size on the fiber (nm)", gelx::Parameters::positive);
  prm.add("mesh", "h_far", g0.h_far, "mesh size away from the fiber (nm)",
          gelx::Parameters::positive);
  prm.add("mesh", "grading", g0.grading, "distance from the fiber over which the size grows (nm)",
          gelx::Parameters::positive);
  prm.add("mesh", "order", 2, "displacement degree, 1 or 2",
          [](int v) { return v == 1 || v == 2 ? "" : "must be 1 or 2"; });
  const gelx::scenes::GelContraction m0;
  prm.add("material", "n_nu_vm", m0.n, "N nu / V_m", gelx::Parameters::positive);
  prm.add("material", "phi_i", m0.phi_i, "polymer volume fraction of the reference state at T_i",
          unit_interval);
  prm.add("material", "alpha0", m0.alpha0, "free contraction ratio from T_i to T_f (Eq. 4.13)",
          unit_interval);
  prm.add("loading", "T_i", m0.T_i, "initial temperature (K)", gelx::Parameters::positive);
  prm.add("loading", "T_f", m0.T_f, "final temperature (K)", gelx::Parameters::positive);
  gelx::LoadSteppingOptions stepping;
  stepping.dt = 0.25;
  stepping.dt_max = 0.5;
  gelx::LoadSteppingOptions::declare(prm, stepping);

  return gelx::run_program(argc, argv, "gelx-fiber_gel", prm, [&](MPI_Comm comm)
  {
    gelx::scenes::FiberCellGeometry g;
    g.d = prm.real("d");
    g.l = prm.real("l");
    g.L = prm.real("L");
    g.D = prm.real("D");
    g.full = prm.text("cell") == "full";
    g.h_fiber = prm.real("h_fiber");
    g.h_far = prm.real("h_far");
    g.grading = prm.real("grading");
    g.check();
    gelx::scenes::GelContraction gel;
    gel.n = prm.real("n_nu_vm");
    gel.phi_i = prm.real("phi_i");
    gel.alpha0 = prm.real("alpha0");
    gel.T_i = prm.real("T_i");
    gel.T_f = prm.real("T_f");
    if (gel.phi_f() >= 1)
      throw gelx::InputError("phi_i / alpha0^3 must stay below 1 (the contracted gel's phi)");
    if (gel.T_f == gel.T_i)
      throw gelx::InputError("T_f must differ from T_i");

    // 2. The cell: mesh, gel, clamped fiber, face constraints with macro unknowns
    const auto start = std::chrono::steady_clock::now();
    gelx::scenes::FiberGelCell cell(comm, g, gel, prm.integer("order"));
    const double setup_time
        = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    // 3. Heat from T_i to T_f: T = T_i + s (T_f - T_i) as the load factor s goes from 0 to 1
    gelx::ResultsWriter writer(comm, prm.text("output"), cell.mesh().mesh);
    gelx::NodalField displacement("displacement", cell.displacement());
    gelx::CellField stress("sigma", cell.stress()); // sigma_vm: Fig. 4.8
    gelx::NewtonSolver newton(comm);
    gelx::scenes::CellContraction last;
    int iterations = 0, steps = 0;
    std::string status = "completed";
    try
    {
      gelx::LoadStepper(cell.system(), newton, gelx::LoadSteppingOptions::from(prm),
                        [&](double s) { cell.set_temperature(gel.T_i + s * (gel.T_f - gel.T_i)); })
          .run(
              [&](const gelx::StepRecord& step)
              {
                last = cell.contraction();
                iterations += step.newton.iterations;
                ++steps;
                const double T = gel.T_i + step.t * (gel.T_f - gel.T_i);
                displacement.update();
                stress.update();
                auto fields = stress.functions();
                fields.push_back(displacement.function());
                writer.write_fields(T, fields);
                writer.append_step({{"step", step.step},
                                    {"T", T},
                                    {"alpha_par", last.alpha_z},
                                    {"alpha_perp", last.alpha_x},
                                    {"alpha_perp_y", last.alpha_y},
                                    {"anisotropy", last.alpha_z / last.alpha_x},
                                    {"newton_iterations", step.newton.iterations},
                                    {"cutbacks", step.cutbacks},
                                    {"wall_time", step.wall_time}});
              });
    }
    catch (const gelx::ConvergenceError& e)
    {
      status = std::string("failed: ") + e.what(); // completed steps stay in the results
    }

    // 4. Contraction ratios at T_f next to the 0-D theory's limits
    const auto [chi_B, chi_A] = gel.chi_line();
    writer.write_summary(
        "fiber_gel", status, prm,
        {{"num_dofs", cell.num_dofs()},
         {"num_cells", cell.mesh().mesh->topology().index_map(3)->size_global()},
         {"chi_A", chi_A},
         {"chi_B", chi_B},
         {"phi_f", gel.phi_f()},
         {"alpha_par", last.alpha_z},
         {"alpha_perp", last.alpha_x},
         {"alpha_perp_y", last.alpha_y},
         {"anisotropy", last.alpha_z / last.alpha_x},
         {"max_shear_macro", last.shear},
         {"theory_alpha0", gel.alpha0},
         {"theory_uniaxial_alpha_perp", gel.uniaxial_alpha_perp()},
         {"min_J_minus_phi0", cell.admissibility_margin()},
         {"load_steps", steps},
         {"newton_iterations", iterations},
         {"setup_time", setup_time},
         {"wall_time",
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}});
    if (status != "completed")
      throw gelx::ConvergenceError(status.substr(8));
  });
}
