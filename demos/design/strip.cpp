#include "strip.h"

#include "design_strip.h" // the generated forms

#include <dolfinx/fem/utils.h>
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
      _s(std::make_shared<fem::Function<double>>(
          space(functionspace_form_design_strip_residual_d_stretch, "stretch", _mesh.mesh))),
      _forms(_mesh.mesh, {{"u", _u}, {"u_target", _u_target}, {"stretch", _s}},
             {{"G", G}, {"K", K}, {"regularisation", regularisation}, {"stretch_prior", 1.0}})
{
  auto V = _u->function_space();
  _s->x()->set(1.0);
  _bcs = std::make_unique<DirichletConditions>(V, _mesh.facet_tags);
  for (int k = 0; k < 3; ++k)
    _bcs->fix(_mesh.tag("x_min"), k);
  _problem = std::make_unique<NonlinearProblem>(
      _u, _forms.form(form_design_strip_residual, {V}),
      _forms.form(form_design_strip_tangent, {V, V}), _bcs->bcs(),
      _forms.expression(expression_design_strip_det_F));
}

int DesignStrip::slab_of(const double* X) const
{
  if (X[2] < _geometry.thickness / 2)
    return -1;
  const int k = static_cast<int>(X[0] / _geometry.length * _geometry.slabs);
  return std::clamp(k, 0, _geometry.slabs - 1);
}

void DesignStrip::set_slabs(const std::vector<double>& stretch)
{
  const std::vector<double> X = _s->function_space()->tabulate_dof_coordinates(false);
  std::span<double> values = _s->x()->mutable_array();
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    const int k = slab_of(&X[3 * i]);
    values[i] = k < 0 ? 1.0 : stretch.at(k);
  }
}

void DesignStrip::solve_from_rest(NewtonSolver& newton, const std::vector<double>& stretch)
{
  _u->x()->set(0.0);
  _problem->unknowns_changed();
  LoadStepper(*_problem, newton, {},
              [&](double t)
              {
                std::vector<double> partial(stretch.size());
                for (std::size_t k = 0; k < stretch.size(); ++k)
                  partial[k] = 1 + t * (stretch[k] - 1);
                set_slabs(partial);
              })
      .run();
}

std::unique_ptr<AdjointGradient> DesignStrip::adjoint(NonlinearSystem& system) const
{
  auto V = _u->function_space();
  auto S = _s->function_space();
  return std::make_unique<AdjointGradient>(
      system, _s, _forms.form(form_design_strip_residual_d_stretch, {V, S}),
      Objective{_forms.form(form_design_strip_objective),
                _forms.form(form_design_strip_objective_d_state, {V}),
                _forms.form(form_design_strip_objective_d_stretch, {S})});
}

} // namespace gelx::scenes
