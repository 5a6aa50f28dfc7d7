// The bistrip's helix and perversion detector (demos/bistrip/centreline.cpp, the one every
// bistrip run reports with) on constructed strips of known shape, no scene run:
//
//  1. A perversion: a right-handed circular helix (radius R = 3 mm, pitch P = 20 mm, the
//     bistrip's sizes) up to the arc length Z_p = 100.05 mm, continued by its mirror image in
//     the plane normal to the tangent there: a left-handed helix of the same R and P whose
//     position, tangent and curvature vector are continuous at Z_p, the twist jumping from
//     +tau to -tau. The width vector is the principal normal, so the frame's twist is the
//     torsion tau = c / (R^2 + c^2), c = P / 2 pi. Samples every 0.1 mm of arc length, Z_p
//     midway between two. Checked: one perversion, at Z_p to 1e-9 mm (the construction is
//     mirror-symmetric about Z_p, so the twists of the two samples beside it are opposite and
//     their linear zero is Z_p, up to round-off); two segments, right- then left-handed; their
//     radius and pitch against R and P, and their frame turns against tau s / 2 pi, to 2e-3
//     (the central differences err by (kappa h)^2 / 6 = 4e-5 for kappa h = 0.016, and the two
//     samples beside the perversion straddle it: 1 of 1000 and of 2000 samples per segment,
//     each off by O(tau), measured below 1e-3);
//  2. a straight strip with a small helical waver (frame turning 0.1 turn in all): no helix;
//  3. a long right-handed helix with one short left-handed stretch (0.1 turn of its frame)
//     in the middle: the stretch is noise, merged away, so one right-handed segment and no
//     perversion.

#include "../demos/bistrip/centreline.h"
#include "support.h"

#include <cmath>
#include <numbers>

namespace
{
using gelx::scenes::CentrelineSamples;
using Vec3 = std::array<double, 3>;
constexpr double pi = std::numbers::pi;

/// A circular helix about z of radius R and pitch P (right-handed for P > 0), at arc length s:
/// its point and principal normal (towards the axis)
std::pair<Vec3, Vec3> helix(double R, double P, double s)
{
  const double c = P / (2 * pi), rho = std::sqrt(R * R + c * c), phi = s / rho;
  return {{R * std::cos(phi), R * std::sin(phi), c * phi}, {-std::cos(phi), -std::sin(phi), 0}};
}

/// The reflection in the plane through `o` normal to the unit vector `n`
Vec3 reflect(const Vec3& x, const Vec3& o, const Vec3& n)
{
  const double d = (x[0] - o[0]) * n[0] + (x[1] - o[1]) * n[1] + (x[2] - o[2]) * n[2];
  return {x[0] - 2 * d * n[0], x[1] - 2 * d * n[1], x[2] - 2 * d * n[2]};
}
} // namespace

int main(int argc, char* argv[])
{
  MPI_Init(&argc, &argv);
  gelx::test::Checks checks(MPI_COMM_WORLD);
  const double R = 3, P = 20, L = 300, h = 0.1, Zp = 100.05;
  const double c = P / (2 * pi), tau = c / (R * R + c * c);
  const int n = int(std::round(L / h)) + 1;

  // 1. The perversion: the right-handed helix to Zp, its mirror image beyond
  {
    const Vec3 o = helix(R, P, Zp).first;
    const double rho = std::sqrt(R * R + c * c);
    const Vec3 tangent{-R * std::sin(Zp / rho) / rho, R * std::cos(Zp / rho) / rho, c / rho};
    CentrelineSamples strip;
    for (int k = 0; k < n; ++k)
    {
      const double Z = k * h;
      strip.Z.push_back(Z);
      if (Z < Zp)
      {
        const auto [x, d] = helix(R, P, Z);
        strip.centre.push_back(x);
        strip.width.push_back(d);
      }
      else
      {
        const auto [x, d] = helix(R, P, 2 * Zp - Z);
        strip.centre.push_back(reflect(x, o, tangent));
        strip.width.push_back(reflect(d, {0, 0, 0}, tangent));
      }
    }
    const auto found = gelx::scenes::analyse_centreline(strip);
    checks.require("one perversion (" + std::to_string(found.perversions.size()) + ")",
                   found.perversions.size() == 1);
    if (found.perversions.size() == 1)
      checks.absolute("the perversion's position (mm)", found.perversions[0], Zp, 1e-9);
    checks.require("two helical segments (" + std::to_string(found.segments.size()) + ")",
                   found.segments.size() == 2);
    if (found.segments.size() == 2)
    {
      const double lengths[2] = {Zp, L - Zp};
      for (int i = 0; i < 2; ++i)
      {
        const auto& s = found.segments[i];
        const std::string tag = i == 0 ? "segment before it: " : "segment after it: ";
        checks.require(tag + "chirality " + std::to_string(s.chirality) + " is "
                           + (i == 0 ? "+1 (right-handed)" : "-1 (left-handed)"),
                       s.chirality == (i == 0 ? 1 : -1));
        checks.relative(tag + "radius (mm)", s.radius, R, 2e-3);
        checks.relative(tag + "pitch (mm)", s.pitch, P, 2e-3);
        checks.relative(tag + "frame turns", s.frame_turns, tau * lengths[i] / (2 * pi), 2e-3);
      }
    }
  }

  // 2. Straight, with a waver: the frame turns 0.1 turn over the strip's length in all
  {
    CentrelineSamples strip;
    for (int k = 0; k < n; ++k)
    {
      const double Z = k * h, phi = 2 * pi * 0.1 * Z / L;
      strip.Z.push_back(Z);
      strip.centre.push_back({0.01 * std::cos(phi), 0.01 * std::sin(phi), Z});
      strip.width.push_back({std::cos(phi), std::sin(phi), 0});
    }
    const auto found = gelx::scenes::analyse_centreline(strip);
    checks.require("a straight strip: no helix (" + std::to_string(found.segments.size())
                       + " segments), no perversion",
                   found.segments.empty() && found.perversions.empty());
  }

  // 3. A right-handed helix whose frame turns back by 0.1 turn over 10 mm in the middle: the
  //    width vector counter-rotated about the tangent there, which makes that stretch's twist
  //    negative without moving the centreline
  {
    CentrelineSamples strip;
    const double from = 145, to = 155;
    // The twist in the stretch: -tau - 2 pi 0.1 / (to - from) per arc length, so -0.1 turn
    const double back = tau + 2 * pi * 0.1 / (to - from);
    for (int k = 0; k < n; ++k)
    {
      const double Z = k * h;
      const auto [x, d] = helix(R, P, Z);
      // The rotation angle of the width vector about the tangent, relative to the normal
      const double angle = Z <= from ? 0.0 : -back * (std::min(Z, to) - from);
      const double rho = std::sqrt(R * R + c * c), phi = Z / rho;
      const Vec3 b{c * std::sin(phi) / rho, -c * std::cos(phi) / rho, R / rho}; // binormal
      strip.Z.push_back(Z);
      strip.centre.push_back(x);
      strip.width.push_back({std::cos(angle) * d[0] + std::sin(angle) * b[0],
                             std::cos(angle) * d[1] + std::sin(angle) * b[1],
                             std::cos(angle) * d[2] + std::sin(angle) * b[2]});
    }
    const auto found = gelx::scenes::analyse_centreline(strip);
    checks.require("a helix with a 0.1-turn counter-twist: one right-handed segment ("
                       + std::to_string(found.segments.size()) + "), no perversion ("
                       + std::to_string(found.perversions.size()) + ")",
                   found.segments.size() == 1 && found.perversions.empty()
                       && found.segments[0].chirality == 1);
  }
  const int failed = checks.finish();
  MPI_Finalize();
  return failed;
}
