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
// alpha0 in every direction (§4.4.2 steps (1)-(5); or chi(T) is given, --chi A,B, and phi_i
// and alpha0 follow from it); the fibers hinder the contraction along
// them. By symmetry 1/8 of the cell is modelled (Fig. 4.8): rollers on the three mirror planes,
// the three outer faces plane with a free normal displacement each (zero macro stress), which is
// what the periodic conditions of Eq. 4.21-4.22 reduce to; `--cell full` solves the whole cell
// with them instead. Outputs the contraction ratios alpha_par (along the fibers), alpha_perp
// (across) and the anisotropy A = alpha_par / alpha_perp.

#include "fiber_gel_cell.h"

#include <gelx/solvers/load_stepping.h>
#include <gelx/systems/problem.h>
#include <gelx/io/program.h>

namespace
{
std::string unit_interval(double v) { return v > 0 && v < 1 ? "" : "must lie in (0, 1)"; }
std::string two_numbers(const std::vector<double>& values)
{
  return values.size() == 2 ? "" : "must be 'fit' or two numbers 'A,B'";
}
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters (lengths in nm, temperatures in K, stresses in MPa)
  gelx::scenes::FiberCellGeometry g;
  gelx::scenes::GelContraction gel;
  int order = 2;
  gelx::LoadSteppingOptions stepping;
  stepping.dt = 0.25;
  stepping.dt_max = 0.5;
  gelx::Parameters prm;
  prm.bind("geometry", "d", g.d, "fiber diameter (nm)", gelx::Parameters::positive);
  prm.bind("geometry", "l", g.l, "fiber length, caps included (nm, d <= l <= L)",
           gelx::Parameters::positive);
  prm.bind("geometry", "L", g.L, "cell length along the fiber (nm)", gelx::Parameters::positive);
  prm.bind("geometry", "D", g.D, "cell width across the fiber (nm, > d)",
           gelx::Parameters::positive);
  prm.bind("geometry", "cell", g.cell,
           "eighth: 1/8 cell with mirror planes; full: periodic; film: the 1/8 cell of a film "
           "one layer of fibers thick, its face x = D/2 free (the state demos/fiber_film tends "
           "to; alpha_perp is then the in-plane one, from U_y)",
           gelx::Parameters::one_of({"eighth", "full", "film"}));
  prm.bind("geometry", "layers", g.layers,
           "with --cell film: layers of fibers in the half film x >= 0, the first in the "
           "mid-plane (the film is 2 layers - 1 of them thick)",
           gelx::Parameters::at_least_one);
  prm.bind("mesh", "h_fiber", g.h_fiber, "mesh size on the fiber (nm)",
           gelx::Parameters::positive);
  prm.bind("mesh", "h_far", g.h_far, "mesh size away from the fiber (nm)",
           gelx::Parameters::positive);
  prm.bind("mesh", "grading", g.grading,
           "distance from the fiber over which the size grows (nm)", gelx::Parameters::positive);
  prm.bind("mesh", "order", order, "displacement degree, 1 or 2",
           [](int v) { return v == 1 || v == 2 ? "" : "must be 1 or 2"; });
  prm.bind("material", "n_nu_vm", gel.n, "N nu / V_m", gelx::Parameters::positive);
  prm.bind("material", "phi_i", gel.phi_i,
           "polymer volume fraction of the reference state at T_i", unit_interval);
  prm.bind("material", "alpha0", gel.alpha0,
           "free contraction ratio from T_i to T_f (Eq. 4.13)", unit_interval);
  std::string chi = "fit";
  prm.bind("material", "chi", chi,
           "chi(T) = A + B T (B in 1/K) as 'A,B'; then phi_i and alpha0 are the free gel's states "
           "at T_i and T_f and may not be set. 'fit': the line through the free gel's chi at "
           "phi_i (T_i) and at phi_i/alpha0^3 (T_f), section 4.4.2",
           [line = gelx::Parameters::reals(two_numbers)](const std::string& text)
           { return text == "fit" ? std::string() : line(text); });
  prm.bind("loading", "T_i", gel.T_i, "initial temperature (K)", gelx::Parameters::positive);
  prm.bind("loading", "T_f", gel.T_f,
           "final temperature (K): with --chi fit, chi(T) is fitted so that the free gel "
           "contracts by alpha0 at T_f (T_f only places that state on the temperature axis); "
           "with --chi A,B the state at T_f is the one chi(T_f) gives",
           gelx::Parameters::positive);
  stepping.bind(prm);

  return gelx::run_program(argc, argv, "gelx-fiber_gel", prm, [&](gelx::Run& run)
  {
    g.check();
    stepping.check();
    if (gel.T_f == gel.T_i)
      throw gelx::InputError("T_f must differ from T_i");
    if (chi != "fit")
    {
      if (prm.given().count("phi_i") || prm.given().count("alpha0"))
        throw gelx::InputError("--chi gives chi(T), from which phi_i and alpha0 follow: give "
                               "neither with it");
      const std::vector<double> line = gelx::Parameters::real_list(chi);
      gel.set_chi(line[0], line[1]);
    }
    if (gel.phi_f() >= 1)
      throw gelx::InputError("phi_i / alpha0^3 must stay below 1 (the contracted gel's phi)");

    // 2. The cell: mesh, gel, clamped fiber, face constraints with macro unknowns
    gelx::scenes::FiberGelCell cell(run.comm(), g, gel, order);
    const auto [chi_B, chi_A] = gel.chi_line();
    run.summary = {{"num_dofs", cell.num_dofs()},
                   {"num_cells", cell.mesh().mesh->topology().index_map(3)->size_global()},
                   {"chi_A", chi_A},
                   {"chi_B", chi_B},
                   {"phi_i", gel.phi_i},
                   {"phi_f", gel.phi_f()},
                   {"theory_alpha0", gel.alpha0},
                   {"theory_uniaxial_alpha_perp", gel.uniaxial_alpha_perp()},
                   {"setup_time", run.elapsed()}};

    // 3. Heat from T_i to T_f: T = T_i + s (T_f - T_i) as the load factor s goes from 0 to 1
    gelx::ResultsWriter& results = run.results(cell.mesh().mesh);
    gelx::FieldSet fields;
    fields.add("cauchy_stress", cell.stress()); // cauchy_stress_vm: Fig. 4.8
    fields.add("displacement", cell.displacement());
    fields.add("energy_density", cell.energy_density());
    gelx::NewtonSolver newton(run.comm());
    gelx::PathState path = run.start_path(cell.system());
    gelx::LoadStepper(cell.system(), newton, stepping,
                      [&](double s) { cell.set_temperature(gel.T_i + s * (gel.T_f - gel.T_i)); })
        .run(path,
             {[&](const gelx::StepRecord& step, gelx::PathState& state)
              {
                const gelx::scenes::CellContraction c = cell.contraction();
                const double alpha_perp = g.film() ? c.alpha_y : c.alpha_x;
                state.scene["newton_iterations"]
                    = state.scene.value("newton_iterations", 0) + step.newton.iterations;
                const double T = gel.T_i + step.load * (gel.T_f - gel.T_i);
                results.write_fields(T, fields.update());
                nlohmann::json row = gelx::step_columns(step);
                row.update({{"T", T},
                            {"alpha_par", c.alpha_z},
                            {"alpha_perp", alpha_perp},
                            {"alpha_perp_y", c.alpha_y},
                            {"anisotropy", c.alpha_z / alpha_perp}});
                results.append_step(row);

                // 4. Contraction ratios at the last temperature reached
                run.summary.update({{"alpha_par", c.alpha_z},
                                    {"alpha_perp", alpha_perp},
                                    {"alpha_perp_y", c.alpha_y},
                                    {"anisotropy", c.alpha_z / alpha_perp},
                                    {"max_shear_macro", c.shear},
                                    {"min_J_minus_phi0", cell.admissibility_margin()},
                                    {"load_steps", step.step},
                                    {"newton_iterations", state.scene["newton_iterations"]}});
              },
              gelx::ProgressLine(
                  run.comm(),
                  {.load_name = "T",
                   .load = [&](const gelx::StepRecord& r)
                   { return gel.T_i + r.load * (gel.T_f - gel.T_i); },
                   .quantity = [&] {
                     return gelx::quantity_text("alpha_par/alpha_perp", run.summary["anisotropy"]);
                   }}),
              run.checkpoints()});
  });
}
