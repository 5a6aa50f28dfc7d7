#pragma once
/// @file centreline.h
/// Helices and perversions read off a deformed strip: its centreline and material frame give
/// curvature and twist along it; helical segments are the stretches of one sign of twist
/// (one chirality), perversions the places where the sign changes.

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

namespace gelx::scenes
{

/// The deformed strip sampled at reference positions Z along it (increasing): the centroid
/// of each cross-section and its width vector (a material line across the strip, here the
/// interface's width: the frame's first director once made normal to the centreline).
struct CentrelineSamples
{
  std::vector<double> Z;
  std::vector<std::array<double, 3>> centre, width;
};

/// The samples from per-layer sums, 10 numbers per node layer k (at Z = k spacing), summed over
/// all ranks: the sum of the layer's node positions (3) and their number, and the positions
/// of the two edges whose difference is the width vector (3 each, the first subtracted).
CentrelineSamples samples_from_layer_sums(const std::vector<double>& sums, double spacing);

/// The centreline's rates at every sample, by central differences (one-sided at the ends):
/// the deformed arc length s, the frame (t, d1, d2 = t x d1) with t the unit chord of the
/// neighbouring centres and d1 the width vector made normal to t, the curvature |t'| and the
/// twist d1' . d2 per arc length. A template so that an objective of them can be
/// differentiated with a dual number (demos/design/centreline_objective.h); T = double for
/// the detector.
template <class T>
struct CentrelineRates
{
  std::vector<T> s, curvature, twist;
  std::vector<std::array<T, 3>> d1;

  CentrelineRates(const std::vector<std::array<T, 3>>& centre,
                  const std::vector<std::array<T, 3>>& width)
  {
    using std::sqrt;
    using V = std::array<T, 3>;
    const auto minus = [](const V& a, const V& b) { return V{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
    const auto dot = [](const V& a, const V& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
    const auto scaled = [](const V& a, const T& c) { return V{c * a[0], c * a[1], c * a[2]}; };
    const auto unit = [&](const V& a) { return scaled(a, 1 / sqrt(dot(a, a))); };
    const auto cross = [](const V& a, const V& b)
    { return V{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; };
    const int n = centre.size();
    s.assign(n, T(0));
    for (int k = 1; k < n; ++k)
    {
      const V ds = minus(centre[k], centre[k - 1]);
      s[k] = s[k - 1] + sqrt(dot(ds, ds));
    }
    std::vector<V> t(n), d2(n);
    d1.resize(n);
    for (int k = 0; k < n; ++k)
    {
      const int a = std::max(k - 1, 0), b = std::min(k + 1, n - 1);
      t[k] = unit(minus(centre[b], centre[a]));
      d1[k] = unit(minus(width[k], scaled(t[k], dot(width[k], t[k]))));
      d2[k] = cross(t[k], d1[k]);
    }
    curvature.resize(n);
    twist.resize(n);
    for (int k = 0; k < n; ++k)
    {
      const int a = std::max(k - 1, 0), b = std::min(k + 1, n - 1);
      const T ds = s[b] - s[a];
      const V dt = minus(t[b], t[a]);
      curvature[k] = sqrt(dot(dt, dt)) / ds;
      twist[k] = dot(minus(d1[b], d1[a]), d2[k]) / ds;
    }
  }
};

/// A stretch of the strip of one chirality.
struct HelicalSegment
{
  double start, end; ///< reference positions
  int chirality;     ///< +1 right-handed (twist > 0), -1 left-handed
  double curvature, twist; ///< means over the segment (1/mm)
  /// R = kappa / (kappa^2 + tau^2) and P = 2 pi |tau| / (kappa^2 + tau^2) of the helix with
  /// the segment's mean curvature and twist
  double radius, pitch;
  double frame_turns; ///< int |tau| ds / (2 pi): how far the frame twists along it
};

struct CentrelineAnalysis
{
  /// At every sample: curvature |t'| and twist d1' . d2 of the frame (t, d1, d2 = t x d1), per
  /// deformed arc length
  std::vector<double> curvature, twist;
  /// At every sample: the frame's first director d1 (the width vector made normal to the
  /// tangent), whose turning about the strip's axis shows how a perversion winds
  std::vector<std::array<double, 3>> frame;
  std::vector<HelicalSegment> segments;
  /// Reference positions of the perversions: where the twist changes sign between two
  /// segments (linear interpolation of the zero)
  std::vector<double> perversions;
  nlohmann::json to_json() const;
};

/// Curvature and twist by central differences; runs of one sign of twist are segments; a
/// run whose frame turns by less than `min_frame_turns` is noise (the straight strip before
/// it buckles, the clamps' boundary layers): the smallest such run is merged into its
/// neighbours until none is left, so a perversion needs real helices of opposite hands on
/// both its sides.
CentrelineAnalysis analyse_centreline(const CentrelineSamples& samples,
                                      double min_frame_turns = 0.25);

} // namespace gelx::scenes
