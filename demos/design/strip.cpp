#include "strip.h"

#include "design_strip.h" // the generated forms

#include <algorithm>
#include <cmath>
#include <dolfinx/fem/utils.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/solvers/load_stepping.h>

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
             {{"G", G}, {"K", K}, {"regularisation", regularisation}, {"stretch_prior", 1.0}})
{
  auto V = _u->function_space();
  set_design(std::vector<double>(_geometry.num_parameters(), 1.0));
  _bcs = std::make_unique<DirichletConditions>(V, _mesh.facet_tags);
  for (int k = 0; k < 3; ++k)
    _bcs->fix(_mesh.tag("x_min"), k);
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
  LoadStepper(system, newton, {},
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
              })
      .run();
}

std::unique_ptr<AdjointGradient> DesignStrip::adjoint(NonlinearSystem& system) const
{
  auto V = _u->function_space();
  auto D = _prestretch->function_space();
  return std::make_unique<AdjointGradient>(
      system, _prestretch, _forms.form(form_design_strip_residual_d_prestretch, {V, D}),
      Objective{_forms.form(form_design_strip_objective),
                _forms.form(form_design_strip_objective_d_state, {V}),
                _forms.form(form_design_strip_objective_d_prestretch, {D})});
}

CentrelineSamples DesignStrip::centreline(const fem::Function<double>& displacement) const
{
  // Per node layer: the sum of the owned nodes' positions and their number, and the positions
  // of the interface's edges y = 0 and y = width
  const int layers = 2 * _geometry.cells[0] + 1; // Q2 nodes
  const double spacing = _geometry.length / (layers - 1), tol = 1e-8 * _geometry.length;
  std::vector<double> sums(layers * 10, 0.0); // centre (3), count, edge y = 0 (3), y = width (3)
  const auto V = _u->function_space();
  const std::int32_t owned = V->dofmap()->index_map->size_local();
  const std::vector<double> X = V->tabulate_dof_coordinates(false);
  const std::span<const double> u = displacement.x()->array();
  for (std::int32_t n = 0; n < owned; ++n)
  {
    const double* Xn = &X[3 * n];
    double* s = &sums[10 * static_cast<int>(std::lround(Xn[0] / spacing))];
    for (int i = 0; i < 3; ++i)
      s[i] += Xn[i] + u[3 * n + i];
    s[3] += 1;
    const bool interface = std::abs(Xn[2] - _geometry.thickness / 2) < tol;
    const bool low = std::abs(Xn[1]) < tol, high = std::abs(Xn[1] - _geometry.width) < tol;
    if (interface && (low || high))
      for (int i = 0; i < 3; ++i)
        s[(low ? 4 : 7) + i] = Xn[i] + u[3 * n + i];
  }
  MPI_Allreduce(MPI_IN_PLACE, sums.data(), sums.size(), MPI_DOUBLE, MPI_SUM,
                _mesh.mesh->comm());
  return samples_from_layer_sums(sums, spacing);
}

} // namespace gelx::scenes
