#include "app/trace_writer.hpp"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace gf::app {

void appendNumber(std::string& out, double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!f) throw std::runtime_error(tmp + ": cannot write");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error(path + ": cannot replace: " + ec.message());
}

TraceWriter::TraceWriter(const sim::World& world, long expected_rows) {
  const sim::SceneDesc& d = world.desc();
  text_.push_back('t');  // (assigning a literal trips GCC 12 -Wrestrict, PR 105329)
  for (std::size_t b = 0; b < d.bodies.size(); ++b) {
    if (d.bodies[b].mass <= 0.0) continue;
    dynamic_bodies_.push_back(static_cast<int>(b));
    for (const char* c : {".px", ".py", ".pz", ".qx", ".qy", ".qz", ".qw"}) {
      text_.append(1, ',').append(d.bodies[b].name).append(c);
    }
  }
  for (const sim::FingerDesc& f : d.fingers) {
    for (const char* c : {".fx", ".fy", ".fz", ".n_sgo", ".r", ".px", ".py", ".pz", ".dx", ".dy", ".dz"}) text_.append(1, ',').append(f.name).append(c);
  }
  for (int b : dynamic_bodies_) {
    for (const char* c : {".vx", ".vy", ".vz", ".wx", ".wy", ".wz"}) {
      text_.append(1, ',').append(d.bodies[static_cast<std::size_t>(b)].name).append(c);
    }
  }
  text_ += '\n';
  const std::size_t per_row = 24 * (1 + 13 * dynamic_bodies_.size() + 11 * d.fingers.size());
  text_.reserve(text_.size() + per_row * static_cast<std::size_t>(std::max(0L, expected_rows)));
}

void TraceWriter::record(const sim::World& world) {
  appendNumber(text_, world.time());
  for (int b : dynamic_bodies_) {
    const sim::Pose p = world.bodyPose(b);
    for (double x : {p.position.x(), p.position.y(), p.position.z(), p.orientation.x(),
                     p.orientation.y(), p.orientation.z(), p.orientation.w()}) {
      text_ += ',';
      appendNumber(text_, x);
    }
  }
  for (int f = 0; f < static_cast<int>(world.desc().fingers.size()); ++f) {
    const sim::Vec3 force = world.couplingForce(f), proxy = world.proxyPosition(f), device = world.devicePosition(f);
    for (double x : {force.x(), force.y(), force.z(), double(world.sgoCount(f)), world.contactRadius(f), proxy.x(),
                     proxy.y(), proxy.z(), device.x(), device.y(), device.z()}) {
      text_ += ',';
      appendNumber(text_, x);
    }
  }
  for (int b : dynamic_bodies_) {
    const sim::Vec3 v = world.bodyLinearVelocity(b), w = world.bodyAngularVelocity(b);
    for (double x : {v.x(), v.y(), v.z(), w.x(), w.y(), w.z()}) {
      text_ += ',';
      appendNumber(text_, x);
    }
  }
  text_ += '\n';
}

void TraceWriter::save(const std::string& path) const { writeFileAtomically(path, text_); }

}  // namespace gf::app
