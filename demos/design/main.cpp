// gelx scene: design — the prestretch that curls a bilayer strip into a prescribed helix
// (thesis §5.2.1, inverse design)
//
// Sample runs:
//   ./gelx run design                                  # R = 3, P = 6 on a 20 x 1 x 1 strip
//   ./gelx run design --radius 4 --pitch 3 --slabs 5
//   ./gelx run design --design_angle false             # the stretch alone: a ring, no pitch
//   ./gelx run design -design_tao_monitor              # TAO's own iteration lines
//   ./gelx run design --objective centreline           # the helix's rates asked, not its placement
//   ./gelx run design --shape perversion --length 30 --thickness 0.5 --nx 60 --slabs 15 \
//       --radius 1.2                           # 1 + 2 turns between clamps, perversion at 10
//
// A bilayer strip L x W x H of the compressible neo-Hookean solid of thesis Eq. 3.1 (G, K),
// clamped at x = 0 (which only removes its rigid motions), its two layers prestretched
// (forms/design_strip.py): in each of `slabs` slabs along the strip, the stretch s of the
// stress-free state along the in-plane direction at angle a from the strip's axis,
// F0 = Q(a) diag(s, s^-1/2, s^-1/2) Q(a)^T. An upper layer that wants to be shorter than the
// lower one curls the strip; a direction off the axis twists it as it curls: a helix. Both
// layers are designed (--design_lower), so that the strip can curl without shortening its
// centreline, as a helix of its length needs.
//
// The design problem: which s and a per slab make the strip a helix of radius R and pitch P?
// The target is the placement of the whole strip on that helix, its material frame carried by
// the helix's rotation: x*(X) = r(X1) + (X2 - W/2) d1(X1) + (X3 - H/2) d2(X1), the frame
// (t, d1, d2) starting as (e_x, e_y, e_z) and turning at the constant rate Omega = tau t -
// kappa d1 with kappa = R / (R^2 + c^2), tau = c / (R^2 + c^2), c = P / (2 pi) (the helix's
// curvature and torsion); the objective J = 1/2 int |u - (x* - X)|^2 dX, or, with
// --objective centreline, the distance of the centreline's curvature and twist (the helix
// detector's, below) to kappa and tau, which leaves the placement free. The start is the
// narrow-strip theory of a bilayer (Timoshenko's curvature 3 eps / (2 H) for a misfit eps
// between equal layers, split between them, and, for a prestretch at angle a, curvature and
// twist in the ratio 1 : tan a, so that eps = 2 H / (3 R), tan a = P / (2 pi R)). PETSc TAO's
// BLMVM (-design_tao_*) minimises J within bounds on s and a, with the adjoint gradient
// (gelx::AdjointGradient: one forward and one adjoint solve per evaluation, whatever the
// number of slabs); each forward solve starts from the last equilibrium. The run reports J
// (as the rms distance to the target) per iteration, and the helix the strip forms, before
// and after, read off its centreline by the bistrip's helix detector (the middle 80 %):
// radius and pitch against R and P (README.md).
//
// With --shape perversion the target is a right-handed helix of turns_before whole turns, a
// perversion at perversion_at, and a left-handed one of turns_after whole turns, of one radius
// (their pitch follows from the turns' length), the strip held between two clamps: after whole
// turns the far end's frame is the clamp's again, so its placement is a translation. From
// rest, the far clamp follows the rigid motion of the end of a rod whose rates grow with the
// prestretch (a translation alone compresses the straight strip, which buckles). The start
// flips the angle's sign past the perversion; the detector reports where the twist changes
// sign and the turns on each side.

#include "strip.h"

#include "design_strip.h" // the generated forms

#include <cmath>
#include <gelx/common/petsc_utils.h>
#include <gelx/io/program.h>
#include <gelx/io/progress.h>
#include <gelx/solvers/design.h>

namespace
{
using Vector = std::array<double, 3>;

/// A rod of constant curvature and twist from the clamp at x = 0, whose frame (t, d1, d2)
/// starts as (e_x, e_y, e_z): a helix of radius R and pitch P (see the header). Its rates may
/// be scaled (the path from the straight strip to the helix, scale 0 to 1).
struct HelixTarget
{
  double radius, pitch, width, thickness;
  int hand = 1;     ///< +1 right-handed (torsion > 0), -1 left-handed
  double scale = 1; ///< the rates' factor
  /// The helix's curvature kappa = R / (R^2 + c^2) and torsion tau = hand c / (R^2 + c^2),
  /// c = P / 2 pi
  double curvature() const { return scale * radius / (radius * radius + c() * c()); }
  double torsion() const { return scale * hand * c() / (radius * radius + c() * c()); }
  double c() const { return pitch / (2 * M_PI); }
  double rate() const { return std::hypot(curvature(), torsion()); }
  /// The unit axis n = (tau, -kappa, 0) / omega about which the frame turns at the rate omega
  Vector axis() const { return {torsion() / rate(), -curvature() / rate(), 0}; }
  /// The frame's rotation after arc length s, applied to v
  Vector turn(double s, const Vector& v) const
  {
    if (rate() == 0)
      return v;
    const Vector n = axis();
    const double cs = std::cos(rate() * s), sn = std::sin(rate() * s);
    const double along = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
    const Vector cross
        = {n[1] * v[2] - n[2] * v[1], n[2] * v[0] - n[0] * v[2], n[0] * v[1] - n[1] * v[0]};
    Vector r;
    for (int i = 0; i < 3; ++i)
      r[i] = v[i] * cs + cross[i] * sn + n[i] * along * (1 - cs);
    return r;
  }
  /// r(s) - r(0) = int_0^s t: the part of e_x along n advances, the rest turns
  Vector advance(double s) const
  {
    if (rate() == 0)
      return {s, 0, 0};
    const Vector n = axis();
    const double omega = rate(), cs = std::cos(omega * s), sn = std::sin(omega * s);
    const Vector normal_part = {1 - n[0] * n[0], -n[0] * n[1], -n[0] * n[2]};
    const Vector n_cross_ex = {0, n[2], -n[1]};
    Vector r;
    for (int i = 0; i < 3; ++i)
      r[i] = n[i] * n[0] * s + normal_part[i] * sn / omega + n_cross_ex[i] * (1 - cs) / omega;
    return r;
  }
  /// x*(X) - X at X
  Vector displacement(const double* X) const
  {
    return placed(advance(X[0]), turn(X[0], {0, 1, 0}), turn(X[0], {0, 0, 1}), X);
  }
  /// x*(X) - X for the section through X whose centre has moved by r from the clamp's and
  /// whose frame is (d1, d2)
  Vector placed(const Vector& r, const Vector& d1, const Vector& d2, const double* X) const
  {
    const Vector start = {0, width / 2, thickness / 2};
    Vector u;
    for (int i = 0; i < 3; ++i)
      u[i] = start[i] + r[i] + (X[1] - width / 2) * d1[i] + (X[2] - thickness / 2) * d2[i]
             - X[i];
    return u;
  }
};

/// Two helices of opposite hands joined by a perversion at X1 = at: the second continues the
/// first's centreline and frame. With whole turns on both sides (the scene's target) the
/// frame at the perversion and at the far end is the clamp's again: the far end's placement
/// is a translation. With the rates scaled, the far end's placement is the rigid motion
/// that carries a second clamp from the straight strip to that translation.
struct PerversionTarget
{
  HelixTarget before, after;
  double at;
  Vector displacement(const double* X) const
  {
    if (X[0] <= at)
      return before.displacement(X);
    const double s = X[0] - at;
    Vector r = before.advance(at);
    const Vector beyond = before.turn(at, after.advance(s));
    for (int i = 0; i < 3; ++i)
      r[i] += beyond[i];
    return before.placed(r, before.turn(at, after.turn(s, {0, 1, 0})),
                         before.turn(at, after.turn(s, {0, 0, 1})), X);
  }
  /// The same with both helices' rates scaled by t
  PerversionTarget scaled(double t) const
  {
    PerversionTarget path = *this;
    path.before.scale = path.after.scale = t;
    return path;
  }
};
} // namespace

int main(int argc, char* argv[])
{
  // 1. Scene parameters (lengths in mm, stresses in MPa)
  gelx::scenes::DesignStripGeometry g;
  g.length = 20;
  g.cells = {40, 2, 2};
  g.design_angle = true;
  g.design_lower = true;
  int nx = 40, ny = 2, nz = 2;
  double G = 1, K = 10, radius = 3, pitch = 6;
  double stretch_min = 0.5, stretch_max = 1.2, angle_max = 1.2;
  std::string objective = "placement", shape = "helix";
  double perversion_at = 10;
  int turns_before = 1, turns_after = 2;
  gelx::Parameters prm;
  prm.bind("geometry", "length", g.length, "strip length along x (mm)", gelx::Parameters::positive);
  prm.bind("geometry", "width", g.width, "strip width along y (mm)", gelx::Parameters::positive);
  prm.bind("geometry", "thickness", g.thickness, "strip thickness along z, two equal layers (mm)",
           gelx::Parameters::positive);
  prm.bind("mesh", "nx", nx, "Q2 hexahedra along the length", [](int n)
           { return n >= 1 ? "" : "must be at least 1"; });
  prm.bind("mesh", "ny", ny, "Q2 hexahedra across the width",
           [](int n) { return n >= 1 ? "" : "must be at least 1"; });
  prm.bind("mesh", "nz", nz, "Q2 hexahedra through the thickness, even (the layers' interface "
           "is a cell face)", [](int n) { return n >= 2 && n % 2 == 0 ? "" : "must be even"; });
  prm.bind("material", "G", G, "shear modulus (MPa)", gelx::Parameters::positive);
  prm.bind("material", "K", K, "bulk modulus (MPa)", gelx::Parameters::positive);
  prm.bind("target", "radius", radius, "radius R of the helix to form (mm)",
           gelx::Parameters::positive);
  prm.bind("target", "pitch", pitch, "pitch P of the helix to form (mm)",
           gelx::Parameters::positive);
  prm.bind("design", "slabs", g.slabs, "slabs along the strip, each with its prestretch",
           [](int n) { return n >= 1 ? "" : "must be at least 1"; });
  prm.bind("design", "design_angle", g.design_angle,
           "design the prestretch's direction per slab too (else it stays along the strip)");
  prm.bind("design", "design_lower", g.design_lower,
           "design the lower layer's prestretch too (else it is stress free and the strip's "
           "centreline shortens as it curls)");
  prm.bind("design", "stretch_min", stretch_min, "lower bound of the stretch s",
           gelx::Parameters::positive);
  prm.bind("design", "stretch_max", stretch_max, "upper bound of the stretch s",
           gelx::Parameters::positive);
  prm.bind("design", "objective", objective,
           "what J measures: 'placement', the distance to the helix's placement of the whole "
           "strip; 'centreline', the distance of the centreline's curvature and twist (the "
           "helix detector's, over the middle 80 %) to the helix's, its placement left free",
           gelx::Parameters::one_of({"placement", "centreline"}));
  prm.bind("target", "shape", shape,
           "'helix': one helix of radius and pitch, the far end free; 'perversion': a "
           "right-handed helix of turns_before whole turns, a perversion at perversion_at, a "
           "left-handed helix of turns_after whole turns, both of radius `radius`, between two "
           "clamps (the pitch follows from the turns' length; --pitch is not used)",
           gelx::Parameters::one_of({"helix", "perversion"}));
  prm.bind("target", "perversion_at", perversion_at,
           "position of the perversion along the strip, a slab boundary (mm)",
           gelx::Parameters::positive);
  prm.bind("target", "turns_before", turns_before, "whole helical turns before the perversion",
           [](int n) { return n >= 1 ? "" : "must be at least 1"; });
  prm.bind("target", "turns_after", turns_after, "whole helical turns after the perversion",
           [](int n) { return n >= 1 ? "" : "must be at least 1"; });
  prm.bind("design", "angle_max", angle_max, "bound of |a| (radians, below pi/2)",
           [](double a) { return a > 0 && a < M_PI / 2 ? "" : "must lie in (0, pi/2)"; });

  return gelx::run_program(argc, argv, "gelx-design", prm, [&](gelx::Run& run)
  {
    if (stretch_min >= stretch_max)
      throw gelx::InputError("stretch_min must be below stretch_max");
    if (nx < g.slabs)
      throw gelx::InputError("nx must be at least the number of slabs");
    g.cells = {std::size_t(nx), std::size_t(ny), std::size_t(nz)};

    // 2. The strip and its target: the helix's placement, or the perversion's between two
    //    clamps, its helices' pitch set by their turns: a turn of length Lambda on a helix of
    //    radius R has c = P / 2 pi = sqrt((Lambda / 2 pi)^2 - R^2)
    const bool perversion = shape == "perversion";
    if (perversion)
    {
      if (objective != "placement" || !g.design_angle)
        throw gelx::InputError("the perversion needs --objective placement and --design_angle "
                               "true (its helices' hands are the prestretch's angles)");
      const double turn = perversion_at / turns_before;
      if (perversion_at >= g.length
          || std::abs((g.length - perversion_at) / turns_after - turn) > 1e-9 * turn)
        throw gelx::InputError("the perversion's helices need turns of one length: "
                               "perversion_at / turns_before = (length - perversion_at) / "
                               "turns_after");
      if (radius >= turn / (2 * M_PI))
        throw gelx::InputError("radius must be below the turn's length / 2 pi = "
                               + std::to_string(turn / (2 * M_PI)) + " mm");
      const double boundary = perversion_at / g.length * g.slabs;
      if (std::abs(boundary - std::round(boundary)) > 1e-9)
        throw gelx::InputError("perversion_at must be a slab boundary (a multiple of length / "
                               "slabs)");
      pitch = 2 * M_PI * std::sqrt(std::pow(turn / (2 * M_PI), 2) - radius * radius);
    }
    const HelixTarget helix{radius, pitch, g.width, g.thickness};
    const PerversionTarget perverted{helix, {radius, pitch, g.width, g.thickness, -1},
                                     perversion_at};
    auto target_displacement = [&](const double* X)
    { return perversion ? perverted.displacement(X) : helix.displacement(X); };
    if (perversion)
      g.far_end = [perverted](double t, const std::array<double, 3>& X)
      { return perverted.scaled(t).displacement(X.data()); };
    gelx::scenes::DesignStrip strip(run.comm(), g, G, K);
    strip.target()->interpolate(
        [&](auto X)
        {
          xt::xtensor<double, 2> values({std::size_t(3), X.shape(1)});
          for (std::size_t i = 0; i < X.shape(1); ++i)
          {
            const double point[3] = {X(0, i), X(1, i), X(2, i)};
            const std::array<double, 3> u = target_displacement(point);
            for (int c = 0; c < 3; ++c)
              values(c, i) = u[c];
          }
          return values;
        });

    // 3. The start: the narrow-strip theory's uniform prestretch, the misfit split between the
    //    layers (the upper one shorter, the lower one longer, the centreline unstretched)
    const int n = g.slabs, m = g.num_parameters(), per_layer = g.parameters_per_layer();
    const double misfit = 2 * g.thickness / (3 * radius),
                 a0 = std::atan(pitch / (2 * M_PI * radius));
    std::vector<double> p(m), lower(m, stretch_min), upper(m, stretch_max);
    for (int layer = 0; layer < (g.design_lower ? 2 : 1); ++layer)
      for (int k = 0; k < n; ++k)
      {
        const int i = layer * per_layer + k;
        const double share = g.design_lower ? misfit / 2 : misfit;
        p[i] = std::clamp(layer == 0 ? 1 - share : 1 + share, stretch_min, stretch_max);
        // the perversion's second helix is left-handed
        const bool flipped = perversion && (k + 0.5) * g.length / n > perversion_at;
        if (g.design_angle)
          std::tie(p[i + n], lower[i + n], upper[i + n])
              = std::make_tuple(flipped ? -a0 : a0, -angle_max, angle_max);
      }
    // A restart (--restart) continues from the checkpoint of the last iterate written: its
    // design, its equilibrium (the checkpoint's unknowns) and the history so far
    gelx::NewtonSolver newton(run.comm());
    gelx::PathState path = run.start_path(strip.problem());
    const bool restarted = path.scene.contains("parameters");
    const double before_gradient0 = path.scene.value("gradient0", 0.0);
    const double fixed_angle = g.design_angle ? a0 : 0.0;
    if (restarted)
    {
      p = path.scene["parameters"].get<std::vector<double>>();
      strip.set_design(p, fixed_angle);
    }
    else
      strip.solve_from_rest(strip.problem(), newton, p, fixed_angle);
    const double volume = g.length * g.width * g.thickness;
    // The shape formed, read off the centreline by the bistrip's detector: the helix's radius
    // and pitch from the mean curvature and twist away from the ends' boundary layers (the
    // middle 80 % of the strip, or of each of the perversion's helices); for the perversion
    // also where the twist changes sign and the turns on each side, int |(kappa, tau)| ds / 2 pi
    auto shape_of = [&](const dolfinx::fem::Function<double>& u)
    {
      const gelx::scenes::CentrelineSamples samples = strip.centreline(u);
      const auto analysis = gelx::scenes::analyse_centreline(samples);
      double kappa = 0, tau = 0, turns[2] = {0, 0};
      int count = 0;
      const double h = samples.Z[1] - samples.Z[0];
      for (std::size_t i = 0; i < samples.Z.size(); ++i)
      {
        const double Z = samples.Z[i], k = analysis.curvature[i], t = analysis.twist[i];
        const bool measured = perversion ? strip.measured(Z, 0, perversion_at)
                                               || strip.measured(Z, perversion_at, g.length)
                                         : strip.measured(Z);
        if (measured)
        {
          kappa += k;
          tau += perversion ? std::abs(t) : t;
          ++count;
        }
        if (!perversion)
          continue;
        // the turns by the trapezoidal rule on each side (a sample at the perversion ends one
        // and starts the other)
        const double rate = std::hypot(k, t) / (2 * M_PI);
        const bool end = i == 0 || i + 1 == samples.Z.size();
        if (std::abs(Z - perversion_at) < h / 2)
          turns[0] += h / 2 * rate, turns[1] += h / 2 * rate;
        else
          turns[Z > perversion_at] += (end ? h / 2 : h) * rate;
      }
      kappa /= count;
      tau /= count;
      const double k2 = kappa * kappa + tau * tau;
      nlohmann::json measures
          = {{"helix_radius", kappa / k2}, {"helix_pitch", 2 * M_PI * std::abs(tau) / k2}};
      if (perversion)
      {
        const auto& found = analysis.perversions;
        const auto nearest = std::min_element(
            found.begin(), found.end(), [&](double a, double b)
            { return std::abs(a - perversion_at) < std::abs(b - perversion_at); });
        measures.update({{"perversions", found.size()},
                         {"perversion_position",
                          nearest == found.end() ? nlohmann::json() : nlohmann::json(*nearest)},
                         {"helix_turns_before", turns[0]},
                         {"helix_turns_after", turns[1]}});
      }
      return measures;
    };
    auto prefixed = [](const std::string& prefix, const nlohmann::json& measures)
    {
      nlohmann::json renamed;
      for (const auto& [key, value] : measures.items())
        renamed[prefix + key] = value;
      return renamed;
    };
    const nlohmann::json target = shape_of(*strip.target());
    if (!restarted)
      run.summary.update(prefixed("start_", shape_of(*strip.displacement())));

    gelx::ResultsWriter& results = run.results(strip.mesh().mesh);
    gelx::FieldSet fields;
    fields.add("displacement", strip.displacement());
    fields.add("target_displacement", strip.target());
    fields.add("energy_density", strip.forms().expression(expression_design_strip_psi));
    if (!restarted)
      results.write_fields(0, fields.update());

    // 4. Minimise J by BLMVM with the adjoint gradient: of the distance to the placement, or
    //    of the centreline's rates to the helix's curvature and torsion (the rms distance to
    //    the placement reported in either case)
    const bool centreline = objective == "centreline";
    const std::unique_ptr<gelx::AdjointGradient> adjoint = strip.adjoint(
        strip.problem(),
        centreline ? gelx::scenes::DesignObjective::centreline
                   : gelx::scenes::DesignObjective::placement,
        helix.curvature(), helix.torsion());
    const auto distance = strip.forms().form(form_design_strip_distance);
    gelx::DesignOptimizer optimizer(strip.problem(), newton, *adjoint, strip.prestretch(), m,
                                    [&](const double* X, int c)
                                    { return strip.parameter_of(X, c); });
    optimizer.set_bounds(lower, upper);
    // Stop when the gradient has fallen by 1e-5 from the start's: J is then within ~1e-10 of
    // its start's scale of the optimum, the shape far closer than the mesh resolves it
    // (README: the tail). The centreline's J fixes the rates only: below 1e-3, BLMVM moves
    // along designs of the same rates (README: R and P within 2e-5 of the asked at 1e-3, the
    // placement drifting after). A restart's TAO starts anew, so there the bound is absolute.
    const double gradient_drop = centreline ? 1e-3 : 1e-5;
    char tolerance[32];
    if (restarted)
    {
      std::snprintf(tolerance, sizeof tolerance, "%.17g", gradient_drop * before_gradient0);
      gelx::set_default_options("design_", {{"tao_gatol", tolerance}, {"tao_gttol", "0"}});
    }
    else
    {
      std::snprintf(tolerance, sizeof tolerance, "%.17g", gradient_drop);
      gelx::set_default_option("design_", "tao_gttol", tolerance);
    }
    // The history: totals over the runs before a restart, and this run's own counts
    const nlohmann::json before = path.scene;
    const int first_iteration = path.step;
    int newton_before = 0;
    const gelx::StepObserver checkpoint = run.checkpoints();
    gelx::ProgressLine progress(
        run.comm(), {.load_name = "rms distance",
                     .quantity = [&] {
                       return gelx::quantity_text("|g|/|g0|",
                                                  run.summary.value("gradient_norm_ratio", 1.0));
                     }});
    const int reason = optimizer.minimise(
        p,
        [&](const gelx::DesignIterate& it)
        {
          if (restarted && it.iteration == 0)
            return; // the checkpoint's iterate, written by the run before
          const int iteration = first_iteration + it.iteration;
          if (iteration == 0)
            path.scene["gradient0"] = it.gradient_norm;
          auto total = [&](const char* key, auto now)
          { return before.value(key, now * 0) + now; };
          const nlohmann::json totals
              = {{"forward_solves", total("forward_solves", it.forward_solves)},
                 {"newton_iterations", total("newton_iterations", it.newton_iterations)},
                 {"adjoint_solves", total("adjoint_solves", it.adjoint_solves)},
                 {"forward_time", total("forward_time", it.forward_time)},
                 {"adjoint_time", total("adjoint_time", it.adjoint_time)}};
          // the history's wall time, in steps.csv and the checkpoint (the summary has the
          // run's own, written at its end)
          const double wall_time = total("wall_time", it.wall_time);
          const double rms = std::sqrt(2 * gelx::assemble_global_scalar(*distance) / volume);
          const double gradient_ratio = it.gradient_norm / path.scene["gradient0"].get<double>();
          nlohmann::json row = {{"step", iteration}, {"rms_distance", rms}};
          row.update(shape_of(*strip.displacement()));
          row["gradient_norm_ratio"] = gradient_ratio;
          if (centreline) // the rms of the rates' errors over the middle 80 %
            row["rms_rate_error"] = std::sqrt(2 * it.objective / strip.measured_length());
          row.update(totals);
          row["wall_time"] = wall_time;
          results.append_step(row);
          std::vector<nlohmann::json> design_rows;
          for (int layer = 0; layer < (g.design_lower ? 2 : 1); ++layer)
            for (int k = 0; k < n; ++k)
            {
              const int i = layer * per_layer + k;
              design_rows.push_back({{"step", iteration},
                                     {"layer", layer == 0 ? "upper" : "lower"},
                                     {"slab", k},
                                     {"stretch", it.parameters[i]},
                                     {"angle", g.design_angle ? it.parameters[i + n] : 0.0}});
            }
          results.append_rows("design.csv", design_rows);
          run.summary.update(totals);
          run.summary.update({{"iterations", iteration},
                              {"rms_distance", rms},
                              {"gradient_norm_ratio", gradient_ratio}});
          if (iteration == 0)
            run.summary["rms_distance_start"] = rms;

          // The checkpoint: this iterate's design and history (and, by Run, its equilibrium
          // and how far steps.csv and design.csv have got)
          path.step = iteration;
          path.scene.update(totals);
          path.scene["wall_time"] = wall_time;
          path.scene["parameters"] = it.parameters;
          gelx::StepRecord record;
          record.step = iteration;
          record.newton.iterations = it.newton_iterations - newton_before;
          newton_before = it.newton_iterations;
          checkpoint(record, path);
          progress.print(record, rms, NAN);
        });
    results.write_fields(1, fields.update());

    // 5. The shape formed, against the target
    const nlohmann::json end = shape_of(*strip.displacement());
    run.summary.update(end);
    run.summary.update(prefixed("target_", target));
    run.summary.update({{"num_dofs", strip.problem().u()->function_space()->dofmap()->index_map
                                         ->size_global() * 3},
                        {"num_parameters", m},
                        {"optimizer_reason", reason},
                        {"target_radius", radius},
                        {"target_pitch", pitch},
                        {"radius_error", std::abs(end["helix_radius"].get<double>() - radius)
                                             / radius},
                        {"pitch_error", std::abs(end["helix_pitch"].get<double>() - pitch)
                                            / pitch}});
  });
}
