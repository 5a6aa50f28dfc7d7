#include <gelx/systems/forms.h>

#include <dolfinx/fem/utils.h>
#include <stdexcept>

namespace gelx
{

FormBinding::FormBinding(std::shared_ptr<const dolfinx::mesh::Mesh> mesh,
                         Coefficients coefficients, const std::map<std::string, double>& constants)
    : _mesh(std::move(mesh)), _coefficients(std::move(coefficients))
{
  for (const auto& [name, value] : constants)
    add_constant(name, {value});
}

void FormBinding::add_constant(const std::string& name, const std::vector<double>& value)
{
  _constants[name] = std::make_shared<dolfinx::fem::Constant<double>>(value);
}

void FormBinding::add_coefficient(const std::string& name,
                                  std::shared_ptr<const dolfinx::fem::Function<double>> f)
{
  _coefficients[name] = std::move(f);
}

void FormBinding::add_subdomains(dolfinx::fem::IntegralType type,
                                 std::shared_ptr<const dolfinx::mesh::MeshTags<std::int32_t>> tags)
{
  _subdomains[type] = std::move(tags);
}

dolfinx::fem::Constant<double>& FormBinding::constant(const std::string& name)
{
  auto it = _constants.find(name);
  if (it == _constants.end())
    throw std::runtime_error("form binding: no constant '" + name + "'");
  return *it->second;
}

std::shared_ptr<dolfinx::fem::Form<double>>
FormBinding::form(const ufcx_form* f,
                  const std::vector<std::shared_ptr<const dolfinx::fem::FunctionSpace>>& spaces) const
{
  const std::map<std::string, std::shared_ptr<const dolfinx::fem::Constant<double>>> constants(
      _constants.begin(), _constants.end());
  std::map<dolfinx::fem::IntegralType, const dolfinx::mesh::MeshTags<std::int32_t>*> subdomains;
  for (const auto& [type, tags] : _subdomains)
    subdomains[type] = tags.get();
  return std::make_shared<dolfinx::fem::Form<double>>(dolfinx::fem::create_form<double>(
      *f, spaces, _coefficients, constants, subdomains, _mesh));
}

std::shared_ptr<dolfinx::fem::Expression<double>>
FormBinding::expression(const ufcx_expression* e) const
{
  const std::map<std::string, std::shared_ptr<const dolfinx::fem::Constant<double>>> constants(
      _constants.begin(), _constants.end());
  return std::make_shared<dolfinx::fem::Expression<double>>(
      dolfinx::fem::create_expression<double>(*e, _coefficients, constants, _mesh));
}

} // namespace gelx
