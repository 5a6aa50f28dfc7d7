#pragma once
/// @file common.h
/// What the material-law tests share: constants by name, forms and expressions on one
/// coefficient, the range of a cell field over all ranks and the NaN check of every output.

#include "support.h"

#include <cmath>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/utils.h>
#include <gelx/solvers/newton.h>
#include <gelx/io/output.h>
#include <map>
#include <memory>
#include <numeric>
#include <xtensor/xtensor.hpp>
#include <string>

namespace gelx::test
{

using Constants = std::map<std::string, std::shared_ptr<const dolfinx::fem::Constant<double>>>;
using Coefficients
    = std::map<std::string, std::shared_ptr<const dolfinx::fem::Function<double>>>;

/// Constants by name, from plain values (a value may be changed later through the returned
/// non-const pointers, see mutable_constants).
inline std::map<std::string, std::shared_ptr<dolfinx::fem::Constant<double>>>
make_constants(const std::map<std::string, double>& values)
{
  std::map<std::string, std::shared_ptr<dolfinx::fem::Constant<double>>> c;
  for (auto& [name, v] : values)
    c[name] = std::make_shared<dolfinx::fem::Constant<double>>(v);
  return c;
}

inline Constants const_constants(const std::map<std::string, std::shared_ptr<dolfinx::fem::Constant<double>>>& c)
{
  return Constants(c.begin(), c.end());
}

/// Residual and tangent forms of one generated pair on the space V.
struct Forms
{
  std::shared_ptr<dolfinx::fem::Form<double>> residual, tangent;
};

inline Forms make_forms(ufcx_form* residual, ufcx_form* tangent,
                        std::shared_ptr<const dolfinx::fem::FunctionSpace> V,
                        const Coefficients& coefficients, const Constants& constants)
{
  return {std::make_shared<dolfinx::fem::Form<double>>(dolfinx::fem::create_form<double>(
              *residual, {V}, coefficients, constants, {})),
          std::make_shared<dolfinx::fem::Form<double>>(dolfinx::fem::create_form<double>(
              *tangent, {V, V}, coefficients, constants, {}))};
}

inline std::shared_ptr<dolfinx::fem::Expression<double>>
make_expression(ufcx_expression* e, const Coefficients& coefficients, const Constants& constants,
                std::shared_ptr<const dolfinx::mesh::Mesh> mesh)
{
  return std::make_shared<dolfinx::fem::Expression<double>>(
      dolfinx::fem::create_expression<double>(*e, coefficients, constants, mesh));
}

/// Smallest and largest of the owned and ghost values of f, over all ranks; NaN propagates
/// as (NaN, NaN) so that any check on the range fails.
inline std::pair<double, double> value_range(const dolfinx::fem::Function<double>& f)
{
  double lo = INFINITY, hi = -INFINITY;
  bool nan = false;
  for (double v : f.x()->array())
  {
    nan = nan || std::isnan(v);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  int any_nan = nan;
  MPI_Comm comm = f.function_space()->mesh()->comm();
  MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &any_nan, 1, MPI_INT, MPI_LOR, comm);
  return any_nan ? std::pair<double, double>{NAN, NAN} : std::pair<double, double>{lo, hi};
}

/// Smallest and largest value of a scalar Expression over the evaluation points of every owned
/// cell (all ranks); NaN propagates as (NaN, NaN).
inline std::pair<double, double> expression_range(const dolfinx::fem::Expression<double>& e)
{
  const auto& mesh = *e.mesh();
  const std::int32_t num_cells = mesh.topology().index_map(mesh.topology().dim())->size_local();
  std::vector<std::int32_t> cells(num_cells);
  std::iota(cells.begin(), cells.end(), 0);
  xt::xtensor<double, 2> values({cells.size(), e.X().second[0] * e.value_size()});
  e.eval(cells, values);
  double lo = INFINITY, hi = -INFINITY;
  int nan = 0;
  for (double v : values)
  {
    nan = nan || std::isnan(v);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  MPI_Comm comm = mesh.comm();
  MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &nan, 1, MPI_INT, MPI_LOR, comm);
  return nan ? std::pair<double, double>{NAN, NAN} : std::pair<double, double>{lo, hi};
}

/// True when every value of every function is finite (all ranks).
inline bool all_finite(const std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>>& fs,
                       MPI_Comm comm)
{
  int ok = 1;
  for (auto& f : fs)
    for (double v : f->x()->array())
      ok = ok && std::isfinite(v);
  MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_LAND, comm);
  return ok;
}

/// Index of a stress component among CellField's outputs (xx, yy, zz, yz, xz, xy, vm, p).
enum StressComponent : int { s_xx = 0, s_yy, s_zz, s_yz, s_xz, s_xy, s_vm, s_p };

} // namespace gelx::test
