#include "app/runs/trace.hpp"

#include "sim/assert.hpp"

namespace gf::app {

bool deviceGivesOrientation(const sim::FingerDesc& f) {
  for (const sim::DeviceTrack::Keyframe& k : f.device.keyframes) {
    if (k.orientation.coeffs() != sim::Quat::Identity().coeffs()) return true;
  }
  return false;
}

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
  // Each two fingers' patch overlap (mm^2, docs/overlap.md), in World::overlap's pair order.
  for (std::size_t a = 0; a < d.fingers.size(); ++a) {
    for (std::size_t b = a + 1; b < d.fingers.size(); ++b) out.push_back(d.fingers[a].name + "+" + d.fingers[b].name + ".overlap_mm2");
  }
  // A 6-DOF device's orientation, last, so a 3-DOF scene's columns are as they always were.
  for (const sim::FingerDesc& f : d.fingers) {
    if (!deviceGivesOrientation(f)) continue;
    for (const char* c : {".dqw", ".dqx", ".dqy", ".dqz"}) out.push_back(f.name + c);
  }
  return out;
}

TraceWriter::TraceWriter(const sim::World& world, const std::string& path)
    : file_(path, traceColumns(world.desc())), row_(file_.columns()) {
  const sim::SceneDesc& d = world.desc();
  for (std::size_t b = 0; b < d.bodies.size(); ++b) {
    if (d.bodies[b].mass > 0.0) dynamic_bodies_.push_back(static_cast<int>(b));
  }
  for (std::size_t f = 0; f < d.fingers.size(); ++f) {
    if (deviceGivesOrientation(d.fingers[f])) oriented_fingers_.push_back(static_cast<int>(f));
  }
}

void TraceWriter::record(const sim::World& world) {
  double* x = row_.data();
  *x++ = world.time();
  for (int b : dynamic_bodies_) {
    const sim::Pose p = world.bodyPose(b);
    for (double v : {p.position.x(), p.position.y(), p.position.z(), p.orientation.x(), p.orientation.y(),
                     p.orientation.z(), p.orientation.w()}) {
      *x++ = v;
    }
  }
  for (int f = 0; f < static_cast<int>(world.desc().fingers.size()); ++f) {
    const sim::Vec3 force = world.couplingForce(f), proxy = world.proxyPosition(f), device = world.devicePosition(f);
    for (double v : {force.x(), force.y(), force.z(), double(world.sgoCount(f)), world.contactRadius(f), proxy.x(),
                     proxy.y(), proxy.z(), device.x(), device.y(), device.z()}) {
      *x++ = v;
    }
  }
  for (int b : dynamic_bodies_) {
    const sim::Vec3 v = world.bodyLinearVelocity(b), w = world.bodyAngularVelocity(b);
    for (double u : {v.x(), v.y(), v.z(), w.x(), w.y(), w.z()}) *x++ = u;
  }
  for (int f = 0; f < static_cast<int>(world.desc().fingers.size()); ++f) {
    const sim::Vec3 sent = world.toldForce(f);
    for (double v : {sent.x(), sent.y(), sent.z(), world.portEnergy(f)}) *x++ = v;
  }
  for (int k = 0; k < world.overlapPairCount(); ++k) *x++ = world.overlap(k).area * 1e6;
  for (int f : oriented_fingers_) {
    const sim::Quat q = world.deviceOrientation(f);
    for (double v : {q.w(), q.x(), q.y(), q.z()}) *x++ = v;
  }
  GF_ASSERT(x == row_.data() + row_.size() && "trace.csv's row matches traceColumns()");
  file_.push(row_.data());
}

}  // namespace gf::app
