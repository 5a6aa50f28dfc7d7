// gelx-flory_rehner: the 0-D Flory-Rehner theory of thesis chapter 4 (sections 4.2-4.3) and
// appendix A. No mesh: the uniaxially constrained hydrogel is a point model.
//
// Sample runs:
//   build/demos/flory_rehner/gelx-flory_rehner --output results/flory_rehner
//   build/demos/flory_rehner/gelx-flory_rehner --output /tmp/fr --n_phi 40 --n_eps 40
//   build/demos/flory_rehner/gelx-flory_rehner --output /tmp/fr --n_nu_vm 0.01 --alpha0 0.77 --phi_i_max 0.45
//   build/demos/flory_rehner/gelx-flory_rehner --output /tmp/fr --scene peo.scene   (PEO values)
//   /usr/bin/python3 demos/flory_rehner/plot.py results/flory_rehner
//
// What it shows: maps of the largest contraction anisotropy A_max(phi_i, eps_par) of a
// uniaxially constrained gel that contracts at fixed length while a free gel contracts by
// alpha0 (Fig. 4.2b: Nnu/Vm = 0.1, 0.01, 0.001; Fig. 4.3b right: Nnu/Vm = 0.002), the check of
// the bound A_max < alpha0^-3/2 without prestrain (Eq. 4.17), and, when the Dormidontova
// parameters are supplied, the PEO gel: T~phi curves (Fig. 4.3a) and its A_max map
// (Fig. 4.3b left). Writes CSV files and summary.json into --output.

#include "theory/amax_map.h"
#include "theory/flory_rehner.h"
#include "theory/peo.h"

#include <algorithm>
#include <gelx/io/parameters.h>
#include <gelx/io/units.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>

namespace th = gelx::theory;
using nlohmann::json;

namespace
{
const char* peo_names[] = {"peo_chi_A",    "peo_chi_B",     "peo_v_over_vp", "peo_energy_p",
                           "peo_entropy_p", "peo_energy_w", "peo_entropy_w"};

/// A list of positive reals
const auto positive_list = gelx::Parameters::reals(
    [](const std::vector<double>& values)
    {
      return std::all_of(values.begin(), values.end(), [](double x) { return x > 0.0; })
                 ? ""
                 : "every value must be positive";
    });

std::string open_unit(double v) { return v > 0.0 && v < 1.0 ? "" : "must lie in (0, 1)"; }
std::string finite_value(double v) { return std::isfinite(v) ? "" : "must be a finite number"; }

json peak_json(const th::AmaxMap::Peak& p)
{
  return {{"A_max", p.A}, {"phi_i", p.phi_i}, {"eps_par", p.eps},
          {"phi_prime_i", p.phi_prime_i}, {"phi_prime_f", p.phi_prime_f}};
}

/// Compute one generic map, write it, and describe it in JSON (timed).
json run_map(double n, double a0, const std::vector<double>& phi, const std::vector<double>& eps,
             const std::string& path)
{
  const auto t0 = std::chrono::steady_clock::now();
  const th::AmaxMap m = th::amax_map(n, a0, phi, eps);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  th::write_csv(m, path);
  // Eq. 4.17 exactly on eps = 0 (the grid need not contain that line).
  th::AmaxMap::Peak zero;
  for (double p : phi)
    if (const auto c = th::contract(n, a0, p, 0.0); c.A_max > zero.A)
      zero = {c.A_max, p, 0.0, c.phi_prime_i, c.phi_prime_f};
  std::cout << "  Nnu/Vm = " << n << ": A_max = " << m.peak().A << " at phi_i = "
            << m.peak().phi_i << ", eps = " << m.peak().eps << "; at eps = 0: " << zero.A
            << " (alpha0^-3/2 = " << std::pow(a0, -1.5) << "); " << seconds << " s\n";
  return {{"n_nu_vm", n},        {"alpha0", a0},       {"csv", std::filesystem::path(path).filename()},
          {"peak", peak_json(m.peak())}, {"peak_eps_1", peak_json(m.peak_at_eps(1.0))},
          {"peak_eps_0", peak_json(zero)}, {"bound_alpha0", std::pow(a0, -1.5)},
          {"undefined", m.undefined}, {"non_unique", m.non_unique}, {"seconds", seconds}};
}
} // namespace

int main(int argc, char* argv[])
{
  // Once the output folder exists, a failure is recorded in its summary.json too
  std::filesystem::path out;
  json summary;
  try
  {
    // 1. Declare the parameters, grouped by concern.
    gelx::Parameters prm;
    prm.add("output", "output", "results/flory_rehner", "folder for CSV files and summary.json");
    prm.add("material", "n_nu_vm", "0.1,0.01,0.001", "N nu / V_m of the Fig. 4.2b maps (list)",
            positive_list);
    prm.add("material", "alpha0", 0.8, "isotropic contraction ratio of the free gel (Eq. 4.13)",
            open_unit);
    prm.add("grid", "phi_i_min", 0.0025, "smallest initial volume fraction phi_i", open_unit);
    prm.add("grid", "phi_i_max", 0.5, "largest phi_i (phi_i/alpha0^3 must stay < 1)", open_unit);
    prm.add("grid", "eps_min", -0.5, "smallest prestrain eps_par (Eq. 4.12)",
            [](double v) { return v > -1.0 ? "" : "must exceed -1"; });
    prm.add("grid", "eps_max", 1.0, "largest prestrain eps_par", finite_value);
    prm.add("grid", "n_phi", 200, "grid points in phi_i", gelx::Parameters::at_least_one);
    prm.add("grid", "n_eps", 200, "grid points in eps_par", gelx::Parameters::at_least_one);
    prm.add("peo", "peo_n_nu_vm", 0.002, "N nu / V_m of Fig. 4.3", gelx::Parameters::positive);
    prm.add("peo", "peo_phi_i_min", 0.05, "smallest phi_i of Fig. 4.3b", open_unit);
    prm.add("peo", "peo_phi_i_max", 0.275, "largest phi_i of Fig. 4.3b", open_unit);
    prm.add("peo", "peo_n_grid", 60, "grid points per axis of the PEO map",
            gelx::Parameters::at_least_one);
    prm.add("peo", "peo_T_min", 250.0, "temperature search range, K", gelx::Parameters::positive);
    prm.add("peo", "peo_T_max", 450.0, "temperature search range, K", gelx::Parameters::positive);
    prm.add("peo", "peo_curve_phi_c", 0.1, "phi_c = lambda_par^-3 of the constrained T~phi curve",
            open_unit);
    const double unset = std::numeric_limits<double>::quiet_NaN();
    const std::string required = "REQUIRED for PEO, no default (Dormidontova 2002): ";
    prm.add("peo", "peo_chi_A", unset, required + "chi = A + B/T, A (Eq. A.2)", finite_value);
    prm.add("peo", "peo_chi_B", unset, required + "chi = A + B/T, B in K", finite_value);
    prm.add("peo", "peo_v_over_vp", unset, required + "v/v_p, water over monomer volume", finite_value);
    prm.add("peo", "peo_energy_p", unset, required + "PEO-water bond: Df_p/kT = E_p/T - S_p, E_p in K", finite_value);
    prm.add("peo", "peo_entropy_p", unset, required + "PEO-water bond entropy S_p, units of k", finite_value);
    prm.add("peo", "peo_energy_w", unset, required + "water-water bond: Df_w/kT = E_w/T - S_w, E_w in K", finite_value);
    prm.add("peo", "peo_entropy_w", unset, required + "water-water bond entropy S_w, units of k", finite_value);

    // 2. Parse the command line and echo every parameter.
    bool help = false;
    const auto rest = prm.parse(argc, argv, &help);
    if (help)
    {
      std::cout << "gelx-flory_rehner [--name value ...]\n" << prm.table(true);
      return 0;
    }
    if (rest.size() > 1)
      throw gelx::InputError("unexpected argument '" + rest[1] + "'");
    const double a0 = prm.real("alpha0");
    if (prm.real("phi_i_min") >= prm.real("phi_i_max") || prm.real("eps_min") >= prm.real("eps_max"))
      throw gelx::InputError("grid ranges must have min < max");
    if (std::max(prm.real("phi_i_max"), prm.real("peo_phi_i_max")) >= a0 * a0 * a0)
      throw gelx::InputError("phi_i_max and peo_phi_i_max must stay below alpha0^3 (the "
                             "contracted gel's phi_i / alpha0^3 below 1)");
    int peo_given = 0;
    for (const char* name : peo_names)
      peo_given += std::isfinite(prm.real(name));
    if (peo_given != 0 && peo_given != 7)
      throw gelx::InputError("the PEO model needs all seven peo_chi_A ... peo_entropy_w values");
    std::cout << "gelx-flory_rehner: Flory-Rehner theory of thesis sections 4.2-4.3\n"
              << prm.table(false);
    out = prm.text("output");
    std::filesystem::create_directories(out);
    std::filesystem::remove(out / "summary.json"); // a previous run's must not pass for this one's
    // The run's scene file, as every gelx run writes: --scene reads it back (the PEO values
    // only when given: an unset one is no value)
    std::set<std::string> omit = {"output"};
    for (const char* name : peo_names)
      if (!std::isfinite(prm.real(name)))
        omit.insert(name);
    std::ofstream(out / "scene.txt") << "# gelx-flory_rehner: ./gelx run flory_rehner --scene "
                                        "scene.txt runs it again\n"
                                     << prm.scene_file(omit);
    summary = {{"scene", "flory_rehner"}, {"parameters", prm.to_json()}};
    const auto t_start = std::chrono::steady_clock::now();

    // 3. Fig. 4.2b: A_max(phi_i, eps_par) for each N nu/V_m.
    std::cout << "Fig. 4.2b maps (alpha0 = " << a0 << "):\n";
    const auto phi = th::linspace(prm.real("phi_i_min"), prm.real("phi_i_max"), prm.integer("n_phi"));
    const auto eps = th::linspace(prm.real("eps_min"), prm.real("eps_max"), prm.integer("n_eps"));
    for (double n : gelx::Parameters::real_list(prm.text("n_nu_vm")))
    {
      std::ostringstream name;
      name << "amax_n" << n << ".csv";
      summary["fig4_2b"].push_back(run_map(n, a0, phi, eps, (out / name.str()).string()));
    }

    // 4. Eq. 4.17 without prestrain, and the Chin et al. numbers quoted in section 4.3.1.
    summary["chin_et_al"] = {{"alpha0", 0.77}, {"bound", std::pow(0.77, -1.5)},
                             {"A_measured", 0.80 / 0.62}};

    // 5. Fig. 4.3b (right): the generic gel on the PEO ranges.
    std::cout << "Fig. 4.3b generic gel:\n";
    const double n_peo = prm.real("peo_n_nu_vm");
    const int ng = prm.integer("peo_n_grid");
    const auto phi3 = th::linspace(prm.real("peo_phi_i_min"), prm.real("peo_phi_i_max"), ng);
    const auto eps3 = th::linspace(prm.real("eps_min"), prm.real("eps_max"), ng);
    summary["fig4_3b_generic"] = run_map(n_peo, a0, phi3, eps3, (out / "amax_generic_n0.002.csv").string());

    // 6. Fig. 4.3a and 4.3b (left): the PEO gel, only with the published parameters supplied.
    if (peo_given == 7)
    {
      const th::PeoModel peo({prm.real("peo_chi_A"), prm.real("peo_chi_B"), prm.real("peo_v_over_vp"),
                              prm.real("peo_energy_p"), prm.real("peo_entropy_p"),
                              prm.real("peo_energy_w"), prm.real("peo_entropy_w")});
      const double T_lo = prm.real("peo_T_min"), T_hi = prm.real("peo_T_max");
      const double lambda_c = std::cbrt(1.0 / prm.real("peo_curve_phi_c"));
      std::ofstream curves(out / "peo_T_phi.csv");
      curves << gelx::units_line({"phi", "T_free", "T_constrained"}, gelx::millimetre)
             << "phi,T_free,T_constrained\n";
      for (double p : th::linspace(0.01, 0.6, 120))
      {
        const auto tf = th::peo_temperatures_free(peo, p, n_peo, T_lo, T_hi);
        const auto tc = th::peo_temperatures_constrained(peo, p, lambda_c, n_peo, T_lo, T_hi);
        for (std::size_t k = 0; k < std::max(tf.size(), tc.size()); ++k)
          curves << p << "," << (k < tf.size() ? tf[k] : NAN) << "," << (k < tc.size() ? tc[k] : NAN) << "\n";
      }
      const auto t0 = std::chrono::steady_clock::now();
      const auto m = th::peo_amax_map(peo, n_peo, a0, phi3, eps3, T_lo, T_hi);
      th::write_csv(m, (out / "amax_peo_n0.002.csv").string());
      summary["fig4_3b_peo"] = {{"peak", peak_json(m.peak())}, {"undefined", m.undefined},
                                {"non_unique", m.non_unique},
                                {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()}};
      std::cout << "PEO map: A_max = " << m.peak().A << " at phi_i = " << m.peak().phi_i
                << ", eps = " << m.peak().eps << "\n";
    }
    else
    {
      summary["fig4_3b_peo"] = "skipped: the Dormidontova (2002) parameters peo_* were not given";
      std::cout << "PEO model skipped: pass all seven --peo_* parameters (see --help)\n";
    }

    // 7. Summary.
    summary["status"] = "completed";
    summary["seconds_total"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    summary["units"] = gelx::summary_units(summary, gelx::millimetre);
    std::ofstream(out / "summary.json") << summary.dump(2) << "\n";
    std::cout << "gelx-flory_rehner: results in " << out.string() << "\n";
    return 0;
  }
  catch (const std::exception& e)
  {
    std::cerr << "gelx-flory_rehner: error: " << e.what() << "\n";
    if (!out.empty())
    {
      summary["status"] = std::string("failed: ") + e.what(); // the maps written so far stay
      std::ofstream(out / "summary.json") << summary.dump(2) << "\n";
    }
    return 1;
  }
}
