#include "sim/scene/device.hpp"

#include <algorithm>

namespace gf::sim {

namespace {

DeviceSample held(const DeviceTrack::Keyframe& k) {
  DeviceSample out;
  out.position = k.position;
  out.orientation = k.orientation;
  return out;
}

}  // namespace

DeviceSample DeviceTrack::sample(double t) const {
  if (keyframes.empty()) return {};
  if (!(t > keyframes.front().time)) return held(keyframes.front());
  if (t >= keyframes.back().time) return held(keyframes.back());
  const auto next = std::upper_bound(keyframes.begin(), keyframes.end(), t,
                                     [](double x, const Keyframe& k) { return x < k.time; });
  const Keyframe& a = *(next - 1);
  const Keyframe& b = *next;
  const double span = b.time - a.time;
  const double u = (t - a.time) / span;
  const Vec3 delta = b.position - a.position;
  DeviceSample out;
  if (interpolation == Interpolation::kLinear) {
    out.position = a.position + u * delta;
    out.velocity = delta / span;
  } else {
    // Smoothstep s(u) = 3u^2 - 2u^3, s'(u) = 6u(1 - u).
    const double s = u * u * (3.0 - 2.0 * u);
    out.position = a.position + s * delta;
    out.velocity = (6.0 * u * (1.0 - u) / span) * delta;
    out.orientation = a.orientation.slerp(s, b.orientation);
    return out;
  }
  out.orientation = a.orientation.slerp(u, b.orientation);
  return out;
}

}  // namespace gf::sim
