#include "strip.h"

#include "design_strip.h" // the generated forms
#include "dual.h"

#include <algorithm>
#include <cmath>
#include <dolfinx/fem/utils.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/solvers/homotopy.h>

using namespace dolfinx;

namespace gelx::scenes
{

namespace
{
std::shared_ptr<fem::FunctionSpace> space(ufcx_function_space* (*of_form)(const char*),
                                          const char* name, std::shared_ptr<mesh::Mesh> mesh)
{
  return std::make_shared<fem::FunctionSpace>(fem::create_functionspace(of_form, name, mesh));
}
} // namespace

DesignStrip::DesignStrip(MPI_Comm comm, const DesignStripGeometry& geometry, double G, double K,
                         double regularisation)
    : _geometry(geometry),
      _mesh(box_mesh(comm, {geometry.length, geometry.width, geometry.thickness}, geometry.cells,
                     mesh::CellType::hexahedron)),
      _u(std::make_shared<fem::Function<double>>(
          space(functionspace_form_design_strip_residual, "u", _mesh.mesh))),
      _u_target(std::make_shared<fem::Function<double>>(_u->function_space())),
      _prestretch(std::make_shared<fem::Function<double>>(space(
          functionspace_form_design_strip_residual_d_prestretch, "prestretch", _mesh.mesh))),
      _forms(_mesh.mesh, {{"u", _u}, {"u_target", _u_target}, {"prestretch", _prestretch}},
             {{"G", G}, {"K", K}, {"regularisation", regularisation}, {"stretch_prior", 1.0},
              {"placement_weight", 1.0}, {"energy_weight", 0.0}})
{
  auto V = _u->function_space();
  set_design(std::vector<double>(_geometry.num_parameters(), 1.0));
  _bcs = std::make_unique<DirichletConditions>(V, _mesh.facet_tags);
  for (int k = 0; k < 3; ++k)
    _bcs->fix(_mesh.tag("x_min"), k);
  if (_geometry.far_end)
  {
    for (int k = 0; k < 3; ++k)
      _bcs->prescribe(_mesh.tag("x_max"), k,
                      [far_end = _geometry.far_end, k](double t, const std::array<double, 3>& X)
                      { return far_end(t, X)[k]; });
    _bcs->update(1);
  }
  _problem = std::make_unique<NonlinearProblem>(
      _u, _forms.form(form_design_strip_residual, {V}),
      _forms.form(form_design_strip_tangent, {V, V}), _bcs->bcs(),
      _forms.expression(expression_design_strip_det_F));
}

int DesignStrip::parameter_of(const double* X, int component) const
{
  const bool lower = X[2] < _geometry.thickness / 2;
  if ((lower && !_geometry.design_lower) || (component == 1 && !_geometry.design_angle))
    return -1;
  const int slab = std::clamp(static_cast<int>(X[0] / _geometry.length * _geometry.slabs), 0,
                              _geometry.slabs - 1);
  return (lower ? _geometry.parameters_per_layer() : 0) + component * _geometry.slabs + slab;
}

void DesignStrip::set_design(const std::vector<double>& p, double angle)
{
  const std::vector<double> X = _prestretch->function_space()->tabulate_dof_coordinates(false);
  std::span<double> values = _prestretch->x()->mutable_array();
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    const int component = i % 2, k = parameter_of(&X[3 * (i / 2)], component);
    values[i] = k >= 0 ? p.at(k) : component == 0 ? 1.0 : angle;
  }
}

void DesignStrip::solve_from_rest(NonlinearSystem& system, NewtonSolver& newton,
                                  const std::vector<double>& p, double angle)
{
  GELX_PETSC(VecSet(system.unknowns(), 0.0));
  system.unknowns_changed();
  follow_homotopy(
      system, newton, {.dt = 0.025, .secant_predictor = true},
      [&](double t)
      {
        // the stretches from 1 (stress free whatever the angle) to theirs
        std::vector<double> partial(p);
        for (int layer = 0; layer < (_geometry.design_lower ? 2 : 1); ++layer)
          for (int k = 0; k < _geometry.slabs; ++k)
          {
            const int i = layer * _geometry.parameters_per_layer() + k;
            partial[i] = 1 + t * (p[i] - 1);
          }
        set_design(partial, angle);
        _bcs->update(t);
      },
      nullptr, "rest_");
}

std::unique_ptr<AdjointGradient> DesignStrip::adjoint(NonlinearSystem& system,
                                                     DesignObjective objective,
                                                     double curvature, double twist,
                                                     double energy_weight)
{
  auto V = _u->function_space();
  auto D = _prestretch->function_space();
  Objective J{_forms.form(form_design_strip_objective),
              _forms.form(form_design_strip_objective_d_state, {V}),
              _forms.form(form_design_strip_objective_d_prestretch, {D})};
  const bool centreline = objective == DesignObjective::centreline;
  _forms.set("placement_weight", centreline ? 0.0 : 1.0);
  _forms.set("energy_weight", energy_weight);
  if (centreline)
    std::tie(J.sampled_value, J.add_sampled_d_state) = centreline_objective(curvature, twist);
  return std::make_unique<AdjointGradient>(
      system, _prestretch, _forms.form(form_design_strip_residual_d_prestretch, {V, D}), J);
}

void DesignStrip::for_each_owned_node(
    const std::function<void(std::int32_t, int, int)>& f) const
{
  const double spacing = _geometry.length / (node_layers() - 1), tol = 1e-8 * _geometry.length;
  const auto V = _u->function_space();
  const std::int32_t owned = V->dofmap()->index_map->size_local();
  const std::vector<double> X = V->tabulate_dof_coordinates(false);
  for (std::int32_t n = 0; n < owned; ++n)
  {
    const double* Xn = &X[3 * n];
    const bool interface = std::abs(Xn[2] - _geometry.thickness / 2) < tol;
    const bool low = std::abs(Xn[1]) < tol, high = std::abs(Xn[1] - _geometry.width) < tol;
    f(n, static_cast<int>(std::lround(Xn[0] / spacing)), interface && (low || high) ? high : -1);
  }
}

CentrelineSamples DesignStrip::centreline(const fem::Function<double>& displacement) const
{
  // Per node layer: the sum of the owned nodes' positions and their number, and the positions
  // of the interface's edges y = 0 and y = width
  std::vector<double> sums(node_layers() * 10, 0.0); // centre (3), count, edges (3 + 3)
  const std::vector<double> X = _u->function_space()->tabulate_dof_coordinates(false);
  const std::span<const double> u = displacement.x()->array();
  for_each_owned_node(
      [&](std::int32_t n, int layer, int edge)
      {
        double* s = &sums[10 * layer];
        for (int i = 0; i < 3; ++i)
          s[i] += X[3 * n + i] + u[3 * n + i];
        s[3] += 1;
        if (edge >= 0)
          for (int i = 0; i < 3; ++i)
            s[4 + 3 * edge + i] = X[3 * n + i] + u[3 * n + i];
      });
  MPI_Allreduce(MPI_IN_PLACE, sums.data(), sums.size(), MPI_DOUBLE, MPI_SUM,
                _mesh.mesh->comm());
  return samples_from_layer_sums(sums, _geometry.length / (node_layers() - 1));
}

std::pair<std::function<double()>, std::function<void(Vec)>>
DesignStrip::centreline_objective(double curvature, double twist) const
{
  // J of the samples, T = double or Dual
  auto objective = [=, this](const auto& centre, const auto& width, const std::vector<double>& Z)
  {
    using T = std::decay_t<decltype(centre[0][0])>;
    const CentrelineRates<T> rates(centre, width);
    const double h = Z[1] - Z[0];
    T J = 0;
    for (std::size_t k = 0; k < Z.size(); ++k)
      if (measured(Z[k]))
      {
        const T dk = rates.curvature[k] - curvature, dt = rates.twist[k] - twist;
        J = J + 0.5 * h * (dk * dk + dt * dt);
      }
    return J;
  };
  auto value = [this, objective]
  {
    const CentrelineSamples samples = centreline(*_u);
    return objective(samples.centre, samples.width, samples.Z);
  };
  auto add_d_state = [this, objective](Vec dJ_du)
  {
    // dJ/d(centre_k, width_k), one dual evaluation per sampled value (6 per layer, each
    // O(layers): cheap beside a solve), the same on every rank
    const CentrelineSamples samples = centreline(*_u);
    const std::size_t n = samples.Z.size();
    std::vector<std::array<Dual, 3>> centre(n), width(n);
    for (std::size_t k = 0; k < n; ++k)
      for (int i = 0; i < 3; ++i)
        centre[k][i] = samples.centre[k][i], width[k][i] = samples.width[k][i];
    std::vector<double> d_centre(3 * n), d_width(3 * n);
    for (std::size_t k = 0; k < n; ++k)
      for (int i = 0; i < 3; ++i)
      {
        centre[k][i].slope = 1;
        d_centre[3 * k + i] = objective(centre, width, samples.Z).slope;
        centre[k][i].slope = 0;
        width[k][i].slope = 1;
        d_width[3 * k + i] = objective(centre, width, samples.Z).slope;
        width[k][i].slope = 0;
      }
    // A centre is the mean of its layer's nodes; a width vector the edge y = width minus the
    // edge y = 0
    std::vector<double> count(n, 0.0);
    for_each_owned_node([&](std::int32_t, int layer, int) { count[layer] += 1; });
    MPI_Allreduce(MPI_IN_PLACE, count.data(), n, MPI_DOUBLE, MPI_SUM, _mesh.mesh->comm());
    PetscScalar* g;
    GELX_PETSC(VecGetArray(dJ_du, &g));
    for_each_owned_node(
        [&](std::int32_t node, int layer, int edge)
        {
          for (int i = 0; i < 3; ++i)
          {
            g[3 * node + i] += d_centre[3 * layer + i] / count[layer];
            if (edge >= 0)
              g[3 * node + i] += (edge == 1 ? 1 : -1) * d_width[3 * layer + i];
          }
        });
    GELX_PETSC(VecRestoreArray(dJ_du, &g));
  };
  return {value, add_d_state};
}

} // namespace gelx::scenes
