#include "app/runs/trace.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

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

int traceStride(double haptic_rate_hz, double trace_rate_hz) {
  if (!(trace_rate_hz > 0.0)) return 1;
  return std::max(1, static_cast<int>(std::lround(haptic_rate_hz / trace_rate_hz)));
}

std::string traceSizeWarning(double haptic_rate_hz, double duration_s, int every_steps, double bytes_per_row) {
  const double rows_per_s = haptic_rate_hz / every_steps, bytes_per_s = bytes_per_row * rows_per_s;
  const double at_end = bytes_per_s * duration_s;
  if (at_end < kTraceWarnBytes) return "";
  // A tenth of the rows, at a rate that divides the haptic rate (1 kHz: 100 Hz).
  const int thinner = every_steps * 10;
  char text[400];
  std::snprintf(text, sizeof text,
                "trace.csv grows %.0f bytes a row at %g rows/s: %.2f GB an hour, about %.0f MB by the run's end "
                "(%g s); thin it with --set record.trace_rate=%g (a row every %d steps) or drop it with --set "
                "record.trace=false",
                bytes_per_row, rows_per_s, bytes_per_s * 3600.0 / 1e9, at_end / 1e6, duration_s,
                haptic_rate_hz / thinner, thinner);
  return text;
}

namespace {

// The writer thread's size check: after kTraceWatchRows rows, the projection, warned once.
RowFileOptions traceFileOptions(const sim::SceneDesc& scene, const TraceOptions& o,
                                const std::shared_ptr<std::string>& warning) {
  RowFileOptions out;
  out.fail_after_bytes = o.fail_after_bytes;
  out.ring_rows = o.ring_rows;
  if (!o.warn_size) return out;
  out.watch_rows = kTraceWatchRows;
  out.on_rows = [name = scene.name, rate = scene.world.haptic_rate_hz, duration = scene.duration,
                 every = std::max(1, o.every_steps), warning](std::size_t rows, std::uint64_t bytes) {
    const std::string text = traceSizeWarning(rate, duration, every, static_cast<double>(bytes) / static_cast<double>(rows));
    if (text.empty()) return;
    std::fprintf(stderr, "%s: warning: %s\n", name.c_str(), text.c_str());
    *warning = text;
  };
  return out;
}

}  // namespace

TraceWriter::TraceWriter(const sim::World& world, const std::string& path, TraceOptions options)
    : every_steps_(std::max(1, options.every_steps)),
      file_(path, traceColumns(world.desc()), traceFileOptions(world.desc(), options, size_warning_)),
      row_(file_.columns()) {
  const sim::SceneDesc& d = world.desc();
  for (std::size_t b = 0; b < d.bodies.size(); ++b) {
    if (d.bodies[b].mass > 0.0) dynamic_bodies_.push_back(static_cast<int>(b));
  }
  for (std::size_t f = 0; f < d.fingers.size(); ++f) {
    if (deviceGivesOrientation(d.fingers[f])) oriented_fingers_.push_back(static_cast<int>(f));
  }
}

void TraceWriter::record(const sim::World& world) {
  if (++steps_ % every_steps_ != 0) return;  // record.trace_rate: not one of the rows
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
