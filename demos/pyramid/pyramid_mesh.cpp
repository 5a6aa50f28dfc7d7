#include "pyramid_mesh.h"

#include <array>
#include <cmath>
#include <gmsh.h>
#include <map>
#include <stdexcept>

namespace gelx::scenes
{
namespace
{
using Point = std::array<double, 3>;

Point mix(std::initializer_list<Point> points)
{
  Point c{0, 0, 0};
  for (const Point& p : points)
    for (int i = 0; i < 3; ++i)
      c[i] += p[i] / points.size();
  return c;
}

Point along(const Point& from, const Point& to, double f)
{
  return {from[0] + f * (to[0] - from[0]), from[1] + f * (to[1] - from[1]),
          from[2] + f * (to[2] - from[2])};
}

/// Builds the model in gmsh's built-in kernel, creating every point, line and quadrilateral once
/// (neighbouring hexahedra share them, which makes the mesh conforming).
class HexBuilder
{
public:
  explicit HexBuilder(double length_scale) : _tol(1e-9 * length_scale) {}

  int point(const Point& p)
  {
    const std::array<long long, 3> key
        = {std::llround(p[0] / _tol), std::llround(p[1] / _tol), std::llround(p[2] / _tol)};
    auto [it, added] = _points.try_emplace(key, 0);
    if (added)
      it->second = gmsh::model::geo::addPoint(p[0], p[1], p[2]);
    return it->second;
  }

  /// The line p -> q, signed by its orientation.
  int line(int p, int q)
  {
    auto it = _lines.find({std::min(p, q), std::max(p, q)});
    if (it == _lines.end())
    {
      const int l = gmsh::model::geo::addLine(p, q);
      _new_lines.push_back(l);
      it = _lines.emplace(std::make_pair(std::min(p, q), std::max(p, q)), p < q ? l : -l).first;
    }
    return p < q ? it->second : -it->second;
  }

  /// The plane quadrilateral p0 p1 p2 p3, structured and recombined.
  int quad(const std::array<int, 4>& p)
  {
    std::array<int, 4> key = p;
    std::sort(key.begin(), key.end());
    auto it = _quads.find(key);
    if (it != _quads.end())
      return it->second;
    const int loop = gmsh::model::geo::addCurveLoop(
        {line(p[0], p[1]), line(p[1], p[2]), line(p[2], p[3]), line(p[3], p[0])});
    const int s = gmsh::model::geo::addPlaneSurface({loop});
    gmsh::model::geo::mesh::setTransfiniteSurface(s, "Left", {p[0], p[1], p[2], p[3]});
    gmsh::model::geo::mesh::setRecombine(2, s);
    _quads[key] = s;
    return s;
  }

  /// The hexahedron with bottom face b (counter-clockwise) and top face c above it.
  void hex(const std::array<Point, 4>& b, const std::array<Point, 4>& c)
  {
    std::array<int, 8> v;
    for (int i = 0; i < 4; ++i)
    {
      v[i] = point(b[i]);
      v[4 + i] = point(c[i]);
    }
    const int loop = gmsh::model::geo::addSurfaceLoop(
        {quad({v[0], v[1], v[2], v[3]}), quad({v[4], v[5], v[6], v[7]}),
         quad({v[0], v[1], v[5], v[4]}), quad({v[1], v[2], v[6], v[5]}),
         quad({v[2], v[3], v[7], v[6]}), quad({v[3], v[0], v[4], v[7]})});
    const int vol = gmsh::model::geo::addVolume({loop});
    gmsh::model::geo::mesh::setTransfiniteVolume(vol, {v.begin(), v.end()});
  }

  /// Lines created since the last call (to give them their number of nodes).
  std::vector<int> take_new_lines() { return std::exchange(_new_lines, {}); }

private:
  double _tol;
  std::map<std::array<long long, 3>, int> _points;
  std::map<std::pair<int, int>, int> _lines;
  std::map<std::array<int, 4>, int> _quads;
  std::vector<int> _new_lines;
};

/// Tetrahedron (apex, base[0..2]) in hexahedra: the tip (the part within `fractions[0]` of the
/// apex) into four, each frustum between successive fractions into three.
void split_tetrahedron(HexBuilder& mesh, const Point& apex, const std::array<Point, 3>& base,
                       const std::vector<double>& fractions)
{
  auto cut = [&](double f)
  {
    return std::array<Point, 3>{along(apex, base[0], f), along(apex, base[1], f),
                                along(apex, base[2], f)};
  };
  // The tip: at each vertex X (with the others Y, Z, W) the hexahedron of X, its edge
  // midpoints, the centroids of its faces and the tetrahedron's centroid
  const auto tip = cut(fractions.front());
  const std::array<Point, 4> v = {apex, tip[0], tip[1], tip[2]};
  const Point centroid = mix({v[0], v[1], v[2], v[3]});
  for (int x = 0; x < 4; ++x)
  {
    const Point& X = v[x];
    const Point &Y = v[(x + 1) % 4], &Z = v[(x + 2) % 4], &W = v[(x + 3) % 4];
    mesh.hex({X, mix({X, Y}), mix({X, Y, Z}), mix({X, Z})},
             {mix({X, W}), mix({X, Y, W}), centroid, mix({X, Z, W})});
  }
  // The frusta: at each corner i of a cut triangle, the quadrilateral of the corner, its edge
  // midpoints and the triangle's centroid, joined to the same one on the next cut
  for (std::size_t k = 0; k + 1 < fractions.size(); ++k)
  {
    const auto upper = cut(fractions[k]), lower = cut(fractions[k + 1]);
    auto corner_quad = [](const std::array<Point, 3>& t, int i)
    {
      const Point &a = t[i], &b = t[(i + 1) % 3], &c = t[(i + 2) % 3];
      return std::array<Point, 4>{a, mix({a, b}), mix({a, b, c}), mix({a, c})};
    };
    for (int i = 0; i < 3; ++i)
      mesh.hex(corner_quad(lower, i), corner_quad(upper, i));
  }
}

/// Number of cells and the progression ratio that cover `length` with a first cell of
/// `first` growing by about `growth` each.
std::pair<int, double> graded(double length, double first, double growth)
{
  if (length <= first)
    return {1, 1.0};
  const int n = std::max(1, int(std::ceil(std::log(1 + length * (growth - 1) / first)
                                          / std::log(growth))));
  // The exact ratio r with first (r^n - 1)/(r - 1) = length, by bisection on [1, growth^2]
  double lo = 1.0 + 1e-12, hi = growth * growth;
  for (int i = 0; i < 200; ++i)
  {
    const double r = 0.5 * (lo + hi);
    (first * (std::pow(r, n) - 1) / (r - 1) < length ? lo : hi) = r;
  }
  return {n, 0.5 * (lo + hi)};
}

/// Whether all points lie on the plane n . x = c, plane = (n, c), within a distance tol.
bool on_plane(const std::vector<Point>& points, const std::array<double, 4>& plane, double tol)
{
  const double n = std::sqrt(plane[0] * plane[0] + plane[1] * plane[1] + plane[2] * plane[2]);
  for (const Point& p : points)
    if (std::abs(plane[0] * p[0] + plane[1] * p[1] + plane[2] * p[2] - plane[3]) > tol * n)
      return false;
  return true;
}

/// The size of the pyramid's cells at its foot (half an edge in `cells` cells), where the base's
/// grading starts.
double foot_cell(const PyramidGeometry& g) { return 0.25 * g.L / g.cells; }

/// The top of the base and the pyramid over the eighth 0 <= y <= x of the cell, or over its
/// mirror image in the plane x = y (`mirrored`: x and y swapped): the tetrahedron A O P Q in
/// hexahedra, and the top of the base outside the pyramid as two quadrilaterals between the
/// pyramid's foot x = a, the side x = w and the lines y = 0, y = x/2 and y = x, graded away
/// from the pyramid. Returns the base's top faces (the pyramid's footprint and the rest), to
/// be extruded.
///
/// Why this top face: it has the diagonal x = y as a mesh line, so that the quarter, built as
/// this part and its mirror image, is meshed conformingly on the diagonal plane, and the eighth
/// alone is exactly half of the quarter's mesh. Its columns are straight lines x = const with
/// 2 cells rows of height x / (2 cells): the pyramid's foot spacing at x = a.
gmsh::vectorpair build_eighth(HexBuilder& mesh, const PyramidGeometry& g, bool mirrored)
{
  const double a = g.L / 2, w = g.W / 2, H = g.L / std::sqrt(2.0), t = g.t;
  auto image = [&](const Point& p) { return mirrored ? Point{p[1], p[0], p[2]} : p; };
  const Point A = image({0, 0, t + H}), O = image({0, 0, t}), P = image({a, 0, t}),
              Q = image({a, a, t});
  std::vector<double> fractions;
  for (int k = g.tip_levels; k >= 0; --k)
    fractions.push_back(std::pow(0.5, k));
  split_tetrahedron(mesh, A, {O, P, Q}, fractions);
  for (int l : mesh.take_new_lines())
    gmsh::model::geo::mesh::setTransfiniteCurve(std::abs(l), g.cells + 1);

  // The top of the base outside the pyramid: two quadrilaterals graded away from it
  const auto [n_out, ratio] = graded(w - a, foot_cell(g), g.growth);
  const int p = mesh.point(P), m = mesh.point(mix({P, Q})), q = mesh.point(Q),
            p_out = mesh.point(image({w, 0, t})), m_out = mesh.point(image({w, w / 2, t})),
            corner = mesh.point(image({w, w, t}));
  // Outward lines first, from the pyramid, so that their progression grows outward; the three
  // share one progression, so that their nodes lie on the same lines x = const
  for (auto [from, to] : std::vector<std::pair<int, int>>{{p, p_out}, {m, m_out}, {q, corner}})
  {
    const int l = mesh.line(from, to);
    gmsh::model::geo::mesh::setTransfiniteCurve(std::abs(l), n_out + 1, "Progression",
                                                l > 0 ? ratio : 1 / ratio);
  }
  mesh.take_new_lines();
  gmsh::vectorpair top;
  for (const std::array<int, 4>& r :
       std::vector<std::array<int, 4>>{{p, p_out, m_out, m}, {m, m_out, corner, q}})
    top.push_back({2, mesh.quad(r)});
  for (int l : mesh.take_new_lines()) // the side's edges, parallel to the pyramid's foot
    gmsh::model::geo::mesh::setTransfiniteCurve(std::abs(l), g.cells + 1);
  // ... and the pyramid's footprint: the bottoms of its lowest hexahedra
  for (const auto& [X, Y, Z] : std::vector<std::array<Point, 3>>{{O, P, Q}, {P, Q, O}, {Q, O, P}})
    top.push_back({2, mesh.quad({mesh.point(X), mesh.point(mix({X, Y})),
                                 mesh.point(mix({X, Y, Z})), mesh.point(mix({X, Z}))})});
  return top;
}

/// The top of the base and the pyramid over the quarter 0 <= x, y of the cell, with the top of
/// the base outside the pyramid as five quadrilaterals graded away from it: two along each
/// side of the pyramid's foot and a block at the cell's corner (which straddles the diagonal
/// x = y). Returns the base's top faces (the pyramid's footprint and the rest), to be
/// extruded. The layout of the default quarter and half; the eighth needs build_eighth's.
gmsh::vectorpair build_quarter_with_corner_block(HexBuilder& mesh, const PyramidGeometry& g)
{
  const double a = g.L / 2, w = g.W / 2, H = g.L / std::sqrt(2.0), t = g.t;
  // The quarter pyramid: two tetrahedra sharing the diagonal plane x = y
  const Point A = {0, 0, t + H}, O = {0, 0, t}, P = {a, 0, t}, Q = {a, a, t}, S = {0, a, t};
  std::vector<double> fractions;
  for (int k = g.tip_levels; k >= 0; --k)
    fractions.push_back(std::pow(0.5, k));
  split_tetrahedron(mesh, A, {O, P, Q}, fractions);
  split_tetrahedron(mesh, A, {O, Q, S}, fractions);
  for (int l : mesh.take_new_lines())
    gmsh::model::geo::mesh::setTransfiniteCurve(std::abs(l), g.cells + 1);

  const auto [n_out, ratio] = graded(w - a, foot_cell(g), g.growth);
  const Point P_out = {w, 0, t}, mPQ = mix({P, Q}), mPQ_out = {w, a / 2, t}, Q_x = {w, a, t},
              Q_y = {a, w, t}, corner = {w, w, t}, mQS = mix({Q, S}), mQS_out = {a / 2, w, t},
              S_out = {0, w, t};
  const int p = mesh.point(P), q = mesh.point(Q), s = mesh.point(S), m1 = mesh.point(mPQ),
            m2 = mesh.point(mQS);
  const int p_o = mesh.point(P_out), m1_o = mesh.point(mPQ_out), qx = mesh.point(Q_x),
            qy = mesh.point(Q_y), c = mesh.point(corner), m2_o = mesh.point(mQS_out),
            s_o = mesh.point(S_out);
  // Outward lines first, from the pyramid, so that their progression grows outward
  for (auto [from, to] : std::vector<std::pair<int, int>>{
           {p, p_o}, {m1, m1_o}, {q, qx}, {q, qy}, {m2, m2_o}, {s, s_o}, {qx, c}, {qy, c}})
  {
    const int l = mesh.line(from, to);
    gmsh::model::geo::mesh::setTransfiniteCurve(std::abs(l), n_out + 1, "Progression",
                                                l > 0 ? ratio : 1 / ratio);
  }
  mesh.take_new_lines();
  gmsh::vectorpair top;
  for (const std::array<int, 4>& r : std::vector<std::array<int, 4>>{
           {p, p_o, m1_o, m1}, {m1, m1_o, qx, q}, {q, qx, c, qy}, {m2, q, qy, m2_o},
           {s, m2, m2_o, s_o}})
    top.push_back({2, mesh.quad(r)});
  for (int l : mesh.take_new_lines()) // the outer edges, parallel to the pyramid's
    gmsh::model::geo::mesh::setTransfiniteCurve(std::abs(l), g.cells + 1);
  // ... and the pyramid's footprint: the bottoms of its lowest hexahedra
  for (const auto& [X, Y, Z] : std::vector<std::array<Point, 3>>{
           {O, P, Q}, {P, Q, O}, {Q, O, P}, {O, Q, S}, {Q, S, O}, {S, O, Q}})
    top.push_back({2, mesh.quad({mesh.point(X), mesh.point(mix({X, Y})),
                                 mesh.point(mix({X, Y, Z})), mesh.point(mix({X, Z}))})});
  return top;
}
} // namespace

TaggedMesh pyramid_mesh(MPI_Comm comm, const PyramidGeometry& g)
{
  const double a = g.L / 2, w = g.W / 2, H = g.L / std::sqrt(2.0), t = g.t;
  if (!(a < w))
    throw std::invalid_argument("the cell width W must exceed the pyramid width L");
  const bool eighth = g.domain == "eighth";
  if (eighth && g.base != "diagonal")
    throw std::invalid_argument("the eighth needs the base meshed along the diagonal");
  auto build = [&]()
  {
    gmsh::model::add("pyramid");
    HexBuilder mesh(g.L);
    // The eighth 0 <= y <= x, and for the quarter on the diagonal base its mirror image in
    // x = y; or the quarter with the corner block
    gmsh::vectorpair top;
    if (g.base == "corner")
      top = build_quarter_with_corner_block(mesh, g);
    else
    {
      top = build_eighth(mesh, g, false);
      if (!eighth)
      {
        const gmsh::vectorpair mirrored = build_eighth(mesh, g, true);
        top.insert(top.end(), mirrored.begin(), mirrored.end());
      }
    }

    // The base: the top face extruded down in layers growing away from it
    const auto [n_layers, layer_ratio] = graded(t, foot_cell(g), g.growth);
    std::vector<int> one_each(n_layers, 1);
    std::vector<double> heights;
    double h = foot_cell(g), z = 0;
    for (int k = 0; k < n_layers; ++k, h *= layer_ratio)
      heights.push_back((z += h) / t);
    heights.back() = 1.0;
    gmsh::vectorpair extruded;
    gmsh::model::geo::extrude(top, 0, 0, -t, extruded, one_each, heights, true);
    gmsh::model::geo::synchronize();

    // Physical groups: every volume, and the boundary surfaces by the plane they lie on
    gmsh::vectorpair volumes, surfaces;
    gmsh::model::getEntities(volumes, 3);
    std::vector<int> volume_tags;
    for (auto [d, tag] : volumes)
      volume_tags.push_back(tag);
    gmsh::model::addPhysicalGroup(3, volume_tags, 1);
    gmsh::model::setPhysicalName(3, 1, "body");
    const double tol = 1e-8 * g.L;
    std::vector<std::pair<std::string, std::array<double, 4>>> planes
        = {{"bottom", {0, 0, 1, 0}},   {"sym_x", {1, 0, 0, 0}},      {"sym_y", {0, 1, 0, 0}},
           {"side_x", {1, 0, 0, w}},   {"side_y", {0, 1, 0, w}},
           {"lateral", {1 / a, 0, 1 / H, 1 + t / H}}, {"lateral", {0, 1 / a, 1 / H, 1 + t / H}}};
    if (eighth) // (in the quarter the diagonal plane is interior)
      planes.push_back({"diagonal", {1, -1, 0, 0}});
    std::map<std::string, std::vector<int>> groups;
    gmsh::model::getEntities(surfaces, 2);
    for (auto [d, tag] : surfaces)
    {
      gmsh::vectorpair corners;
      gmsh::model::getBoundary({{2, tag}}, corners, false, false, true);
      std::vector<Point> xs;
      for (auto [dc, pt] : corners)
      {
        std::vector<double> x;
        gmsh::model::getValue(0, pt, {}, x);
        xs.push_back({x[0], x[1], x[2]});
      }
      for (const auto& [name, plane] : planes)
        if (on_plane(xs, plane, tol))
        {
          groups[name].push_back(tag);
          break;
        }
    }
    int group = 1;
    for (const auto& [name, tags] : groups)
    {
      gmsh::model::addPhysicalGroup(2, tags, group);
      gmsh::model::setPhysicalName(2, group++, name);
    }
  };
  const std::vector<int> mirror_axes = g.domain == "half" ? std::vector<int>{1} : std::vector<int>{};
  // At least one block of cells^3 hexahedra at each tip level (a bound from below, for
  // mesh_gmsh_model's refusal of a mesh that cannot fit)
  const double fewest_cells = std::pow(double(g.cells), 3) * (g.tip_levels + 1);
  return mesh_gmsh_model(comm, build, {}, mirror_axes, fewest_cells);
}

} // namespace gelx::scenes
