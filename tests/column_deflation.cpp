// Verification: distinct equilibria of a column by deflation (issue #14).
//
// The clamped-free column with ty / tx = 1.2 and a sliding base (tests/column_inertia.cpp:
// the perfect column stays straight) under a dead axial load P. Euler-Bernoulli theory
// (inextensible elastica) gives the equilibria at a fixed load:
//   P < P_cr1: the straight column;
//   P_cr1 < P < P_cr2 = (ty/tx)^2 P_cr1: also the two bent in x (+x, -x), stable; the
//     straight one is unstable in one direction (bending in x);
//   P > P_cr2: also the two bent in y, unstable in one direction (bending in x); the straight
//     column unstable in two.
// so 3 at P = 1.2 P_cr1 and 5 at 1.6 P_cr1. A bent column's tip deflection is the
// cantilever elastica's: d/L = 2k / K(k) with K(k) = (pi / 2) sqrt(P / P_cr) (K the complete
// elliptic integral of the first kind, k = sin of half the tip rotation).
//
// From one initial guess (the straight state at P perturbed by a small lateral displacement
// in x and y: Newton's step keeps the straight column straight, so the guess must leave it),
// gelx::DeflationSolver finds solutions until its search fails. Asserted: the number found;
// that they are distinct (pairwise distances far above the solver's min_distance); each
// classified by its tip deflection (straight: below 1e-6 L); each bent one's tip deflection
// within 1 % of the elastica's at its load (the bound: the 3-D continuum column
// differs from the inextensible beam by its axial strain P/(EA) ~ 1e-3 and shear O((r/L)^2);
// the mesh by 0.4 % in the critical load); and each one's stability (negative eigenvalues of
// its tangent) as theory labels it.
//
// usage: test_column_deflation [LAST_LOAD]: the continuation up to LAST_LOAD P_cr1 (default 1.6)
// and the checks at the loads it reaches. At 2 ranks: 1.2, the first bifurcation and its three
// equilibria (the second, at 1.44 P_cr1, and its searches are half the cost; 1 rank checks it).

#include "euler_column.h"
#include "support.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <gelx/solvers/deflation.h>
#include <gelx/common/petsc_utils.h>
#include <slepcsys.h>

namespace
{
/// The loads (over P_cr1) at which the branches are checked; a run ends at one of them
constexpr std::array<double, 2> checked_loads = {1.2, 1.6};

/// Tip deflection d/L of the cantilever elastica at P / P_cr = ratio > 1.
double elastica_tip_deflection(double ratio)
{
  const double K = M_PI / 2 * std::sqrt(ratio);
  double lo = 0, hi = 1 - 1e-15; // K(k) increases from pi/2 to infinity on [0, 1)
  for (int i = 0; i < 200; ++i)
  {
    const double k = 0.5 * (lo + hi);
    (std::comp_ellint_1(k) < K ? lo : hi) = k;
  }
  const double k = 0.5 * (lo + hi);
  return 2 * k / K;
}

struct Expected
{
  std::string name;
  int axis;        ///< bending axis: -1 straight, 0 x, 1 y
  int sign;        ///< direction of the tip
  int negative;    ///< negative eigenvalues of its tangent
  double ratio;    ///< P over the critical load of its mode
};
} // namespace

int main(int argc, char* argv[])
{
  // A run ending between the checked loads would check less than it says
  const bool given = argc > 1 && argv[1][0] != '-';
  char* end = nullptr;
  const double last_load = given ? std::strtod(argv[1], &end) : checked_loads.back();
  if (given
      && (*end != '\0'
          || std::find(checked_loads.begin(), checked_loads.end(), last_load)
                 == checked_loads.end()))
  {
    std::fprintf(stderr, "test_column_deflation: LAST_LOAD is %g or %g, not %s\n",
                 checked_loads[0], checked_loads[1], argv[1]);
    return 1;
  }
  SlepcInitialize(&argc, &argv, nullptr, nullptr);
  int status;
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    const bool root = dolfinx::MPI::rank(comm) == 0;
    gelx::test::Checks checks(comm);
    gelx::scenes::ColumnParameters p;
    p.ty = 1.2 * p.tx;
    p.base = "sliding";
    gelx::scenes::EulerColumn column(comm, p);
    const double E = 2 * p.G * (1 + p.nu);
    const double P_cr1 = M_PI * M_PI * E * p.ty * std::pow(p.tx, 3) / 12 / std::pow(2 * p.L, 2);
    const double P_cr2 = M_PI * M_PI * E * p.tx * std::pow(p.ty, 3) / 12 / std::pow(2 * p.L, 2);
    const double scale = column.euler_load() / P_cr1; // the scene's load factor in P_cr1

    // The symmetry breakers: lateral displacements (z/L)^2 0.1 tx in x and in y
    auto& problem = column.problem();
    const std::array<gelx::OwnedVec, 2> perturbations
        = {column.lateral_perturbation(0, 0.1 * p.tx), column.lateral_perturbation(1, 0.1 * p.tx)};

    // Deflated continuation from the straight column at 0.95 P_cr1 to 1.6 P_cr1, in steps
    // refined after each critical load (where the bent branches rise steeply); new branches
    // are sought from the previous load's solutions perturbed either way in x and in y
    std::vector<double> loads;
    for (double load : {0.95, 1.01, 1.03, 1.06, 1.1, 1.15, 1.2, 1.3, 1.4, 1.45, 1.47, 1.5, 1.55,
                        1.6})
      if (load <= last_load)
        loads.push_back(load);
    gelx::NewtonSolver straight(comm, "straight_newton_");
    column.set_load_factor(loads[0] / scale);
    checks.require("the straight column at 0.95 P_cr1 solved from rest",
                   straight.solve(problem).converged);
    gelx::OwnedVec start(problem.create_vector());
    VecCopy(problem.unknowns(), start.get());
    // New branches sought where a branch's stability changes (deflated_continuation): the
    // searches are the cost, each one ending in a failed solve
    gelx::set_default_option("deflation_", "search", "at_bifurcations");
    gelx::DeflationSolver deflation(comm, problem);
    // Per load, the solutions: (tip deflection, negative eigenvalues, state)
    struct Point
    {
      int branch;
      std::array<double, 2> tip;
      int negative;
      Vec state;
    };
    std::map<double, std::vector<Point>> at_load;
    const auto branches = gelx::deflated_continuation(
        deflation, loads, [&](double l) { column.set_load_factor(l / scale); }, start.get(),
        [&](Vec x)
        {
          std::vector<gelx::OwnedVec> guesses;
          for (const auto& perturbation : perturbations)
            for (double sign : {1.0, -1.0})
            {
              guesses.emplace_back(problem.create_vector());
              VecWAXPY(guesses.back().get(), sign, perturbation.get(), x);
            }
          return guesses;
        },
        [&](const gelx::Branch& branch, const gelx::Equilibrium& point)
        {
          problem.set_state(point.state.get());
          const auto tip = column.tip_deflection();
          const double energy = column.potential_energy(); // collective: on every rank
          if (root)
            std::printf("P = %.3f P_cr1: branch %d, tip (%.6f, %.6f) L, energy %.8g, %d negative "
                        "eigenvalues, %d Newton iterations\n",
                        branch.loads.back(), branch.id, tip[0], tip[1], energy,
                        point.negative_eigenvalues,
                        point.newton.iterations);
          at_load[branch.loads.back()].push_back(
              {branch.id, tip, point.negative_eigenvalues, point.state.get()});
        });

    for (const double load : checked_loads)
    {
      if (load > last_load)
        continue; // the 2-rank run ends at 1.2 on purpose (usage above)
      std::vector<Expected> expected = {{"straight", -1, 0, 1, 0},
                                        {"+x", 0, 1, 0, load},
                                        {"-x", 0, -1, 0, load}};
      if (load * P_cr1 > P_cr2)
      {
        expected[0].negative = 2;
        expected.push_back({"+y", 1, 1, 1, load * P_cr1 / P_cr2});
        expected.push_back({"-y", 1, -1, 1, load * P_cr1 / P_cr2});
      }
      const std::string at = "P = " + std::to_string(load).substr(0, 3) + " P_cr1: ";
      const auto& found = at_load[load];
      checks.require(at + std::to_string(found.size()) + " solutions (theory: "
                         + std::to_string(expected.size()) + ")",
                     found.size() == expected.size());
      double closest = INFINITY;
      for (std::size_t i = 0; i < found.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
          closest = std::min(closest, deflation.distance(found[i].state, found[j].state));
      // Distinct: the nearest two differ by far more than the Newton tolerance (1e-8 of the
      // change) and the deflation's min_distance (1e-6 of the state)
      checks.require(at + "pairwise distances (rms) >= " + std::to_string(closest) + " > 1e-3",
                     found.size() < 2 || closest > 1e-3);
      for (const Expected& e : expected)
      {
        // The solution that matches: straight, or bent along e.axis in direction e.sign
        int match = -1;
        for (std::size_t i = 0; i < found.size(); ++i)
        {
          const auto& tip = found[i].tip;
          const double along = e.axis < 0 ? 0 : e.sign * tip[e.axis];
          const double across = e.axis < 0 ? std::hypot(tip[0], tip[1]) : std::abs(tip[1 - e.axis]);
          if (e.axis < 0 ? across < 1e-6 : along > 1e-2 && across < 1e-2 * along)
            match = int(i);
        }
        checks.require(at + e.name + (match >= 0 ? ": found (branch "
                                                       + std::to_string(found[match].branch) + ")"
                                                 : ": NOT found"),
                       match >= 0);
        if (match < 0)
          continue;
        if (e.axis >= 0)
          checks.relative(at + e.name + ": tip deflection / L against the elastica's",
                          e.sign * found[match].tip[e.axis], elastica_tip_deflection(e.ratio),
                          0.01);
        checks.absolute(at + e.name + ": negative eigenvalues of its tangent",
                        found[match].negative, e.negative, 0);
      }
    }
    status = checks.finish();
  }
  SlepcFinalize();
  return status;
}
