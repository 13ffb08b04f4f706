// forces.csv: the force on each listed body other than gravity, from its change of velocity
// over each step, streamed while the run goes; the first body's y force kept for the Fig. 8 chart.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/runs/files.hpp"
#include "render/chart/chart.hpp"
#include "sim/world/world.hpp"

namespace gf::app {

/// The force on each body of `names` other than gravity (N): m (dv/dt - g) over each step. This
/// is the paper's Fig. 8 curve for the pinched cylinder. Haptic thread only; allocates only in
/// its constructor (it reserves `rows` samples).
class ForceWriter {
 public:
  /// Streams forces.csv to `path` when it is not empty and a body is listed. Throws
  /// std::runtime_error naming the file when it cannot be created.
  ForceWriter(const sim::World& world, const std::vector<std::string>& names, long rows, const std::string& path);
  /// True when no listed body is in the scene.
  bool empty() const { return bodies_.empty(); }
  /// Appends the row of the step of `dt` seconds that just ended.
  void record(const sim::World& world, double dt);
  /// Writes the last rows and puts forces.csv in place.
  void close();
  /// The y force on the first body against time, as a chart curve.
  render::ChartSeries series(const std::string& label, const Eigen::Vector3f& colour) const;

 private:
  std::unique_ptr<RowFile> file_;
  std::vector<double> row_;  // the row being filled
  std::vector<int> bodies_;
  std::vector<sim::Vec3> previous_;
  std::vector<double> times_, fy_;
  sim::Vec3 gravity_ = sim::Vec3::Zero();
};

}  // namespace gf::app
