// Verification: stability by inertia along the straight path of a column with two critical
// loads (issue #14).
//
// The clamped-free column of the buckling scene (demos/buckling/euler_column.h; compressible
// neo-Hookean, P2 tetrahedra, L = 30 tx) with ty / tx = 1.2 bends first about its weak axis
// (in x) at Euler's P_cr1 = pi^2 E I_y / (2L)^2, I_y = ty tx^3 / 12, and then about its strong
// one (in y) at P_cr2 = (ty / tx)^2 P_cr1 = 1.44 P_cr1. The perfect column is followed along
// its straight path by arc-length continuation from 0.9 to 1.6 P_cr1 in load steps of 0.01
// (psi = 1: on the straight path the step is nearly all load), the number of negative
// eigenvalues of the tangent read from the LDL^T factorisation of every point
// (-stability inertia): it must be 0 below P_cr1, 1 between the two and 2 beyond, changing by
// one at a time, and each change must lie within 2 % of Euler's load (the bound: the
// continuum column differs from Euler's beam by O((r/L)^2) ~ 1e-3 of shear and Poisson effect,
// the mesh by 0.4 % (tests/euler_column.cpp), and a change is located to half a step, 0.5 %).

#include "euler_column.h"
#include "support.h"

#include <cmath>
#include <cstdio>
#include <gelx/solvers/arclength.h>
#include <gelx/common/petsc_utils.h>
#include <slepcsys.h>

int main(int argc, char* argv[])
{
  SlepcInitialize(&argc, &argv, nullptr, nullptr);
  int status;
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    gelx::test::Checks checks(comm);
    gelx::scenes::ColumnParameters p;
    p.ty = 1.2 * p.tx;
    p.base = "sliding"; // a perfect column that stays straight (ColumnParameters::base)
    gelx::scenes::EulerColumn column(comm, p);
    // Euler's loads computed here from the column's data, in units of the first
    const double E = 2 * p.G * (1 + p.nu);
    const double P_cr1 = M_PI * M_PI * E * p.ty * std::pow(p.tx, 3) / 12 / std::pow(2 * p.L, 2);
    const double P_cr2 = M_PI * M_PI * E * p.tx * std::pow(p.ty, 3) / 12 / std::pow(2 * p.L, 2);
    const double first = 1, second = P_cr2 / P_cr1;
    const double scale = column.euler_load() / P_cr1; // the scene's load factor in P_cr1

    // The straight column at 0.9 P_cr1 (stable: Newton converges to it from rest)
    const double start = 0.9;
    column.set_load_factor(start / scale);
    gelx::NewtonSolver newton(comm, "start_newton_");
    checks.require("straight column at 0.9 P_cr1 solved",
                   newton.solve(column.problem()).converged);
    const std::string prefix = "straight_arclength_";
    for (auto [name, value] : {std::pair{"psi", "1"}, {"ds", "0.01"}, {"ds_max", "0.01"},
                               {"stability", "inertia"}})
      gelx::set_default_option(prefix, name, value);
    gelx::ArcLength straight(comm, column.problem(),
                             [&](double l) { column.set_load_factor(l); }, prefix);
    gelx::PathState path;
    path.load = start / scale;
    std::vector<std::pair<double, int>> points; // (load in P_cr1, negative eigenvalues)
    straight.run(path, 100,
                 {[&](const gelx::StepRecord& pt, gelx::PathState&)
                  { points.emplace_back(pt.load * scale, pt.negative_eigenvalues); }},
                 [&](const gelx::StepRecord& pt) { return pt.load * scale >= 1.6; });

    // Where the count changes: between consecutive points, located at their middle
    std::vector<double> changes;
    bool single_steps = true;
    for (std::size_t k = 1; k < points.size(); ++k)
      if (points[k].second != points[k - 1].second)
      {
        changes.push_back(0.5 * (points[k].first + points[k - 1].first));
        single_steps = single_steps && points[k].second == points[k - 1].second + 1;
      }
    std::string counts;
    for (const auto& [load, count] : points)
      if (std::abs(load - first) < 0.03 || std::abs(load - second) < 0.03)
        counts += " " + std::to_string(load).substr(0, 5) + ":" + std::to_string(count);
    int rank;
    MPI_Comm_rank(comm, &rank);
    if (rank == 0)
      std::printf("points near the critical loads (P/P_cr1:count):%s\n", counts.c_str());
    checks.require("the count is 0 at the start (" + std::to_string(points.front().second)
                       + " at " + std::to_string(points.front().first) + " P_cr1)",
                   points.front().second == 0);
    checks.require("it rises by one at a time, twice (" + std::to_string(changes.size())
                       + " changes)",
                   single_steps && changes.size() == 2);
    checks.require("it is 2 at the end (" + std::to_string(points.back().second) + " at "
                       + std::to_string(points.back().first) + " P_cr1)",
                   points.back().second == 2 && points.back().first >= 1.6);
    if (changes.size() == 2)
    {
      checks.absolute("first change (P / P_cr1) against Euler's P_cr1", changes[0], first, 0.02);
      checks.absolute("second change (P / P_cr1) against (ty/tx)^2 P_cr1", changes[1], second,
                      0.02);
    }
    status = checks.finish();
  }
  SlepcFinalize();
  return status;
}
