#include "sim/device.hpp"

#include <algorithm>

namespace gf::sim {

DeviceSample DeviceTrack::sample(double t) const {
  if (keyframes.empty()) return {};
  if (!(t > keyframes.front().time)) return {keyframes.front().position, Vec3::Zero()};
  if (t >= keyframes.back().time) return {keyframes.back().position, Vec3::Zero()};
  const auto next = std::upper_bound(keyframes.begin(), keyframes.end(), t,
                                     [](double x, const Keyframe& k) { return x < k.time; });
  const Keyframe& a = *(next - 1);
  const Keyframe& b = *next;
  const double span = b.time - a.time;
  const double u = (t - a.time) / span;
  const Vec3 delta = b.position - a.position;
  if (interpolation == Interpolation::kLinear) return {a.position + u * delta, delta / span};
  // Smoothstep s(u) = 3u^2 - 2u^3, s'(u) = 6u(1 - u).
  return {a.position + (u * u * (3.0 - 2.0 * u)) * delta, (6.0 * u * (1.0 - u) / span) * delta};
}

}  // namespace gf::sim
