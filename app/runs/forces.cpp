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
    file_ = std::make_unique<StreamedFile>(path);
    std::string& text = file_->block();
    text.push_back('t');
    for (int b : bodies_) {
      for (const char* c : {".fx", ".fy", ".fz"}) text.append(1, ',').append(d.bodies[static_cast<std::size_t>(b)].name).append(c);
    }
    text += '\n';
    file_->rowDone();
  }
  gravity_ = d.effects.gravity ? d.world.gravity : sim::Vec3::Zero();
  times_.reserve(static_cast<std::size_t>(std::max(0L, rows)));
  fy_.reserve(static_cast<std::size_t>(std::max(0L, rows)));
}

void ForceWriter::record(const sim::World& world, double dt) {
  times_.push_back(world.time());
  std::string* text = file_ ? &file_->block() : nullptr;
  if (text) appendNumber(*text, world.time());
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const sim::Vec3 v = world.bodyLinearVelocity(bodies_[i]);
    const sim::Vec3 f = world.desc().bodies[bodies_[i]].mass * ((v - previous_[i]) / dt - gravity_);
    previous_[i] = v;
    if (i == 0) fy_.push_back(f.y());
    if (!text) continue;
    for (double x : {f.x(), f.y(), f.z()}) {
      *text += ',';
      appendNumber(*text, x);
    }
  }
  if (!text) return;
  *text += '\n';
  file_->rowDone();
}

void ForceWriter::close() {
  if (file_) file_->close();
}

render::ChartSeries ForceWriter::series(const std::string& label, const Eigen::Vector3f& colour) const {
  return {label, colour, times_, fy_};
}

}  // namespace gf::app
