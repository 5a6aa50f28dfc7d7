#include "bistrip.h"
#include "prestretched_strip.h"

#include <cmath>
#include <cstdio>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/utils.h>
#include <gelx/common/collectives.h>
#include <gelx/io/parameters.h>
#include <gelx/systems/prestretch.h>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <xtensor/xtensor.hpp>

using namespace dolfinx;

namespace gelx::scenes
{

void BistripParameters::bind(Parameters& prm)
{
  prm.bind("geometry", "w", w, "width of each strip (mm; the thesis varies it, 5 to 9)",
           Parameters::positive);
  prm.bind("geometry", "h", h, "thickness of each strip before A is stretched (mm)",
           Parameters::positive);
  prm.bind("geometry", "L", L, "length (mm)", Parameters::positive);
  prm.bind("geometry", "stretch", stretch,
           "L / L': the stretch of strip A before bonding (1: no misfit, < 1: compressed)",
           Parameters::positive);
  prm.bind("geometry", "section", section,
           "layers from the bottom up, 'KIND WxH' in mm, comma-separated: B stress-free, A "
           "prestretched (natural size), S prestretched (bonded size); empty: 'B wxh, A wxh'");
  prm.bind("geometry", "ends", ends,
           "clamped (z = 0 encastred, z = L a rigid face moving along z) or free",
           Parameters::one_of({"clamped", "free"}));
  prm.bind("material", "law", law,
           "nh neo-Hookean (thesis Eq. 3.1, the law of the thesis' runs), mr Mooney-Rivlin",
           Parameters::one_of({"nh", "mr"}));
  prm.bind("material", "mooney_share", mooney_share,
           "Mooney-Rivlin C01 / (C10 + C01), with C10 + C01 = G/2 (law mr)",
           [](double v) { return v >= 0 && v < 1 ? "" : "must be in [0, 1)"; });
  prm.bind("material", "G", G, "shear modulus (MPa)", Parameters::positive);
  prm.bind("material", "K", K, "bulk modulus (MPa)", Parameters::positive);
  prm.bind("material", "rho", rho, "mass density (the dynamic methods)", Parameters::positive);
  prm.bind("mesh", "degree", degree, "displacement element: 2 (Q2 hexahedra) or 1 (Q1)",
           [](int d) { return d == 1 || d == 2 ? "" : "must be 1 or 2"; });
  prm.bind("mesh", "nz", nz, "cell layers (slabs) along the strip", Parameters::at_least_one);
  prm.bind("mesh", "nx", nx, "cells across strip A's width", Parameters::at_least_one);
  prm.bind("mesh", "ns", ns, "cells across each of B's overhangs", Parameters::at_least_one);
  prm.bind("mesh", "nb", nb, "cells through B's thickness", Parameters::at_least_one);
  prm.bind("mesh", "na", na, "cells through A's thickness", Parameters::at_least_one);
}

void BistripParameters::check() const
{
  if (law != "mr" && mooney_share != 0)
    throw InputError("--mooney_share applies to --law mr only");
  double thickness = 0;
  for (const Layer& layer : layers()) // throws on a malformed section
    thickness += layer.thickness;
  if (ends == "free" && (nz % 2 != 0 && degree == 1))
    throw InputError("free ends need a node layer at z = L/2: an even nz with Q1");
  // A floor, not a convergence claim: slabs longer than a few thicknesses do not resolve the
  // strip's buckling. Measured on the default strip (Q2, 4.70 mm thick): the first critical
  // shortening 3.8 % below the converged 26.10 mm with slabs of 15 mm (3.2 thicknesses), 44 %
  // with 30 mm, 94 % with 100 mm (and 73 % above it with one slab of 300 mm)
  constexpr double slabs_per_thickness = 3.5;
  if (L / nz > slabs_per_thickness * thickness)
  {
    const int floor_nz = static_cast<int>(std::ceil(L / (slabs_per_thickness * thickness)));
    char text[320];
    std::snprintf(text, sizeof(text),
                  "--nz %d makes slabs of %.3g mm, more than %.1f times the section's "
                  "thickness %.3g mm: the strip's buckling is not resolved (use --nz %d or "
                  "more)",
                  nz, L / nz, slabs_per_thickness, thickness, floor_nz);
    throw InputError(text);
  }
}

double uniaxial_lateral_stretch(double stretch, double G, double K, double mooney_share)
{
  const double C10 = (1 - mooney_share) * G / 2, C01 = mooney_share * G / 2;
  const auto lateral_stress = [&](double l)
  {
    // sigma = 2/J dev[(C10 + C01 I1_bar) B_bar - C01 B_bar^2] + K (J - 1) I, whose lateral
    // principal value, with B_bar's lateral and axial eigenvalues b_l and b_a, is
    // 2/(3J) (b_l - b_a)(C10 + C01 b_l) + K (J - 1)
    const double J = stretch * l * l, isochoric = std::pow(J, -2.0 / 3.0);
    const double b_l = isochoric * l * l, b_a = isochoric * stretch * stretch;
    return 2 / (3 * J) * (b_l - b_a) * (C10 + C01 * b_l) + K * (J - 1);
  };
  // sigma_lateral -> -inf as l -> 0 (J -> 0, the deviatoric part ~ (b_l - b_a)/J < 0 for
  // l < stretch); and > 0 once l is large enough (K (J - 1) grows like l^2, the deviatoric
  // part decays): the bracket is widened until it holds the root
  double lo = 1e-3 * std::min(1.0, stretch), hi = std::max(1.0, 2.0 / std::sqrt(stretch));
  while (lateral_stress(hi) < 0)
    hi *= 2;
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (lateral_stress(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double BistripParameters::lateral_stretch() const
{
  return uniaxial_lateral_stretch(stretch, G, K, law == "mr" ? mooney_share : 0.0);
}

std::vector<Layer> BistripParameters::layers() const
{
  std::ostringstream bistrip;
  bistrip << "B " << w << "x" << h << ", A " << w << "x" << h;
  return parse_section(section.empty() ? bistrip.str() : section, lateral_stretch());
}

namespace
{
/// Tags of layered_strip_mesh
constexpr int strip_A = 1, fixed_end = 1, moving_end = 2;

/// A node's place in the structured mesh, from its reference position: its layer along z and
/// its cross-section position to 1e-3 mm (the mirror image of a node is the node with the
/// same cross-section position in layer `layers - 1 - layer`; gmsh's extruded layers repeat
/// the section's coordinates to about 1e-7 mm, and nodes are over 0.1 mm apart)
std::tuple<int, std::int64_t, std::int64_t> node_key(const double* X, double layer_spacing)
{
  return {static_cast<int>(std::lround(X[2] / layer_spacing)), std::llround(X[0] * 1e3),
          std::llround(X[1] * 1e3)};
}

/// The generated kernels of one law and displacement element (forms/prestretched_strip.py)
struct Kernels
{
  const char* u; ///< the displacement coefficient's name
  ufcx_function_space* (*space)(const char*);
  ufcx_function_space* (*cell_space)(const char*); ///< the DG0 space of cell_energy
  const ufcx_form *residual, *tangent, *mass, *energy_A, *energy_B, *cell_energy;
  const ufcx_expression *stress, *psi, *psi_section, *det_F;
};

#define STRIP_KERNELS(law, q)                                                                  \
  {{#law, q},                                                                                  \
   {"u_q" #q, functionspace_form_prestretched_strip_residual_##law##_q##q,                     \
    functionspace_form_prestretched_strip_cell_energy_##law##_q##q,                            \
    form_prestretched_strip_residual_##law##_q##q, form_prestretched_strip_tangent_##law##_q##q, \
    form_prestretched_strip_mass_q##q, form_prestretched_strip_energy_A_##law##_q##q,          \
    form_prestretched_strip_energy_B_##law##_q##q,                                             \
    form_prestretched_strip_cell_energy_##law##_q##q,                                          \
    expression_prestretched_strip_stress_##law##_q##q,                                         \
    expression_prestretched_strip_psi_##law##_q##q,                                            \
    expression_prestretched_strip_psi_section_##law##_q##q,                                    \
    expression_prestretched_strip_det_F_q##q}}
/// The generated kernels of the scene's law and displacement element
const Kernels& kernels(const BistripParameters& p)
{
  static const std::map<std::pair<std::string, int>, Kernels> all
      = {STRIP_KERNELS(nh, 1), STRIP_KERNELS(nh, 2), STRIP_KERNELS(mr, 1), STRIP_KERNELS(mr, 2)};
  return all.at({p.law, p.degree});
}
#undef STRIP_KERNELS
} // namespace

Bistrip::Bistrip(MPI_Comm comm, BistripParameters p)
    : _p(p), _geo(layered_strip_mesh(comm, p.layers(), p.L, {p.nz, p.nx, p.ns, p.nb, p.na})),
      _frame_half_width(p.layers()[0].width / 2), _end_distance(p.L)
{
  const Kernels& k = kernels(p);
  auto V = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(k.space, k.u, _geo.mesh));
  _u = std::make_shared<fem::Function<double>>(V);
  _u->name = "displacement";

  // Strip A's prestretch: F0 maps the bonded (mesh) state to A's stress-free state, its
  // natural length L / stretch and its unshrunk cross-section
  _F0 = std::make_shared<fem::Function<double>>(std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(k.space, "F0", _geo.mesh)));
  set_prestretch_fraction(1);

  _forms = std::make_unique<FormBinding>(
      _geo.mesh, FormBinding::Coefficients{{k.u, _u}, {"F0", _F0}},
      std::map<std::string, double>{
          {"G", p.G}, {"K", p.K}, {"mooney_share", p.mooney_share}, {"rho", p.rho}});
  _forms->add_subdomains(fem::IntegralType::cell, _geo.cell_tags);

  _bcs = std::make_unique<DirichletConditions>(V, _geo.facet_tags);
  std::vector<std::shared_ptr<const fem::DirichletBC<double>>> bcs;
  if (p.ends == "clamped")
  {
    _bcs->clamp(fixed_end);
    _bcs->fix(moving_end, 0);
    _bcs->fix(moving_end, 1);
    _bcs->prescribe(moving_end, 2, [this](double, const std::array<double, 3>&)
                    { return _end_distance - _p.L; });
    _bcs->update(0);
    bcs = _bcs->bcs();
  }
  else
  {
    // Free: only the rigid motions are held, by conditions the free strip's symmetries
    // satisfy exactly: u1 = 0 on the plane x = 0, u3 = 0 on the mid-section z = L/2, and
    // u2 = 0 on the line where the two meet the interface y = 0
    const auto plane = [&](int component, std::function<bool(const double*)> where)
    {
      auto Vc = V->sub({component});
      auto [collapsed, map] = Vc->collapse();
      auto dofs = fem::locate_dofs_geometrical(
          {*Vc, collapsed},
          [&](const xt::xtensor<double, 2>& x)
          {
            auto marked = xt::xtensor<bool, 1>::from_shape({x.shape(1)});
            for (std::size_t i = 0; i < x.shape(1); ++i)
            {
              const double X[3] = {x(0, i), x(1, i), x(2, i)};
              marked(i) = where(X);
            }
            return marked;
          });
      auto zero = std::make_shared<fem::Function<double>>(
          std::make_shared<fem::FunctionSpace>(std::move(collapsed)));
      bcs.push_back(std::make_shared<fem::DirichletBC<double>>(zero, std::move(dofs), Vc));
    };
    const double tol = 1e-8 * p.L;
    plane(0, [=](const double* X) { return std::abs(X[0]) < tol; });
    plane(2, [=](const double* X) { return std::abs(X[2] - p.L / 2) < tol; });
    plane(1, [=](const double* X)
          {
            return std::abs(X[0]) < tol && std::abs(X[1]) < tol
                   && std::abs(X[2] - p.L / 2) < tol;
          });
  }
  _problem = std::make_unique<NonlinearProblem>(
      _u, _forms->form(k.residual, {V}), _forms->form(k.tangent, {V, V}), bcs,
      _forms->expression(k.det_F));

  _energy_A = _forms->form(k.energy_A);
  _energy_B = _forms->form(k.energy_B);
  auto cells = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(k.cell_space, "v_0", _geo.mesh));
  _cell_energy = _forms->form(k.cell_energy, {cells});
  _psi_section = _forms->expression(k.psi_section);

  // Each owned cell's slab (by its midpoint) and strip
  const auto& mesh = *_geo.mesh;
  const std::int32_t owned_cells = mesh.topology().index_map(3)->size_local();
  const auto& x = mesh.geometry().x();
  const auto& cell_nodes = mesh.geometry().dofmap();
  std::vector<int> strip_of(owned_cells, 2);
  for (std::size_t i = 0; i < _geo.cell_tags->indices().size(); ++i)
    if (_geo.cell_tags->indices()[i] < owned_cells)
      strip_of[_geo.cell_tags->indices()[i]] = _geo.cell_tags->values()[i];
  for (std::int32_t c = 0; c < owned_cells; ++c)
  {
    double z = 0;
    for (std::int32_t node : cell_nodes.links(c))
      z += x[3 * node + 2];
    z /= cell_nodes.links(c).size();
    _slab_of_cell.push_back(std::min(p.nz - 1, static_cast<int>(z / p.L * p.nz)));
    _strip_of_cell.push_back(strip_of[c]);
  }
  _X = V->tabulate_dof_coordinates(false);
}

void Bistrip::set_prestretch_fraction(double s)
{
  const double lateral = std::pow(1 / _p.lateral_stretch(), s),
               axial = std::pow(1 / _p.stretch, s);
  set_prestretch(*_F0, *_geo.cell_tags,
                 {{strip_A, {lateral, 0, 0, 0, lateral, 0, 0, 0, axial}}});
}

void Bistrip::set_end_distance(double d)
{
  _end_distance = d;
  _bcs->update(0);
}

double Bistrip::end_force() const
{
  return boundary_resultant(*_problem, *_geo.facet_tags, moving_end).force[2];
}

std::pair<double, double> Bistrip::strip_energies() const
{
  return {assemble_global_scalar(*_energy_A), assemble_global_scalar(*_energy_B)};
}

double Bistrip::strain_energy() const
{
  const auto [A, B] = strip_energies();
  return A + B;
}

std::vector<std::pair<double, double>> Bistrip::slab_energies() const
{
  const auto& dofmap = *_cell_energy->function_spaces()[0]->dofmap();
  std::vector<double> cell_energy(
      (dofmap.index_map->size_local() + dofmap.index_map->num_ghosts()) * dofmap.index_map_bs(),
      0.0);
  fem::assemble_vector<double>(cell_energy, *_cell_energy);
  std::vector<double> slabs(2 * _p.nz, 0.0); // A and B, slab after slab
  for (std::size_t c = 0; c < _slab_of_cell.size(); ++c)
    slabs[2 * _slab_of_cell[c] + (_strip_of_cell[c] == strip_A ? 0 : 1)]
        += cell_energy[dofmap.cell_dofs(c)[0]];
  MPI_Allreduce(MPI_IN_PLACE, slabs.data(), slabs.size(), MPI_DOUBLE, MPI_SUM, _geo.mesh->comm());
  std::vector<std::pair<double, double>> result(_p.nz);
  for (int n = 0; n < _p.nz; ++n)
    result[n] = {slabs[2 * n], slabs[2 * n + 1]};
  return result;
}

std::vector<Bistrip::SectionPoint> Bistrip::section_energy(int slab) const
{
  std::vector<std::int32_t> cells;
  for (std::size_t c = 0; c < _slab_of_cell.size(); ++c)
    if (_slab_of_cell[c] == slab)
      cells.push_back(c);
  xt::xtensor<double, 2> psi({cells.size(), 25});
  _psi_section->eval(std::span<const std::int32_t>(cells), psi);
  // The grid's reference points (forms/bistrip.py: 5 x 5, x fastest) mapped by the cell's
  // extent in x and y: the cells are the extrusion of axis-aligned rectangles. Reference
  // coordinates of the mesh before any imperfection: the cell's bounding box is good to the
  // imperfection's amplitude
  const auto& x = _geo.mesh->geometry().x();
  const auto& cell_nodes = _geo.mesh->geometry().dofmap();
  std::vector<double> local; // x, y, strip, psi
  for (std::size_t i = 0; i < cells.size(); ++i)
  {
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (std::int32_t node : cell_nodes.links(cells[i]))
      for (int d = 0; d < 2; ++d)
      {
        lo[d] = std::min(lo[d], x[3 * node + d]);
        hi[d] = std::max(hi[d], x[3 * node + d]);
      }
    for (int j = 0; j < 25; ++j)
      local.insert(local.end(), {lo[0] + (j % 5 + 0.5) / 5 * (hi[0] - lo[0]),
                                 lo[1] + (j / 5 + 0.5) / 5 * (hi[1] - lo[1]),
                                 double(_strip_of_cell[cells[i]]), psi(i, j)});
  }
  const std::vector<double> all = all_gather(_geo.mesh->comm(), local);
  std::vector<SectionPoint> points;
  for (std::size_t i = 0; i < all.size(); i += 4)
    points.push_back({all[i], all[i + 1], all[i + 2] == strip_A ? 'A' : 'B', all[i + 3]});
  return points;
}

CentrelineSamples Bistrip::centreline() const
{
  // Per node layer: the sum of the owned nodes' positions and their number, and the positions
  // of the bottom layer's two top edges x = -+_frame_half_width, y = 0
  const int layers = _p.degree * _p.nz + 1;
  const double spacing = _p.L / (layers - 1);
  std::vector<double> sums(layers * 10, 0.0); // centre (3), count, minus edge (3), plus (3)
  const std::int32_t owned = space()->dofmap()->index_map->size_local();
  const auto& u = _u->x()->array();
  // Positions on the current mesh, which carries the imperfection if one was seeded
  const std::vector<double> X = space()->tabulate_dof_coordinates(false);
  const double tol = 1e-6 * _frame_half_width;
  for (std::int32_t n = 0; n < owned; ++n)
  {
    const auto [layer, ix, iy] = node_key(&_X[3 * n], spacing);
    double* s = &sums[10 * layer];
    for (int i = 0; i < 3; ++i)
      s[i] += X[3 * n + i] + u[3 * n + i];
    s[3] += 1;
    if (std::abs(_X[3 * n + 1]) < tol
        && std::abs(std::abs(_X[3 * n]) - _frame_half_width) < tol)
      for (int i = 0; i < 3; ++i)
        s[(_X[3 * n] < 0 ? 4 : 7) + i] = X[3 * n + i] + u[3 * n + i];
  }
  MPI_Allreduce(MPI_IN_PLACE, sums.data(), sums.size(), MPI_DOUBLE, MPI_SUM, _geo.mesh->comm());
  return samples_from_layer_sums(sums, spacing);
}

std::pair<double, double> Bistrip::mirror_asymmetry(const fem::Function<double>& v) const
{
  const int layers = _p.degree * _p.nz + 1;
  const double spacing = _p.L / (layers - 1);
  const std::int32_t owned = space()->dofmap()->index_map->size_local();
  std::vector<double> local; // layer, x key, y key, v (3)
  for (std::int32_t n = 0; n < owned; ++n)
  {
    const auto [layer, ix, iy] = node_key(&_X[3 * n], spacing);
    local.insert(local.end(), {double(layer), double(ix), double(iy), v.x()->array()[3 * n],
                               v.x()->array()[3 * n + 1], v.x()->array()[3 * n + 2]});
  }
  const std::vector<double> all = all_gather(_geo.mesh->comm(), local);
  std::map<std::tuple<int, std::int64_t, std::int64_t>, std::array<double, 3>> at;
  for (std::size_t i = 0; i < all.size(); i += 6)
    at[{int(all[i]), std::int64_t(all[i + 1]), std::int64_t(all[i + 2])}]
        = {all[i + 3], all[i + 4], all[i + 5]};
  double norm = 0, symmetric = 0, antisymmetric = 0;
  for (const auto& [key, value] : at)
  {
    const auto& [layer, ix, iy] = key;
    const std::array<double, 3>& image = at.at({layers - 1 - layer, ix, iy});
    const double Sv[3] = {image[0], image[1], -image[2]};
    for (int i = 0; i < 3; ++i)
    {
      norm += value[i] * value[i];
      symmetric += std::pow(value[i] - Sv[i], 2);
      antisymmetric += std::pow(value[i] + Sv[i], 2);
    }
  }
  return {std::sqrt(symmetric / norm), std::sqrt(antisymmetric / norm)};
}

std::shared_ptr<fem::Function<double>> Bistrip::random_imperfection(int harmonics,
                                                                    unsigned seed) const
{
  std::mt19937 twister(seed);
  // The raw 32-bit draws, not std::uniform_real_distribution, whose algorithm the standard
  // leaves to the library: the same coefficients everywhere
  const auto uniform = [&] { return 2.0 * twister() / 4294967295.0 - 1; };
  std::vector<double> a(harmonics), b(harmonics);
  for (int k = 0; k < harmonics; ++k)
  {
    a[k] = uniform();
    b[k] = uniform();
  }
  auto f = std::make_shared<fem::Function<double>>(_u->function_space());
  std::span<double> v = f->x()->mutable_array();
  double largest = 0;
  for (std::size_t n = 0; n < _X.size() / 3; ++n)
  {
    for (int k = 0; k < harmonics; ++k)
    {
      const double s = std::sin((k + 1) * M_PI * _X[3 * n + 2] / _p.L);
      v[3 * n] += a[k] * s;
      v[3 * n + 1] += b[k] * s;
    }
    largest = std::max({largest, std::abs(v[3 * n]), std::abs(v[3 * n + 1])});
  }
  MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, _geo.mesh->comm());
  for (double& value : v)
    value /= largest;
  return f;
}

std::shared_ptr<fem::Form<double>> Bistrip::mass_form() const
{
  return _forms->form(kernels(_p).mass, {space(), space()});
}

std::shared_ptr<fem::Expression<double>> Bistrip::stress() const
{
  return _forms->expression(kernels(_p).stress);
}

std::shared_ptr<fem::Expression<double>> Bistrip::energy_density() const
{
  return _forms->expression(kernels(_p).psi);
}

} // namespace gelx::scenes
