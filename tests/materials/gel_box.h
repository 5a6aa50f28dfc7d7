#pragma once
/// @file gel_box.h
/// A Flory-Rehner gel block (forms/gel.py, thesis Eq. 4.28) on a coarse box with symmetry
/// rollers on x = 0, y = 0, z = 0: homogeneous states are exact in it, so the gel tests compare
/// it with the 0-D theory (cpp/theory/flory_rehner.h) to solver tolerance.

#include "common.h"
#include "gel.h"

#include <gelx/systems/boundary.h>

namespace gelx::test
{

/// The gel parameters of the tests: n = N nu / V_m = 0.01, reference (mesh) state phi0 = 0.2,
/// nu = 2.99e-29 m^3 and the energy scale of the thesis' UHYPER (appendix B) with
/// length_scale 1e-6, so stresses are in MPa. chi = chi_A + chi_B T with chi_B = 0.005 / K.
struct GelParameters
{
  double n = 0.01, phi0 = 0.2, nu = 2.99e-29, length_scale = 1e-6;
  double chi_A = 0, chi_B = 0.005, T = 300;
  /// Temperature at which chi = chi_A + chi_B T takes the value chi.
  double temperature(double chi) const { return (chi - chi_A) / chi_B; }
  /// kT/nu * length_scale, the stress unit of Eq. 4.11 in the units of the output.
  double kT_nu(double T_) const { return 1.38064852e-23 * T_ / nu * length_scale; }
};

struct GelBox
{
  static constexpr std::array<double, 3> L = {1.0, 1.0, 1.0};
  TaggedBox box;
  std::shared_ptr<dolfinx::fem::FunctionSpace> V;
  std::shared_ptr<dolfinx::fem::Function<double>> u;
  std::map<std::string, std::shared_ptr<dolfinx::fem::Constant<double>>> constants;
  Forms forms;
  std::shared_ptr<const dolfinx::fem::Expression<double>> stress, margin, J;
  std::unique_ptr<DirichletConditions> bcs;

  GelBox(MPI_Comm comm, const GelParameters& p, std::array<std::size_t, 3> n)
  {
    box = tagged_box(comm, L, n);
    V = std::make_shared<dolfinx::fem::FunctionSpace>(
        dolfinx::fem::create_functionspace(functionspace_form_gel_residual_p1, "u_p1", box.mesh));
    u = std::make_shared<dolfinx::fem::Function<double>>(V);
    constants = make_constants({{"n", p.n}, {"phi0", p.phi0}, {"chi_A", p.chi_A},
                                {"chi_B", p.chi_B}, {"T", p.T}, {"nu", p.nu},
                                {"length_scale", p.length_scale}});
    const Constants c = const_constants(constants);
    const Coefficients coefficients = {{"u_p1", u}};
    forms = make_forms(form_gel_residual_p1, form_gel_tangent_p1, V, coefficients, c);
    stress = make_expression(expression_gel_stress_p1, coefficients, c, box.mesh);
    margin = make_expression(expression_gel_margin_p1, coefficients, c, box.mesh);
    J = make_expression(expression_gel_J_p1, coefficients, c, box.mesh);
    bcs = std::make_unique<DirichletConditions>(V, box.facets);
    bcs->fix(x_min, 0);
    bcs->fix(y_min, 1);
    bcs->fix(z_min, 2);
  }

  void set_temperature(double T) { constants.at("T")->value = {T}; }

  /// Stretch along each axis from the displacement of the far face (min and max over its
  /// nodes, which agree for a homogeneous state).
  std::array<std::pair<double, double>, 3> stretches() const
  {
    std::array<std::pair<double, double>, 3> s;
    for (int axis = 0; axis < 3; ++axis)
    {
      auto [lo, hi] = component_range(*u, *box.facets, 2 * axis + 2, axis);
      s[axis] = {1 + lo / L[axis], 1 + hi / L[axis]};
    }
    return s;
  }
};

} // namespace gelx::test
