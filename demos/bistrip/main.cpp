// gelx scene: the prestretched bistrip of thesis chapter 3 — helices, a perversion, and where
// the strain energy goes
//
// Sample runs:
//   ./gelx run bistrip                                    (the whole path, 30 -> 9 cm)
//   ./gelx run bistrip --end_distance 200 --nz 60         (coarse, up to the first helices)
//   ./gelx run bistrip --ends free --stretch 1.02 --L 60 --nz 20   (the small-misfit check)
//   ./gelx run bistrip --w 9 --section "B 9x3, S 9x3, B 9x0.2"     (a tristrip, Fig. 3.10c)
//   ./gelx run bistrip --w 3 --stretch 0.4 --seed random --bonding ramp --end_distance 270
//                      --return_distance 300                     (pre-compressed, Figs. 3.8-9)
//   ./gelx run bistrip --end_distance 233 --equilibria 6          (other equilibria there)
//   ./gelx run bistrip --law mr --mooney_share 0.5 --end_distance 200 --nz 60  (Mooney-Rivlin)
//   ./gelx sweep bistrip                                  (the studies of thesis section 3.4)
//
// The model (thesis section 3.2-3.3, Table 3.1): strip B (lower, w x h) is stress-free; strip A
// (upper) was stretched from its natural length L / stretch to L, its cross-section shrinking
// by the lateral stretch of that uniaxial stretch (Fig. 3.10a), and bonded to B's top face. A
// carries the stretch as its prestretch F0, so the bonded, straight strip is the reference
// state. End z = 0 is encastred; end z = L moves along z as a rigid face that does not rotate.
//
//  1. Eigen-buckling about the bonded state (Fig. 3.1c): the first modes, their critical
//     end shortening and their symmetry about the mid-plane z = L/2 (eigenvalues.csv, modes/).
//  2. The mode to seed (mode 1 by default) is added to the mesh at the thesis' amplitude, as
//     ABAQUS' *IMPERFECTION does.
//  3. The ends come together from L to the final end distance on a smooth-step ramp, by damped
//     quasi-static dynamics (gelx::DampedDynamics, ABAQUS' *STABILIZE; --method dynamics) or
//     with inertia from the bonded strip's equilibrium at rest (gelx::InertialDynamics,
//     ABAQUS/Explicit's problem; --method inertia, or explicit central differences as
//     ABAQUS/Explicit integrates it, --method explicit), methods.h. At every output
//     distance: end force, the strain energy of each strip, kinetic and dissipated energy, the
//     work of the end force, the number of negative tangent eigenvalues, the helical segments
//     and perversions read off the centreline (centreline.h), the energy of every slab (Fig.
//     3.4b) and the shape coloured by von Mises stress (fields.xdmf). With --method arclength
//     the path is followed by arc-length continuation in the end shortening instead: it stays
//     on the unstable branch that continues the straight strip (demos/bistrip/README.md).
//     With --return_distance the end then moves back out (the stretching of Fig. 3.9).
//  4. At the final distance: the energy density over three cross-sections (Fig. 3.6): a
//     helical site, the edge and the centre of the perversion nearest mid-length; with
//     --equilibria, further equilibria there by deflation, their energies and stability.
// With --ends free (no support, the misfit alone) the scene solves the bonded strip's free
// equilibrium instead: the curvature of the bilayer (tests/bistrip.py checks it against
// Timoshenko's bimetal formula).

#include "analysis.h"
#include "bistrip.h"
#include "methods.h"
#include "path_record.h"
#include "stability.h"

#include <gelx/solvers/buckling.h>
#include <gelx/solvers/newton.h>
#include <gelx/io/output.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/io/program.h>

int main(int argc, char* argv[])
{
  // 1. Scene parameters: the strip (bistrip.h) and what is done with it (analysis.h)
  gelx::scenes::BistripParameters p;
  gelx::scenes::BistripAnalysis a;
  gelx::Parameters prm;
  p.bind(prm);
  a.bind(prm);

  return gelx::run_program(argc, argv, "gelx-bistrip", prm, [&](gelx::Run& run)
  {
    p.check();
    a.check(p);

    // 2. The bonded strip
    gelx::scenes::Bistrip strip(run.comm(), p);
    gelx::NonlinearProblem& problem = strip.problem();
    const auto [prestress_A, prestress_B] = strip.strip_energies();
    run.summary = {{"num_dofs", strip.space()->dofmap()->index_map->size_global() * 3},
                   {"lateral_stretch", p.lateral_stretch()},
                   {"prestress_energy", prestress_A + prestress_B}};
    gelx::FieldSet fields;
    fields.add("displacement", strip.displacement());
    fields.add("cauchy_stress", strip.stress());
    fields.add("energy_density", strip.energy_density());

    if (p.ends == "free")
    {
      // The misfit alone: the free bilayer's equilibrium. Newton's linearised steps stretch
      // the bending strip, so |R| grows on the way to the solution and a backtracking line
      // search on |R| stalls (measured: 25 steps of 4 %); full Newton steps converge in 7
      gelx::set_default_option("newton_", "snes_linesearch_type", "basic");
      gelx::NewtonSolver newton(run.comm());
      gelx::ResultsWriter& results = run.results(strip.mesh().mesh);
      const gelx::NewtonReport report = newton.solve(problem);
      if (!report.converged)
        throw gelx::ConvergenceError("the free bilayer's equilibrium: " + report.reason);
      results.write_fields(1, fields.update());
      const gelx::scenes::CentrelineSamples c = strip.centreline();
      std::vector<nlohmann::json> rows;
      for (std::size_t k = 0; k < c.Z.size(); ++k)
        rows.push_back({{"Z", c.Z[k]}, {"x", c.centre[k][0]}, {"y", c.centre[k][1]},
                        {"z", c.centre[k][2]}});
      results.write_table("centreline.csv", rows);
      run.summary["newton_iterations"] = report.iterations;
      return;
    }

    // 3. The bonded state's stability, when A is pre-compressed (a strip A in tension leaves
    //    the bonded strip stable): the inertia of its tangent at u = 0. Compressed enough, A
    //    makes it unstable already, and it needs a leg 0 (--bonding quench or ramp). About a
    //    stable one, eigen-buckling: the tangent K and the tangent under a small end
    //    shortening (the perturbation load), the critical shortening its load factor times
    //    the probe's
    if (p.stretch < 1)
    {
      const int bonded_negative = gelx::tangent_negative_eigenvalues(run.comm(), problem);
      run.summary["bonded_negative_eigenvalues"] = bonded_negative;
      if (bonded_negative > 0 && a.bonding == "instant")
        throw gelx::InputError(
            "the bonded strip is unstable (" + std::to_string(bonded_negative)
            + " negative eigenvalues of its tangent): eigen-buckling about it does not apply "
              "and dynamics from it needs steps of 1e-9 s: use --bonding quench or ramp with "
              "--seed random");
    }
    gelx::scenes::BondedBuckling bonded;
    if (a.seed == "mode")
      bonded = gelx::scenes::bonded_buckling(run.comm(), strip, p, a, prm.text("output"),
                                             run.summary);
    const std::vector<gelx::BucklingMode>& modes = bonded.modes;

    // 4. The imperfection, a buckling mode (plus --noise, random) or random (and, with
    //    --bonding ramp, A without its prestretch yet)
    if (a.bonding == "ramp")
      strip.set_prestretch_fraction(0);
    std::vector<gelx::BucklingMode> shapes;
    std::vector<double> amplitudes;
    if (a.seed == "mode")
    {
      shapes.push_back(modes[a.seed_mode - 1]);
      amplitudes.push_back(a.imperfection);
    }
    if (a.seed == "random" || a.noise > 0)
    {
      shapes.push_back({0, strip.random_imperfection(a.harmonics, a.random_seed)});
      amplitudes.push_back(a.seed == "random" ? a.imperfection : a.noise);
    }
    gelx::seed_imperfection(*strip.mesh().mesh, shapes, amplitudes);
    gelx::ResultsWriter& results = run.results(strip.mesh().mesh);
    if (!modes.empty())
      results.write_table("eigenvalues.csv", bonded.rows);

    // 5. The path from L to the final end distance by the chosen method (methods.h), recorded
    //    at every step and output every output_every of end travel (path_record.h). Before
    //    the first critical end distance the strip is straight: the last output there is
    //    recorded as such (the same on any number of ranks; tests/CMakeLists.txt compares)
    const double prebuckled_distance
        = modes.empty() ? NAN : p.L - modes[0].load_factor * a.probe_shortening;
    gelx::scenes::PathRecord record(run, results, fields, strip, p, a, prebuckled_distance);
    gelx::scenes::follow_path(run, strip, p, a, record);

    // 6. The energy density over three cross-sections of the final state (Fig. 3.6): the
    //    perversion nearest mid-length, its edge and the helix beyond it
    record.write_sections();

    // 7. With --equilibria: other equilibria at the final end distance by deflation (the
    //    thesis' "metastable states ... with very close strain energy but different numbers
    //    of perversions"), guessed from the path's state and the buckling modes
    if (a.equilibria > 0)
      gelx::scenes::seek_equilibria(run.comm(), strip, a, modes,
                                    record.last_negative_eigenvalues(), results, fields,
                                    prm.text("output"), run.summary);
  });
}
