// What `godfinger compare` charts: a quantity of a body (the angle it turned, its tilt from
// upright, height or speed) or any trace.csv column, taken along a run from its trace or its states, thinned for
// drawing; and how each contact model is named and coloured in the comparison.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "app/scene/session_desc.hpp"
#include "render/chart/chart.hpp"
#include "sim/mesh/mesh.hpp"

namespace gf::app {

/// The chart's quantity.
struct Quantity {
  enum Kind { kRotation, kTilt, kHeight, kSpeed, kColumn } kind = kRotation;
  int body = -1;
  std::string body_name, column;
  std::string label;  ///< the y axis's label
};

/// The quantity `chart` names ("rotation", "tilt", "height", "speed" of `body`, by default the
/// scene's first dynamic body; or a trace.csv column of the scene). Empty: the body's tilt, or
/// for a sphere (whose tilt says nothing) the angle it turned, how far it rolled. Throws
/// InputError naming --chart or --body.
Quantity chartQuantity(const SessionDesc& session, const std::string& chart, const std::string& body);

/// The --chart name of `q` ("tilt", or its trace.csv column).
std::string quantityName(const Quantity& q);

/// The quantity along one run, fed each state in time order after the start: the angle turned
/// (the integral of |angular velocity| over time, so a rolling ball's keeps growing), the tilt
/// (the angle of the body's y axis, a cylinder's or capsule's axis, from the world's up, 0 to 180
/// degrees: a body that spins over and comes upright again reads 0), the centre's height or
/// speed.
class QuantityTrack {
 public:
  /// `start`: the body's orientation at t = 0.
  QuantityTrack(const Quantity& q, const sim::Quat& start) : q_(q), start_(start) {}
  /// The quantity at time `t` (s) for the body's state then.
  double next(double t, const sim::Pose& pose, const sim::Vec3& velocity, const sim::Vec3& angular_velocity);
  /// The value at t = 0 when the description gives it: nothing turned, at rest; NaN otherwise.
  double atStart() const;

 private:
  const Quantity& q_;
  sim::Quat start_;
  double last_t_ = 0.0, turned_ = 0.0;
};

/// Thins a series to at most 4000 points: each bucket of samples keeps its lowest and highest (in
/// time order), so peaks survive; the last sample is always kept.
void thin(std::vector<double>& x, std::vector<double>& y);

/// The quantity of one run from its trace.csv (every row, t = 0 first where it is known). Throws
/// InputError naming the file.
render::ChartSeries traceSeries(const Quantity& q, const sim::SceneDesc& scene, const std::filesystem::path& trace);

/// An empty chart of `q` against time.
render::ChartSpec chartFor(const Quantity& q);

/// Headline numbers of a series: the last value, the largest and the mean magnitude.
nlohmann::json seriesMeasures(const render::ChartSeries& s);

/// Each model's colour in the chart and its panel's swatch (linear RGB); others by position.
Eigen::Vector3f modelColour(const std::string& model, std::size_t index);
/// Each model's line: the god-finger (and its 3-DOF pad) solid, the 6-DOF god-finger dotted,
/// the soft finger dashed, the god-object dash-dotted,
/// each with its own marker shape every 90 px, the markers of model `index` of `count` shifted
/// by index / count of that, so curves that coincide stay visible (in the legend too).
void styleModelSeries(render::ChartSeries& s, const std::string& model, std::size_t index, std::size_t count);
/// "god-object", "soft finger", "god-finger", "god-finger 3-DOF", "god-finger 6-DOF".
std::string modelTitle(const std::string& model);
/// The settings that make the model what it is, for its panel (the first finger's).
std::string modelDetail(const SessionDesc& session);

}  // namespace gf::app
