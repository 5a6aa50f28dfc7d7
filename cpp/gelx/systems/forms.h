#pragma once
/// @file forms.h
/// The generated forms and expressions of a form file, bound to one set of coefficients,
/// constants and sub-domains.

#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/mesh/MeshTags.h>
#include <map>
#include <memory>
#include <string>
#include <ufcx.h>
#include <vector>

namespace gelx
{

/// What the forms of one form file share: their coefficients (by the names FFCx gives the
/// module-level variables of the form file), their constants (likewise, with values that may
/// change between solves: a temperature, a pressure) and the sub-domains of their integrals.
/// form() and expression() bind a generated kernel to them, so a scene names each only once.
class FormBinding
{
public:
  using Coefficients
      = std::map<std::string, std::shared_ptr<const dolfinx::fem::Function<double>>>;

  /// @param constants initial values of scalar constants, by name
  FormBinding(std::shared_ptr<const dolfinx::mesh::Mesh> mesh, Coefficients coefficients,
              const std::map<std::string, double>& constants = {});

  /// Add a constant (a tensor: its values, row-major) or a coefficient.
  void add_constant(const std::string& name, const std::vector<double>& value);
  void add_coefficient(const std::string& name,
                       std::shared_ptr<const dolfinx::fem::Function<double>> f);
  /// Integrals of `type` (ds, dS, dx) over the entities tagged in `tags` (ds(k) is tag k).
  void add_subdomains(dolfinx::fem::IntegralType type,
                      std::shared_ptr<const dolfinx::mesh::MeshTags<std::int32_t>> tags);

  /// A constant by name, to change its value; throws for an unknown name.
  dolfinx::fem::Constant<double>& constant(const std::string& name);
  void set(const std::string& name, double value) { constant(name).value = {value}; }

  /// A form: spaces {} for a functional, {V} for a linear form, {V, V} for a bilinear one.
  std::shared_ptr<dolfinx::fem::Form<double>>
  form(const ufcx_form* f,
       const std::vector<std::shared_ptr<const dolfinx::fem::FunctionSpace>>& spaces = {}) const;
  std::shared_ptr<dolfinx::fem::Expression<double>> expression(const ufcx_expression* e) const;

  std::shared_ptr<const dolfinx::mesh::Mesh> mesh() const { return _mesh; }

private:
  std::shared_ptr<const dolfinx::mesh::Mesh> _mesh;
  Coefficients _coefficients;
  std::map<std::string, std::shared_ptr<dolfinx::fem::Constant<double>>> _constants;
  std::map<dolfinx::fem::IntegralType,
           std::shared_ptr<const dolfinx::mesh::MeshTags<std::int32_t>>>
      _subdomains;
};

} // namespace gelx
