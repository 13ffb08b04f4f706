#include "app/runs/trace.hpp"

namespace gf::app {

std::vector<std::string> traceColumns(const sim::SceneDesc& d) {
  std::vector<std::string> out = {"t"};
  for (const sim::BodyDesc& b : d.bodies) {
    if (b.mass <= 0.0) continue;
    for (const char* c : {".px", ".py", ".pz", ".qx", ".qy", ".qz", ".qw"}) out.push_back(b.name + c);
  }
  for (const sim::FingerDesc& f : d.fingers) {
    for (const char* c : {".fx", ".fy", ".fz", ".n_sgo", ".r", ".px", ".py", ".pz", ".dx", ".dy", ".dz"}) out.push_back(f.name + c);
  }
  for (const sim::BodyDesc& b : d.bodies) {
    if (b.mass <= 0.0) continue;
    for (const char* c : {".vx", ".vy", ".vz", ".wx", ".wy", ".wz"}) out.push_back(b.name + c);
  }
  // The force sent to the device (.fx: the force applied to the proxy) and the port's energy.
  for (const sim::FingerDesc& f : d.fingers) {
    for (const char* c : {".sent_fx", ".sent_fy", ".sent_fz", ".port_energy"}) out.push_back(f.name + c);
  }
  return out;
}

TraceWriter::TraceWriter(const sim::World& world, const std::string& path) : file_(path) {
  const sim::SceneDesc& d = world.desc();
  for (std::size_t b = 0; b < d.bodies.size(); ++b) {
    if (d.bodies[b].mass > 0.0) dynamic_bodies_.push_back(static_cast<int>(b));
  }
  std::string& text = file_.block();
  for (const std::string& column : traceColumns(d)) {
    if (!text.empty()) text += ',';
    text += column;
  }
  text += '\n';
  file_.rowDone();
}

void TraceWriter::record(const sim::World& world) {
  std::string& text = file_.block();
  appendNumber(text, world.time());
  for (int b : dynamic_bodies_) {
    const sim::Pose p = world.bodyPose(b);
    for (double x : {p.position.x(), p.position.y(), p.position.z(), p.orientation.x(),
                     p.orientation.y(), p.orientation.z(), p.orientation.w()}) {
      text += ',';
      appendNumber(text, x);
    }
  }
  for (int f = 0; f < static_cast<int>(world.desc().fingers.size()); ++f) {
    const sim::Vec3 force = world.couplingForce(f), proxy = world.proxyPosition(f), device = world.devicePosition(f);
    for (double x : {force.x(), force.y(), force.z(), double(world.sgoCount(f)), world.contactRadius(f), proxy.x(),
                     proxy.y(), proxy.z(), device.x(), device.y(), device.z()}) {
      text += ',';
      appendNumber(text, x);
    }
  }
  for (int b : dynamic_bodies_) {
    const sim::Vec3 v = world.bodyLinearVelocity(b), w = world.bodyAngularVelocity(b);
    for (double x : {v.x(), v.y(), v.z(), w.x(), w.y(), w.z()}) {
      text += ',';
      appendNumber(text, x);
    }
  }
  for (int f = 0; f < static_cast<int>(world.desc().fingers.size()); ++f) {
    const sim::Vec3 sent = world.feedbackForce(f);
    for (double x : {sent.x(), sent.y(), sent.z(), world.portEnergy(f)}) {
      text += ',';
      appendNumber(text, x);
    }
  }
  text += '\n';
  file_.rowDone();
}

}  // namespace gf::app
