#include "centreline.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace gelx::scenes
{

CentrelineSamples samples_from_layer_sums(const std::vector<double>& sums, double spacing)
{
  CentrelineSamples samples;
  for (std::size_t k = 0; k < sums.size() / 10; ++k)
  {
    const double* s = &sums[10 * k];
    samples.Z.push_back(k * spacing);
    samples.centre.push_back({s[0] / s[3], s[1] / s[3], s[2] / s[3]});
    samples.width.push_back({s[7] - s[4], s[8] - s[5], s[9] - s[6]});
  }
  return samples;
}

namespace
{

/// A run of samples [first, last] of one sign of twist
struct Run
{
  int first, last, sign;
};
} // namespace

nlohmann::json CentrelineAnalysis::to_json() const
{
  nlohmann::json segs = nlohmann::json::array();
  for (const HelicalSegment& s : segments)
    segs.push_back({{"start", s.start},
                    {"end", s.end},
                    {"chirality", s.chirality > 0 ? "right" : "left"},
                    {"curvature", s.curvature},
                    {"twist", s.twist},
                    {"radius", s.radius},
                    {"pitch", s.pitch},
                    {"frame_turns", s.frame_turns}});
  return {{"perversions", perversions}, {"segments", segs}};
}

CentrelineAnalysis analyse_centreline(const CentrelineSamples& samples, double min_frame_turns)
{
  const int n = samples.Z.size();
  if (n < 3)
    throw std::invalid_argument("analyse_centreline: fewer than 3 samples");
  const CentrelineRates<double> rates(samples.centre, samples.width);
  const std::vector<double>& s = rates.s;
  CentrelineAnalysis result;
  result.frame = rates.d1;
  result.curvature = rates.curvature;
  result.twist = rates.twist;

  // Runs of one sign, then the noise merged away: the run of least frame rotation first
  const auto frame_turns = [&](const Run& r)
  {
    double turns = 0;
    for (int k = r.first; k < r.last; ++k)
      turns += 0.5 * (std::abs(result.twist[k]) + std::abs(result.twist[k + 1]))
               * (s[k + 1] - s[k]);
    return turns / (2 * std::numbers::pi);
  };
  std::vector<Run> runs;
  for (int k = 0; k < n; ++k)
  {
    const int sign = result.twist[k] >= 0 ? 1 : -1;
    if (runs.empty() || runs.back().sign != sign)
      runs.push_back({k, k, sign});
    else
      runs.back().last = k;
  }
  while (runs.size() > 1)
  {
    auto weakest = std::min_element(runs.begin(), runs.end(), [&](const Run& a, const Run& b)
                                    { return frame_turns(a) < frame_turns(b); });
    if (frame_turns(*weakest) >= min_frame_turns)
      break;
    // Absorbed by its neighbours: both when they have the same sign, else the stronger one
    const bool has_left = weakest != runs.begin(), has_right = weakest + 1 != runs.end();
    if (has_left && has_right && (weakest - 1)->sign == (weakest + 1)->sign)
    {
      (weakest - 1)->last = (weakest + 1)->last;
      runs.erase(weakest, weakest + 2);
    }
    else if (has_left
             && (!has_right || frame_turns(*(weakest - 1)) >= frame_turns(*(weakest + 1))))
    {
      (weakest - 1)->last = weakest->last;
      runs.erase(weakest);
    }
    else
    {
      (weakest + 1)->first = weakest->first;
      runs.erase(weakest);
    }
  }

  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    const Run& r = runs[i];
    if (frame_turns(r) < min_frame_turns)
      continue; // a strip without any helix: one run, all noise
    double length = s[r.last] - s[r.first], kappa = 0, tau = 0;
    for (int k = r.first; k < r.last; ++k)
    {
      const double ds = s[k + 1] - s[k];
      kappa += 0.5 * (result.curvature[k] + result.curvature[k + 1]) * ds;
      tau += 0.5 * (result.twist[k] + result.twist[k + 1]) * ds;
    }
    kappa /= length;
    tau /= length;
    const double k2 = kappa * kappa + tau * tau;
    result.segments.push_back({samples.Z[r.first], samples.Z[r.last], r.sign, kappa, tau,
                               kappa / k2, 2 * std::numbers::pi * std::abs(tau) / k2,
                               frame_turns(r)});
    // A perversion between this segment and the next: the twist changes sign between the
    // last sample of one and the first of the other (an edge of the original runs), at the
    // zero of its linear interpolation
    if (i + 1 < runs.size())
    {
      const int k = r.last;
      const double f = result.twist[k] / (result.twist[k] - result.twist[k + 1]);
      result.perversions.push_back(samples.Z[k] + f * (samples.Z[k + 1] - samples.Z[k]));
    }
  }
  return result;
}

} // namespace gelx::scenes
