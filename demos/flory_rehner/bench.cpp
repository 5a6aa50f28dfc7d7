// gelx-bench-flory_rehner: speed of the A_max map of Fig. 4.2b (200 x 200 grid, one core).
//
//   build/demos/flory_rehner/gelx-bench-flory_rehner [repeats]
//
// Prints, for each N nu/V_m of Fig. 4.2b, the minimum and median wall time of `repeats`
// (default 7) computations of the 200 x 200 map, and the time per grid point.

#include "theory/amax_map.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char* argv[])
{
  namespace th = gelx::theory;
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 7;
  const auto phi = th::linspace(0.0025, 0.5, 200);
  const auto eps = th::linspace(-0.5, 1.0, 200);
  std::printf("A_max map, 200 x 200 (phi_i in [0.0025, 0.5], eps in [-0.5, 1]), alpha0 = 0.8, "
              "%d repeats\n", repeats);
  std::printf("%10s %12s %12s %14s %10s\n", "Nnu/Vm", "min [s]", "median [s]", "per point [us]",
              "A_max");
  for (double n : {0.1, 0.01, 0.001})
  {
    std::vector<double> t;
    double a = 0.0;
    for (int r = 0; r < repeats; ++r)
    {
      const auto t0 = std::chrono::steady_clock::now();
      const th::AmaxMap m = th::amax_map(n, 0.8, phi, eps);
      t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      a = m.peak().A;
    }
    std::sort(t.begin(), t.end());
    std::printf("%10g %12.4f %12.4f %14.3f %10.4f\n", n, t.front(), t[t.size() / 2],
                1e6 * t.front() / (200.0 * 200.0), a);
  }
  return 0;
}
