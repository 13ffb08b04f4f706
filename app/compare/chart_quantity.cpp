#include "app/compare/chart_quantity.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "app/runs/run_reader.hpp"
#include "app/runs/trace.hpp"
#include "app/scene/input_error.hpp"
#include "sim/scene/settings.hpp"

namespace gf::app {
namespace {

constexpr std::size_t kMaxChartPoints = 4000;  // per model: the chart is at most 1920 pixels wide
constexpr float kModelMarkerSpacingPx = 90.0f;  // markers along a model's curve, this far apart in x

}  // namespace

Eigen::Vector3f modelColour(const std::string& model, std::size_t index) {
  // Okabe–Ito's colours (render::kOkabeIto), each model's its own in every chart.
  const auto okabeIto = [](std::size_t i) { return render::linearFromSrgb(render::kOkabeIto[i]); };
  if (model == "god_object") return okabeIto(1);                                  // vermillion
  if (model == "soft_finger") return okabeIto(2);                                 // bluish green
  if (model == "god_finger" || model == "god_finger_3dof") return okabeIto(0);   // blue
  if (model == "god_finger_6dof") return okabeIto(4);                             // orange
  if (model == "fem_pad") return okabeIto(3);                                     // reddish purple
  return okabeIto(index % 2 ? 5 : 6);                                             // sky blue, black
}

void styleModelSeries(render::ChartSeries& s, const std::string& model, std::size_t index, std::size_t count) {
  using render::LineDash;
  using render::MarkerShape;
  s.style = render::SeriesStyle::kLine;
  if (model == "god_finger" || model == "god_finger_3dof") {
    s.dash = LineDash::kSolid;
    s.marker = MarkerShape::kCircle;
  } else if (model == "god_finger_6dof") {
    s.dash = LineDash::kDotted;
    s.marker = MarkerShape::kDiamond;
  } else if (model == "soft_finger") {
    s.dash = LineDash::kDashed;
    s.marker = MarkerShape::kSquare;
  } else if (model == "god_object") {
    s.dash = LineDash::kDashDot;
    s.marker = MarkerShape::kTriangle;
  } else {
    s.dash = LineDash::kDotted;
    s.marker = MarkerShape::kDiamond;
  }
  s.marker_spacing_px = kModelMarkerSpacingPx;
  s.marker_phase = count > 0 ? static_cast<float>(index) / static_cast<float>(count) : 0.0f;
}

std::string modelTitle(const std::string& model) {
  for (std::size_t i = 0; i < std::size(sim::kContactModelNames); ++i) {
    if (model == sim::kContactModelNames[i]) return std::string(sim::kContactModelLabels[i]);
  }
  if (model == "god_finger_3dof") return "god-finger 3-DOF";
  if (model == "god_finger_6dof") return "god-finger 6-DOF";
  return model;
}

// The first finger's settings: the bundled scenes give every finger the same.
std::string modelDetail(const SessionDesc& session) {
  if (session.scene.fingers.empty()) return "";
  const sim::PatchSettings& p = session.scene.fingers.front().patch;
  char b[200];
  // An oriented pad follows the device's orientation (docs/pad-model.md): say so, and its tip.
  char pad[48] = "";
  if (p.pad_model == sim::PadModel::kOriented) std::snprintf(pad, sizeof pad, ", oriented pad (tip %.2g)", p.tip_ratio);
  switch (sim::effectiveModel(p)) {
    case sim::ContactModel::kGodObject: std::snprintf(b, sizeof b, "one point, mu %.3g", p.friction); break;
    case sim::ContactModel::kSoftFinger:
      std::snprintf(b, sizeof b, "one point, torsion %.3g mm x normal force, mu %.3g%s", 1000.0 * p.torsional_friction,
                    p.friction, pad);
      break;
    case sim::ContactModel::kGodFinger:
      std::snprintf(b, sizeof b, "%d SGOs%s, r_max %.3g mm, alpha %.3g, tau_a %.3g deg, mu %.3g%s", p.n_sgo,
                    p.fill == sim::PatchFill::kFilled ? " (filled)" : "", 1000.0 * p.r_max, p.alpha,
                    p.tau_a * 180.0 / std::numbers::pi, p.friction, pad);
      break;
    case sim::ContactModel::kFemPad: {
      const sim::PadSettings& s = session.scene.fingers.front().pad;
      std::snprintf(b, sizeof b, "FEM pad %.3g mm thick, %.3g mm elements, E %.3g kPa, nu %.2g, mu %.3g",
                    1000.0 * s.thickness, 1000.0 * s.element_size, s.young / 1000.0, s.poisson, p.friction);
      break;
    }
  }
  return b;
}

Quantity chartQuantity(const SessionDesc& session, const std::string& chart, const std::string& body) {
  Quantity q;
  const std::vector<sim::BodyDesc>& bodies = session.scene.bodies;
  const bool of_body = chart.empty() || chart == "rotation" || chart == "tilt" || chart == "height" || chart == "speed";
  if (!of_body) {
    // A trace.csv column: checked against the columns the runs will write.
    const std::vector<std::string> columns = traceColumns(session.scene);
    if (std::find(columns.begin(), columns.end(), chart) == columns.end()) {
      std::string known;
      for (const std::string& c : columns) known.append(known.empty() ? "" : ", ").append(c);
      throw commandLineError("--chart",
                       "'" + chart + "' is neither rotation, tilt, height, speed nor a trace.csv column of this scene (" +
                           known + ")");
    }
    if (!body.empty()) throw commandLineError("--body", "a trace column names its body itself: drop --body");
    q.kind = Quantity::kColumn;
    q.column = chart;
    q.label = chart;
    return q;
  }
  std::string dynamic;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].mass <= 0.0) continue;
    dynamic.append(dynamic.empty() ? "" : ", ").append(bodies[b].name);
    if (body.empty() ? q.body < 0 : bodies[b].name == body) q.body = static_cast<int>(b);
  }
  if (q.body < 0 && body.empty()) {
    throw commandLineError("--chart",
                     (chart.empty() ? std::string("the default chart (tilt or rotation)") : chart) +
                         " is of a dynamic body and the scene has none: chart a trace.csv column (e.g. a finger's .fy)");
  }
  if (q.body < 0) {
    throw commandLineError("--body", "no dynamic body '" + body + "' (the scene's: " + dynamic + ")");
  }
  q.body_name = bodies[static_cast<std::size_t>(q.body)].name;
  const bool sphere = bodies[static_cast<std::size_t>(q.body)].shape == sim::ShapeKind::kSphere;
  q.kind = chart == "rotation" || (chart.empty() && sphere) ? Quantity::kRotation
           : chart == "tilt" || chart.empty() ? Quantity::kTilt
           : chart == "height" ? Quantity::kHeight
                               : Quantity::kSpeed;
  q.label = q.kind == Quantity::kRotation ? q.body_name + ": angle turned since the start, deg"
            : q.kind == Quantity::kTilt   ? q.body_name + ": tilt from upright, deg"
            : q.kind == Quantity::kHeight ? q.body_name + ": height, mm"
                                          : q.body_name + ": speed, m/s";
  return q;
}

std::string quantityName(const Quantity& q) {
  switch (q.kind) {
    case Quantity::kRotation: return "rotation";
    case Quantity::kTilt: return "tilt";
    case Quantity::kHeight: return "height";
    case Quantity::kSpeed: return "speed";
    case Quantity::kColumn: break;
  }
  return q.column;
}

double QuantityTrack::next(double t, const sim::Pose& pose, const sim::Vec3& velocity,
                           const sim::Vec3& angular_velocity) {
  turned_ += angular_velocity.norm() * (t - last_t_) * 180.0 / std::numbers::pi;
  last_t_ = t;
  switch (q_.kind) {
    case Quantity::kRotation: return turned_;
    case Quantity::kTilt: {
      const sim::Vec3 axis = pose.orientation * sim::Vec3::UnitY();
      return std::atan2(axis.cross(sim::Vec3::UnitY()).norm(), axis.y()) * 180.0 / std::numbers::pi;
    }
    case Quantity::kHeight: return 1000.0 * pose.position.y();
    case Quantity::kSpeed: return velocity.norm();
    case Quantity::kColumn: break;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double QuantityTrack::atStart() const {
  if (q_.kind == Quantity::kTilt) {  // the starting orientation's
    const sim::Vec3 axis = start_ * sim::Vec3::UnitY();
    return std::atan2(axis.cross(sim::Vec3::UnitY()).norm(), axis.y()) * 180.0 / std::numbers::pi;
  }
  return q_.kind == Quantity::kRotation || q_.kind == Quantity::kSpeed ? 0.0 : std::numeric_limits<double>::quiet_NaN();
}

void thin(std::vector<double>& x, std::vector<double>& y) {
  const std::size_t n = std::min(x.size(), y.size());
  const std::size_t k = (2 * n + kMaxChartPoints - 1) / kMaxChartPoints;
  if (k <= 2) return;
  std::size_t out = 0;
  for (std::size_t a = 0; a < n; a += k) {
    const std::size_t e = std::min(n, a + k);
    std::size_t lo = a, hi = a;
    for (std::size_t i = a; i < e; ++i) {
      if (y[i] < y[lo]) lo = i;
      if (y[i] > y[hi]) hi = i;
    }
    const std::size_t first = std::min(lo, hi), second = std::max(lo, hi);
    x[out] = x[first], y[out] = y[first], ++out;
    if (second != first) x[out] = x[second], y[out] = y[second], ++out;
  }
  if (x[out - 1] != x[n - 1]) x[out] = x[n - 1], y[out] = y[n - 1], ++out;
  x.resize(out);
  y.resize(out);
}

render::ChartSeries traceSeries(const Quantity& q, const sim::SceneDesc& scene, const std::filesystem::path& trace) {
  render::ChartSeries s;
  if (q.kind == Quantity::kColumn) {
    std::vector<std::vector<double>> c = readCsvColumns(trace.string(), {"t", q.column});
    s.x = std::move(c[0]);
    s.y = std::move(c[1]);
    return s;
  }
  std::vector<std::string> names = {"t"};
  for (const char* k : {".px", ".py", ".pz", ".qx", ".qy", ".qz", ".qw", ".vx", ".vy", ".vz", ".wx", ".wy", ".wz"}) {
    names.push_back(q.body_name + k);
  }
  const std::vector<std::vector<double>> c = readCsvColumns(trace.string(), names);
  QuantityTrack track(q, scene.bodies[static_cast<std::size_t>(q.body)].orientation);
  if (std::isfinite(track.atStart())) {
    s.x.push_back(0.0);
    s.y.push_back(track.atStart());
  }
  for (std::size_t i = 0; i < c[0].size(); ++i) {
    const sim::Pose pose{sim::Vec3(c[1][i], c[2][i], c[3][i]), sim::Quat(c[7][i], c[4][i], c[5][i], c[6][i])};
    s.x.push_back(c[0][i]);
    s.y.push_back(track.next(c[0][i], pose, sim::Vec3(c[8][i], c[9][i], c[10][i]), sim::Vec3(c[11][i], c[12][i], c[13][i])));
  }
  return s;
}

render::ChartSpec chartFor(const Quantity& q) {
  render::ChartSpec chart;
  chart.x_label = "time, s";
  chart.y_label = q.label;
  return chart;
}

nlohmann::json seriesMeasures(const render::ChartSeries& s) {
  double largest = 0.0, sum = 0.0, last = std::numeric_limits<double>::quiet_NaN();
  long n = 0;
  for (double v : s.y) {
    if (!std::isfinite(v)) continue;
    largest = std::max(largest, std::abs(v));
    sum += std::abs(v);
    last = v;
    ++n;
  }
  return {{"final", std::isfinite(last) ? nlohmann::json(last) : nlohmann::json(nullptr)},
          {"max_abs", largest},
          {"mean_abs", n > 0 ? sum / static_cast<double>(n) : 0.0}};
}

}  // namespace gf::app
