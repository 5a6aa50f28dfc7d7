#include "section.h"

#include <algorithm>
#include <cmath>
#include <gmsh.h>
#include <map>

namespace gelx::scenes
{

TaggedMesh layered_strip_mesh(MPI_Comm comm, const std::vector<Layer>& layers, double L,
                              const SectionCells& cells)
{
  // The breakpoints across: every layer's edges x = +-width/2, shared by the layers above and
  // below so that the interfaces conform; the narrowest width is the central interval
  std::vector<double> half;
  for (const Layer& l : layers)
    half.push_back(l.width / 2);
  std::sort(half.begin(), half.end());
  const double tol = 1e-9 * half.back();
  half.erase(std::unique(half.begin(), half.end(),
                         [&](double a, double b) { return b - a < tol; }),
             half.end());
  std::vector<double> xs;
  for (auto h = half.rbegin(); h != half.rend(); ++h)
    xs.push_back(-*h);
  xs.insert(xs.end(), half.begin(), half.end());
  const int central = static_cast<int>(half.size()) - 1;
  std::vector<double> ys = {-layers[0].thickness, 0};
  for (std::size_t k = 1; k < layers.size(); ++k)
    ys.push_back(ys.back() + layers[k].thickness);
  auto inside = [&](const Layer& layer, std::size_t j) // interval j is under the layer
  { return std::max(std::abs(xs[j]), std::abs(xs[j + 1])) <= layer.width / 2 + tol; };
  auto across = [&](std::size_t j) { return int(j) == central ? cells.centre : cells.overhang; };
  auto through = [&](const Layer& layer)
  { return layer.prestretched ? cells.prestretched : cells.stressfree; };
  // The hexahedra it makes, known before meshing (in reals: absurd counts overflow int)
  double section_cells = 0;
  for (const Layer& layer : layers)
    for (std::size_t j = 0; j + 1 < xs.size(); ++j)
      if (inside(layer, j))
        section_cells += double(across(j)) * through(layer);

  auto build = [&]()
  {
    gmsh::model::add("layered_strip");
    std::map<std::pair<int, int>, int> points; // (level, breakpoint) -> tag
    auto point = [&](int level, int j)
    {
      auto [it, added] = points.try_emplace({level, j}, 0);
      if (added)
        it->second = gmsh::model::geo::addPoint(xs[j], ys[level], 0);
      return it->second;
    };
    std::map<std::pair<int, int>, int> lines; // (from, to) point tags -> line tag
    auto line = [&](int a, int b, int intervals)
    {
      if (auto it = lines.find({b, a}); it != lines.end())
        return -it->second;
      auto [it, added] = lines.try_emplace({a, b}, 0);
      if (added)
      {
        it->second = gmsh::model::geo::addLine(a, b);
        gmsh::model::geo::mesh::setTransfiniteCurve(it->second, intervals + 1);
      }
      return it->second;
    };
    std::vector<int> prestretched_volumes, stressfree_volumes, bases, tops;
    for (std::size_t k = 0; k < layers.size(); ++k)
    {
      const Layer& layer = layers[k];
      for (std::size_t j = 0; j + 1 < xs.size(); ++j)
      {
        if (!inside(layer, j))
          continue;
        const int p00 = point(k, j), p10 = point(k, j + 1), p11 = point(k + 1, j + 1),
                  p01 = point(k + 1, j);
        const int loop = gmsh::model::geo::addCurveLoop(
            {line(p00, p10, across(j)), line(p10, p11, through(layer)),
             line(p11, p01, across(j)), line(p01, p00, through(layer))});
        const int surface = gmsh::model::geo::addPlaneSurface({loop});
        gmsh::model::geo::mesh::setTransfiniteSurface(surface);
        gmsh::model::geo::mesh::setRecombine(2, surface);
        // Extruded one by one, as the .geo kernel keeps shared sides shared
        gmsh::vectorpair extruded;
        gmsh::model::geo::extrude({{2, surface}}, 0, 0, L, extruded, {cells.along}, {}, true);
        bases.push_back(surface);
        tops.push_back(extruded[0].second);
        (layer.prestretched ? prestretched_volumes : stressfree_volumes)
            .push_back(extruded[1].second);
      }
    }
    gmsh::model::geo::synchronize();
    if (!prestretched_volumes.empty())
    {
      gmsh::model::addPhysicalGroup(3, prestretched_volumes, 1);
      gmsh::model::setPhysicalName(3, 1, "A");
    }
    if (!stressfree_volumes.empty())
    {
      gmsh::model::addPhysicalGroup(3, stressfree_volumes, 2);
      gmsh::model::setPhysicalName(3, 2, "B");
    }
    gmsh::model::addPhysicalGroup(2, bases, 1);
    gmsh::model::setPhysicalName(2, 1, "fixed");
    gmsh::model::addPhysicalGroup(2, tops, 2);
    gmsh::model::setPhysicalName(2, 2, "moving");
  };
  return mesh_gmsh_model(comm, build, {}, {}, section_cells * cells.along);
}

} // namespace gelx::scenes
