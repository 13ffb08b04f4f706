#include "app/runs/forces.hpp"

#include <algorithm>

namespace gf::app {

ForceWriter::ForceWriter(const sim::World& world, const std::vector<std::string>& names, long rows,
                         const std::string& path) {
  const sim::SceneDesc& d = world.desc();
  for (const std::string& n : names) {
    for (std::size_t b = 0; b < d.bodies.size(); ++b) {
      if (d.bodies[b].name != n) continue;
      bodies_.push_back(static_cast<int>(b));
      previous_.push_back(world.bodyLinearVelocity(static_cast<int>(b)));
    }
  }
  if (!path.empty() && !bodies_.empty()) {
    std::vector<std::string> columns = {"t"};
    for (int b : bodies_) {
      for (const char* c : {".fx", ".fy", ".fz"}) columns.push_back(d.bodies[static_cast<std::size_t>(b)].name + c);
    }
    file_ = std::make_unique<RowFile>(path, columns);
    row_.resize(columns.size());
  }
  gravity_ = d.effects.gravity ? d.world.gravity : sim::Vec3::Zero();
  times_.reserve(static_cast<std::size_t>(std::max(0L, rows)));
  fy_.reserve(static_cast<std::size_t>(std::max(0L, rows)));
}

void ForceWriter::record(const sim::World& world, double dt) {
  times_.push_back(world.time());
  if (file_) row_[0] = world.time();
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const sim::Vec3 v = world.bodyLinearVelocity(bodies_[i]);
    const sim::Vec3 f = world.desc().bodies[bodies_[i]].mass * ((v - previous_[i]) / dt - gravity_);
    previous_[i] = v;
    if (i == 0) fy_.push_back(f.y());
    if (file_) std::copy(f.data(), f.data() + 3, &row_[1 + 3 * i]);
  }
  if (file_) file_->push(row_.data());
}

void ForceWriter::close() {
  if (file_) file_->close();
}

render::ChartSeries ForceWriter::series(const std::string& label, const Eigen::Vector3f& colour) const {
  return {label, colour, times_, fy_};
}

}  // namespace gf::app
