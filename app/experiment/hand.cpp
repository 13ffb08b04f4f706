#include "app/experiment/hand.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "app/experiment/random.hpp"
#include "app/runs/files.hpp"

namespace gf::app {
namespace {

using sim::Vec3;

// A sum of sinusoids with random frequencies in [lo, hi] Hz and random phases, per axis, whose
// RMS is `rms`.
struct Wobble {
  static constexpr int kWaves = 4;
  std::array<std::array<double, kWaves>, 3> hz{}, phase{};
  double amplitude = 0.0;
  Wobble(SeededRandom& rng, double lo, double hi, double rms) : amplitude(rms * std::sqrt(2.0 / kWaves)) {
    for (int a = 0; a < 3; ++a) {
      for (int k = 0; k < kWaves; ++k) {
        hz[a][k] = rng.uniform(lo, hi);
        phase[a][k] = rng.uniform(0.0, 2.0 * std::numbers::pi);
      }
    }
  }
  double at(int axis, double t) const {
    double s = 0.0;
    for (int k = 0; k < kWaves; ++k) s += std::sin(2.0 * std::numbers::pi * hz[axis][k] * t + phase[axis][k]);
    return amplitude * s;
  }
};

Vec3 gaussian(SeededRandom& rng, double sd) { return sd * Vec3(rng.normal(), rng.normal(), rng.normal()); }

// Minimum jerk from 0 to 1 over tau in [0, 1].
double minimumJerk(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
}

}  // namespace

HandParams drawHand(std::uint64_t seed, int participant, double noise, const HandPopulation& pop) {
  SeededRandom rng = SeededRandom::of({seed, 3, static_cast<std::uint64_t>(participant)});
  HandParams h;
  // Drawn whatever the noise, so that the same participant is the same person at every level.
  const double reaction = pop.reaction_mean_s + pop.reaction_sd_s * rng.normal();
  const double pace = std::exp(pop.speed_log_sd * rng.normal());
  const double spread = std::exp(0.2 * rng.normal());  // some hands are steadier than others
  h.reaction_s = noise * std::max(0.1, reaction);
  h.speed = std::pow(pace, noise);
  h.endpoint_sd_m = noise * spread * pop.endpoint_sd_m;
  h.finger_sd_m = noise * spread * pop.finger_sd_m;
  h.tremor_rms_m = noise * spread * pop.tremor_rms_m;
  h.grip_sd_m = noise * spread * pop.grip_sd_m;
  return h;
}

std::vector<HandTrack> moveHand(const std::vector<sim::FingerDesc>& fingers,
                                const std::vector<std::pair<std::string, Vec3>>& grip, const HandParams& hand,
                                std::uint64_t trial_seed, double noise, double duration, double rate_hz) {
  SeededRandom rng(trial_seed);
  // This trial's own pace and delay about the participant's.
  const double pace = hand.speed * std::exp(0.08 * noise * rng.normal());
  const double delay = std::max(0.0, hand.reaction_s + 0.03 * noise * rng.normal());
  // The hand's scatter per waypoint, shared by the fingers (a waypoint repeated is a hold: the
  // same miss); the scripts' fingers share their keyframe times in the bundled tasks, and a
  // finger with other times draws on at its own keyframes.
  std::vector<Vec3> hand_miss;
  std::vector<HandTrack> out;
  for (std::size_t f = 0; f < fingers.size(); ++f) {
    const sim::DeviceTrack& script = fingers[f].device;
    HandTrack track;
    track.finger = fingers[f].name;
    for (const auto& k : script.keyframes) track.oriented |= !k.orientation.isApprox(sim::Quat::Identity());
    Vec3 grip_dir = Vec3::Zero();
    for (const auto& [name, d] : grip) {
      if (name == track.finger) grip_dir = d;
    }
    SeededRandom frng = SeededRandom::of({trial_seed, 7, f});
    const Wobble tremor(frng, 8.0, 12.0, hand.tremor_rms_m);
    const Wobble wander(frng, 0.5, 2.0, hand.grip_sd_m);
    const double grip_bias = hand.grip_sd_m * frng.normal();
    // The waypoints as this hand reaches them: times after the delay at its pace, positions missed.
    std::vector<double> times;
    std::vector<Vec3> points;
    for (std::size_t k = 0; k < script.keyframes.size(); ++k) {
      const auto& key = script.keyframes[k];
      times.push_back(delay + (key.time - script.keyframes.front().time) / pace + script.keyframes.front().time);
      if (k == 0) {
        points.push_back(key.position);  // where the hand starts: as scripted
        continue;
      }
      if (key.position.isApprox(script.keyframes[k - 1].position, 1e-12)) {
        points.push_back(points.back());
        continue;
      }
      while (hand_miss.size() < k) hand_miss.push_back(gaussian(rng, hand.endpoint_sd_m));
      points.push_back(key.position + hand_miss[k - 1] + gaussian(frng, hand.finger_sd_m));
    }
    const int rows = static_cast<int>(std::floor(duration * rate_hz + 1e-9)) + 1;
    for (int i = 0; i < rows; ++i) {
      const double t = i / rate_hz;
      std::size_t k = 0;
      while (k + 1 < times.size() && times[k + 1] <= t) ++k;
      Vec3 p = points[k];
      double s = 0.0;  // the way from waypoint k to the next (at k itself: 0)
      if (k + 1 < times.size() && t > times[k]) {
        s = minimumJerk((t - times[k]) / (times[k + 1] - times[k]));
        p = points[k] + s * (points[k + 1] - points[k]);
      }
      for (int a = 0; a < 3; ++a) p[a] += tremor.at(a, t);
      p += (grip_bias + wander.at(0, t)) * grip_dir;
      std::vector<double> row = {t, p.x(), p.y(), p.z()};
      if (track.oriented) {
        const sim::Quat& q0 = script.keyframes[k].orientation;
        const sim::Quat q = k + 1 < times.size() ? q0.slerp(s, script.keyframes[k + 1].orientation) : q0;
        row.insert(row.end(), {q.w(), q.x(), q.y(), q.z()});
      }
      track.rows.push_back(std::move(row));
    }
    out.push_back(std::move(track));
  }
  return out;
}

void writeHandCsv(const std::string& path, const HandTrack& track) {
  std::string text = track.oriented ? "t,x,y,z,qw,qx,qy,qz\n" : "t,x,y,z\n";
  for (const std::vector<double>& row : track.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i) text += ',';
      appendNumber(text, row[i]);
    }
    text += '\n';
  }
  writeFileAtomically(path, text);
}

}  // namespace gf::app
