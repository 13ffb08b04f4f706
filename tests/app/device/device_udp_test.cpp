// A live device through loopback: a C++ device program drives `godfinger run --realtime` over
// UDP (docs/device-protocol.md), in lockstep (each packet is sent once the reply echoing the one
// before has come, so nothing depends on how fast either side runs). Every reply is checked; the
// run is stopped with Ctrl-C and its summary.json checked for what was sent.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "app/device/device_protocol.hpp"
#include "app/runs/run_reader.hpp"
#include "tests/app/device/loopback.hpp"
#include "tests/app/run_helpers.hpp"

namespace gf::app {
namespace {

using namespace test;
using gf::test::kGuardMs;
using gf::test::loopback;
using gf::test::packetBytes;
using gf::test::portOf;
using sim::Vec3;

constexpr double kSceneStep = 0.001;          // s: the scene's haptic step
// s: the scene's stale_after, its largest value: only a dropout the test makes on purpose is one,
// however long this process waits for the CPU between two packets.
constexpr double kStaleAfter = 1.0;
constexpr double kRamp = 0.1;          // s: the scene's force_ramp
constexpr double kMaxForce = 40.0;     // N: the coupling's default clamp

// The port a run's first "listening on 127.0.0.1:PORT, channel C" line gives, or 0.
int listeningPort(std::FILE* lines) {
  const std::string line = lineWith(lines, "listening on 127.0.0.1:");
  return line.empty() ? 0 : portOf(line.substr(0, line.find(',')));
}

// A finger above the ground, driven over UDP on any free loopback port.
const std::string kScene = R"(name = "udp-loopback"
duration = 600.0
effects = ["gravity", "friction", "god_finger", "force_feedback"]
[bodies.ground]
shape = "plane"
friction = 0.8
[fingers.finger]
n_sgo = 8
r_max = 0.01
[fingers.finger.device]
udp = "127.0.0.1:0"
start = [0, 0.05, 0]
stale_after = 1.0
force_ramp = 0.1
[record]
trace = false
)";

// The device side: one loopback socket, packets out, replies in; every reply is checked against
// the protocol's promises as it arrives.
class Device {
 public:
  explicit Device(int port, std::uint32_t first_seq = 0) : server_(loopback(port)), next_seq_(first_seq) {
    fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    // Room for replies while this process waits for a core (the kernel caps it at
    // net.core.rmem_max: 0.2-0.3 s of replies at the default).
    const int buffer = 1 << 20;
    setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &buffer, sizeof buffer);
  }
  ~Device() { close(fd_); }

  // A valid packet; returns its seq.
  std::uint32_t send(const Vec3& position) {
    DevicePacket p;
    p.seq = next_seq_++;
    p.time = 1000.0 + p.seq * kSceneStep;
    p.position = position;
    std::array<std::uint8_t, DevicePacket::kSize> bytes;
    encodeDevicePacket(p, bytes);
    raw(bytes);
    sent_at_.push_back(std::chrono::steady_clock::now());
    ++valid_;
    return p.seq;
  }
  void raw(std::span<const std::uint8_t> bytes) {
    sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&server_), sizeof server_);
  }
  std::uint32_t nextSeq() const { return next_seq_; }
  long validSent() const { return valid_; }

  // The next reply, checked; nullopt when none came within the guard.
  std::optional<DeviceReply> next() {
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, kGuardMs) != 1) return std::nullopt;
    std::array<std::uint8_t, 128> buffer;
    const ssize_t size = recv(fd_, buffer.data(), buffer.size(), 0);
    DeviceReply r;
    EXPECT_TRUE(size >= 0 && parseDeviceReply(std::span<const std::uint8_t>(buffer.data(), static_cast<std::size_t>(size)), r))
        << "a reply of " << size << " bytes";
    check(r);
    return r;
  }

  // Replies until one echoes `seq`; that one (nullopt when the guard ran out, or after a
  // minute of simulated replies without it).
  std::optional<DeviceReply> echo(std::uint32_t seq) {
    for (int n = 0; n < 60000; ++n) {
      std::optional<DeviceReply> r = next();
      if (!r || r->seq == seq) {
        if (r && seq < sent_at_.size() && !answered_[seq]) {
          rtt_us_.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - sent_at_[seq]).count());
        }
        if (r) answered_[seq] = true;
        return r;
      }
    }
    ADD_FAILURE() << "no reply echoed seq " << seq;
    return std::nullopt;
  }

  std::vector<double>& rtts() { return rtt_us_; }
  long replies() const { return replies_; }
  const std::vector<DeviceReply>& heard() const { return heard_; }  // every reply, in order

 private:
  void check(const DeviceReply& r) {
    ++replies_;
    heard_.push_back(r);
    EXPECT_EQ(r.channel, 0u);
    EXPECT_TRUE(r.force.allFinite());
    EXPECT_LE(r.force.norm(), kMaxForce + 1e-9) << "at t = " << r.time;
    EXPECT_GE(r.gain, 0.0f);
    EXPECT_LE(r.gain, 1.0f);
    if (r.gain < 1.0f && !(r.flags & DeviceReply::kDisplaced)) {
      EXPECT_TRUE(r.flags & DeviceReply::kRamping) << "at t = " << r.time;
    }
    EXPECT_LT(r.seq, next_seq_) << "echoes a seq not sent";
    if (previous_) {
      // One reply a step, in order; the seq echoed never goes back; the gain never steps.
      EXPECT_GT(r.time, previous_->time);
      EXPECT_GE(r.seq, previous_->seq);
      if (!(r.flags & DeviceReply::kDisplaced)) {  // a displaced sender's gain is 0
        EXPECT_LE(std::abs(r.gain - previous_->gain), (r.time - previous_->time) / kRamp + 1e-5) << "gain step at t = " << r.time;
      }
      // While ramping the force sent changes by at most max_force / force_ramp per second.
      if (r.flags & DeviceReply::kRamping) {
        EXPECT_LE((r.force - previous_->force).norm(), kMaxForce * (r.time - previous_->time) / kRamp + 1e-9)
            << "force step at t = " << r.time;
      }
    }
    previous_ = r;
  }

  int fd_ = -1;
  sockaddr_in server_{};
  std::uint32_t next_seq_;
  long valid_ = 0, replies_ = 0;
  std::optional<DeviceReply> previous_;
  std::vector<DeviceReply> heard_;
  std::vector<std::chrono::steady_clock::time_point> sent_at_;
  std::array<bool, 100000> answered_{};
  std::vector<double> rtt_us_;
};

// 1. Down from 5 cm above the ground to the ground in 200 packets, then held there: the
// proxy (8 mm radius) rests on the ground, and the device feels the coupling spring pushing it
// up. Held until the start ramp has reached full force and the proxy has settled.
void pressAndHold(Device& device, double& held_force) {
  std::optional<DeviceReply> r;
  for (int k = 0; k < 20000; ++k) {
    const double y = std::max(0.0, 0.05 * (1.0 - k / 200.0));
    r = device.echo(device.send(Vec3(0.0, y, 0.0)));
    ASSERT_TRUE(r) << "no reply to packet " << k;
    if (k >= 600 && !(r->flags & DeviceReply::kRamping)) break;
  }
  ASSERT_EQ(r->gain, 1.0f);
  EXPECT_FALSE(r->flags & DeviceReply::kStale);
  EXPECT_TRUE(r->flags & DeviceReply::kTouching);
  EXPECT_EQ(r->sgo_count, 8u);
  EXPECT_GT(r->radius, 0.0);
  // At rest the coupling (800 N/m) and the contact (20000 N/m) are springs in series over the
  // proxy's radius: F = 800 * 0.008 / (1 + 800 / 20000) = 6.154 N, up.
  const double spring = 800.0 * 0.008 / (1.0 + 800.0 / 20000.0);
  EXPECT_NEAR(r->force.y(), spring, 0.01 * spring);
  EXPECT_NEAR(r->force.x(), 0.0, 0.01);
  held_force = r->force.norm();
}

// 2. Garbage between two valid packets: each ignored, none fatal.
void garbageMovesNothing(Device& device, double held_force) {
  const Vec3 hold(0.0, 0.0, 0.0);
  std::optional<DeviceReply> r;
  std::vector<std::uint8_t> bytes = packetBytes(device.nextSeq(), 0, hold);
  device.raw(std::span<const std::uint8_t>(bytes.data(), 47));  // short
  bytes.push_back(0);
  device.raw(bytes);                                             // long
  bytes.pop_back();
  bytes[3] = '2';
  device.raw(bytes);                                             // "GFD2": another version
  device.raw(packetBytes(device.nextSeq(), 0, Vec3(std::nan(""), 0.0, 0.0)));  // not finite
  device.raw(packetBytes(device.nextSeq(), 0, Vec3(0.0, 150.0, 0.0)));         // beyond 100 m
  device.raw(packetBytes(device.nextSeq(), 7, hold));                          // no finger reads channel 7
  device.raw(packetBytes(device.nextSeq() - 5, 0, Vec3(0.0, 0.04, 0.0)));      // older than the last
  r = device.echo(device.send(hold));
  ASSERT_TRUE(r);
  EXPECT_NEAR(r->force.norm(), held_force, 0.01 * held_force);  // the garbage moved nothing
}

// 3. Silence: once no packet came for stale_after the device is stale, the proxy holds, and
// the force ramps to zero over force_ramp (times are simulated: exact to a step).
void silenceRampsTheForceToZero(Device& device, double held_force) {
  std::optional<DeviceReply> r = device.echo(device.send(Vec3(0.0, 0.0, 0.0)));
  ASSERT_TRUE(r);
  const double last_taken = r->time - kSceneStep;  // the step that took the last packet started here
  std::optional<DeviceReply> first_stale, zero;
  while (!zero) {
    r = device.next();
    ASSERT_TRUE(r);
    if (!(r->flags & DeviceReply::kStale)) continue;
    if (!first_stale) first_stale = r;
    if (r->gain > 0.1f) {
      EXPECT_NEAR(r->force.norm() / r->gain, held_force, 0.01 * held_force) << "the proxy held";
    }
    if (r->gain == 0.0f) zero = r;
  }
  EXPECT_GT(first_stale->time - last_taken, kStaleAfter);
  EXPECT_LE(first_stale->time - last_taken, kStaleAfter + 2 * kSceneStep + 1e-9);
  EXPECT_NEAR(zero->time - first_stale->time, kRamp, 1.5 * kSceneStep);
  EXPECT_EQ(zero->force.norm(), 0.0);
}

// 4. Packets again: the device is followed at once and the force ramps back up, no step.
void packetsRampItBackUp(Device& device, double held_force) {
  const Vec3 hold(0.0, 0.0, 0.0);
  std::optional<DeviceReply> r;
  r = device.echo(device.send(hold));
  ASSERT_TRUE(r);
  EXPECT_FALSE(r->flags & DeviceReply::kStale);
  EXPECT_LE(r->gain, 2 * kSceneStep / kRamp + 1e-6);
  for (int k = 0; (r->flags & DeviceReply::kRamping) && k < 20000; ++k) {
    r = device.echo(device.send(hold));
    ASSERT_TRUE(r);
  }
  EXPECT_EQ(r->gain, 1.0f);
  EXPECT_FALSE(r->flags & DeviceReply::kRamping);
  EXPECT_NEAR(r->force.norm(), held_force, 0.02 * held_force);
}

// 5. A second program takes the channel (newer seqs) where the first holds: the first is not
// left pushing. It hears a reply every step, flagged displaced, its force fading from the press
// to zero at the ramp's rate (Device::check: no step above max_force dt / force_ramp), then
// zero; the second gets the press faded in from zero.
void aTakeoverFadesTheFirstOut(Device& device, Device& second, double held_force) {
  const Vec3 hold(0.0, 0.0, 0.0);
  std::optional<DeviceReply> r;
  r = second.echo(second.send(hold));
  ASSERT_TRUE(r);
  EXPECT_LE(r->force.norm(), kMaxForce * 2 * kSceneStep / kRamp + 1e-9) << "faded in from zero";
  std::optional<DeviceReply> displaced, told_nothing;
  for (int k = 0; k < 20000 && !told_nothing; ++k) {
    const std::optional<DeviceReply> d = device.next();
    ASSERT_TRUE(d) << "the displaced program waits for a reply";
    if (!(d->flags & DeviceReply::kDisplaced)) continue;  // the steps before the takeover
    if (!displaced) displaced = d;
    if (d->force.norm() == 0.0) told_nothing = d;
  }
  ASSERT_TRUE(displaced && told_nothing);
  EXPECT_NEAR(displaced->force.norm(), held_force, 0.4 + 0.02 * held_force) << "the fade starts from the press";
  EXPECT_NEAR(told_nothing->time - displaced->time, held_force * kRamp / kMaxForce, 2 * kSceneStep);
  EXPECT_FALSE(told_nothing->flags & DeviceReply::kRamping);
  const std::optional<DeviceReply> after = device.next();
  ASSERT_TRUE(after) << "still answered once faded";
  EXPECT_TRUE(after->flags & DeviceReply::kDisplaced);
}

// 6. The run ends (Ctrl-C, or its duration) while `device` presses with `held_force`: the replies
// go on after the last step, flagged ending, the force fading from the press to zero at the
// ramp's rate (Device::check: no step above max_force dt / force_ramp) over force_ramp, and the
// run's last reply tells zero. `sending`: the device goes on sending while it listens. Returns
// the simulated time of the first reply flagged ending.
double theEndFadesThePressOut(Device& device, double held_force, bool sending) {
  const std::vector<DeviceReply>& heard = device.heard();
  std::size_t looked = heard.size();
  std::optional<std::size_t> first, zero;  // the first reply flagged ending, the first of them telling zero
  for (int k = 0; k < 600000 && !zero; ++k) {
    if (sending) device.send(Vec3::Zero());  // a packet a reply: the replies after the end echo none of them
    if (!device.next()) break;
    for (; looked < heard.size() && !zero; ++looked) {
      const DeviceReply& r = heard[looked];
      if (!(r.flags & DeviceReply::kEnding)) {
        EXPECT_FALSE(first) << "a reply after the end not flagged ending, at t = " << r.time;
        continue;
      }
      if (!first) first = looked;
      if (r.force.isZero(0.0)) zero = looked;
    }
  }
  if (!first || !zero) {
    ADD_FAILURE() << "no fade to zero was heard";
    return 0.0;
  }
  // The run's last step ended a step before the first reply flagged ending (which the caller
  // checks where it knows when that was); the fade starts from the press, one step in.
  const double end = heard[*first].time - kSceneStep;
  EXPECT_NEAR(heard[*first].force.norm(), held_force, 0.02 * held_force + kMaxForce * kSceneStep / kRamp)
      << "the press when the run ended";
  EXPECT_NEAR(heard[*zero].time - end, kRamp, 1.5 * kSceneStep) << "faded over force_ramp";
  EXPECT_NE(heard[*first].flags & DeviceReply::kRamping, 0u);
  for (std::size_t i = *first; i <= *zero; ++i) {
    EXPECT_EQ(heard[i].seq, heard[*first].seq) << "no packet is taken after the last step, t = " << heard[i].time;
  }
  return heard[*first].time;
}

TEST(UdpDevice, ADeviceDrivesARealtimeRunThroughLoopback) {
  const fs::path dir = freshFolder("gf_udp_loopback");
  {
    std::ofstream(dir / "scene.toml") << kScene;
  }
  Child child = start(kBin + " run " + (dir / "scene.toml").string() + " --realtime --quiet --out " + (dir / "run").string(),
                      (dir / "stdout.txt").string());
  ASSERT_GT(child.pid, 0);
  KillGroupOnExit stop{child.pid};  // whatever happens below, the run does not outlive the test
  const int port = listeningPort(child.lines);
  ASSERT_GT(port, 0) << "the run did not say where it listens";
  Device device(port);

  double held_force = 0.0;
  ASSERT_NO_FATAL_FAILURE(pressAndHold(device, held_force));
  ASSERT_NO_FATAL_FAILURE(garbageMovesNothing(device, held_force));
  ASSERT_NO_FATAL_FAILURE(silenceRampsTheForceToZero(device, held_force));
  ASSERT_NO_FATAL_FAILURE(packetsRampItBackUp(device, held_force));
  Device second(port, device.nextSeq() + 1000);
  ASSERT_NO_FATAL_FAILURE(aTakeoverFadesTheFirstOut(device, second, held_force));

  // 6. Ctrl-C while the second presses: the run stops, its device hears its press fade out,
  // and the run writes its summary and exits 130.
  std::optional<DeviceReply> r;
  for (int k = 0; k < 20000 && (!r || r->flags & DeviceReply::kRamping); ++k) r = second.echo(second.send(Vec3::Zero()));
  ASSERT_TRUE(r && !(r->flags & DeviceReply::kRamping));
  kill(-child.pid, SIGINT);
  theEndFadesThePressOut(second, held_force, false);
  EXPECT_EQ(finish(child), 130);
  stop.done = true;
  const nlohmann::json summary = summaryOf(dir / "run");
  EXPECT_TRUE(summary["interrupted"].get<bool>());
  const nlohmann::json& socket = summary["udp_devices"]["sockets"][0];
  EXPECT_EQ(socket["wrong_size"], 2);
  EXPECT_EQ(socket["bad_magic"], 1);
  EXPECT_EQ(socket["bad_value"], 2);
  EXPECT_EQ(socket["unknown_channel"], 1);
  EXPECT_EQ(socket["receive_errors"], 0);
  const nlohmann::json& finger = summary["udp_devices"]["fingers"][0];
  EXPECT_EQ(finger["finger"], "finger");
  EXPECT_EQ(finger["out_of_order"], 1);
  EXPECT_EQ(finger["packets_taken"], device.validSent() + second.validSent());
  EXPECT_EQ(finger["takeovers"], 1);
  EXPECT_GT(finger["displaced_replies"].get<long>(), 0);
  EXPECT_GE(finger["stale_periods"].get<long>(), 1);
  EXPECT_GE(finger["replies_sent"].get<long>() + finger["ending_replies"].get<long>(), device.replies());
  EXPECT_GT(finger["ending_replies"].get<long>(), 0);
  EXPECT_EQ(finger["send_errors"], 0);

  // The loopback round trip (send to the reply echoing it: the wait for the next step, the
  // step, both sockets), for the record; not a pass/fail figure.
  std::vector<double>& rtt = device.rtts();
  std::sort(rtt.begin(), rtt.end());
  if (!rtt.empty()) {
    std::printf("loopback round trip over %zu packets: p50 %.0f us, p99 %.0f us, max %.0f us; late steps %s\n",
                rtt.size(), rtt[rtt.size() / 2], rtt[rtt.size() * 99 / 100], rtt.back(),
                summary["realtime"]["late_steps"].dump().c_str());
  }
}

// A run that reaches its duration while a device program presses and goes on sending (the
// defect this guards against: the last step's 6 N stayed the program's last word, and its packets
// went unanswered while the run wrote its outputs). The press fades out after the duration,
// every reply flagged ending, and the run exits 0 with the replies counted in its summary.
TEST(UdpDevice, ARunThatReachesItsDurationFadesThePressOut) {
  const fs::path dir = freshFolder("gf_udp_duration");
  {
    std::ofstream(dir / "scene.toml") << kScene;
  }
  // Long enough for the press and its ramp in lockstep, even on a slow (sanitizer) build.
  constexpr double kDuration = 6.0;
  Child child = start(kBin + " run " + (dir / "scene.toml").string() + " --realtime --quiet --set duration=" +
                          std::to_string(kDuration) + " --out " + (dir / "run").string(),
                      (dir / "stdout.txt").string());
  ASSERT_GT(child.pid, 0);
  KillGroupOnExit stop{child.pid};
  const int port = listeningPort(child.lines);
  ASSERT_GT(port, 0) << "the run did not say where it listens";
  Device device(port);
  double held_force = 0.0;
  ASSERT_NO_FATAL_FAILURE(pressAndHold(device, held_force));
  const double ended = theEndFadesThePressOut(device, held_force, true);
  EXPECT_NEAR(ended, kDuration + kSceneStep, 0.5 * kSceneStep) << "the first reply after the last step";
  EXPECT_EQ(finish(child), 0);
  stop.done = true;
  const nlohmann::json summary = summaryOf(dir / "run");
  EXPECT_FALSE(summary["interrupted"].get<bool>());
  const nlohmann::json& finger = summary["udp_devices"]["fingers"][0];
  EXPECT_GE(finger["replies_sent"].get<long>() + finger["ending_replies"].get<long>(), device.replies());
  EXPECT_EQ(finger["last_seq"].get<long>(), device.heard().back().seq) << "the last packet the run took";
}

// Runs `device-udp` in realtime with both fingers on one free port (and the `--set`s of `extra`),
// drives it with the example client (examples/device-udp/client.py `client_args`), then stops
// it with Ctrl-C: the client's JSON report, or null (with the failure reported) when a step
// failed. The run's folder is dir/run.
nlohmann::json driveWithExampleClient(const fs::path& dir, const std::string& extra, const std::string& client_args) {
  Child child = start(kBin + " run device-udp --realtime --quiet --set duration=30 --set fingers.left.device.udp=0 " +
                          "--set fingers.right.device.udp=0" + extra + " --out " + (dir / "run").string(),
                      (dir / "stdout.txt").string());
  if (child.pid <= 0) {
    ADD_FAILURE() << "the run did not start";
    return nullptr;
  }
  KillGroupOnExit stop{child.pid};
  const int port = listeningPort(child.lines);
  if (port <= 0) {
    ADD_FAILURE() << "the run did not say where it listens";
    return nullptr;
  }
  const std::string command = std::string(GF_PYTHON3) + " " + GF_SOURCE_DIR + "/examples/device-udp/client.py --port " +
                              std::to_string(port) + " " + client_args;
  std::FILE* client = popen(command.c_str(), "r");
  if (client == nullptr) {
    ADD_FAILURE() << "cannot start " << command;
    return nullptr;
  }
  char line[1024] = {};
  const bool read = std::fgets(line, sizeof line, client) != nullptr;
  EXPECT_EQ(pclose(client), 0) << line;
  kill(-child.pid, SIGINT);
  EXPECT_EQ(finish(child), 130);
  stop.done = true;
  if (!read) {
    ADD_FAILURE() << "client.py printed nothing";
    return nullptr;
  }
  return nlohmann::json::parse(line);
}

// The example device program and the bundled scene it is written for: client.py replays the
// Fig. 8 pinch on both channels of the scene's socket (here any free port) and reports what it
// sent and got back. Its JSON line and the run's summary must agree on a pinch that squeezed.
TEST(UdpDevice, TheExampleClientDrivesTheBundledScene) {
  const fs::path dir = freshFolder("gf_udp_example");
  // 1.5 s of the pinch: the fingers close in by 0.5 s and squeeze (about 4 N each).
  const nlohmann::json report = driveWithExampleClient(dir, "", "--seconds 1.5 --rate 1000");
  ASSERT_TRUE(report.is_object());
  EXPECT_EQ(report["sent"], 2 * 1501);  // both fingers, 1.5 s at 1 kHz, both ends
  EXPECT_EQ(report["channels"], 2);
  EXPECT_EQ(report["bad_replies"], 0);
  EXPECT_GT(report["answered"].get<long>(), 0);
  EXPECT_LE(report["answered"].get<long>(), report["sent"].get<long>());
  EXPECT_GT(report["rtt_us_p50"].get<double>(), 0.0);
  EXPECT_GE(report["rtt_us_p99"].get<double>(), report["rtt_us_p50"].get<double>());
  EXPECT_GT(report["max_force_n"].get<double>(), 1.0);  // the squeeze was felt
  EXPECT_LE(report["max_force_n"].get<double>(), kMaxForce);
  const nlohmann::json summary = summaryOf(dir / "run");
  const nlohmann::json& sockets = summary["udp_devices"]["sockets"];
  ASSERT_EQ(sockets.size(), 1u);  // both fingers on one socket
  // Loopback does not lose datagrams, but the kernel drops them when the haptic thread falls
  // behind by more than its buffer holds (a loaded machine): counted, and nothing else missing.
  EXPECT_EQ(sockets[0]["datagrams"].get<long>() + sockets[0]["kernel_drops"].get<long>(), report["sent"].get<long>());
  long taken = 0;
  for (const nlohmann::json& f : summary["udp_devices"]["fingers"]) {
    taken += f["packets_taken"].get<long>();
    EXPECT_EQ(f["out_of_order"], 0);
  }
  EXPECT_EQ(taken, sockets[0]["datagrams"].get<long>());  // in order on loopback: every packet read is taken
}

// The example program as a 6-DOF device (--gfd2: 64-byte packets with each keyframe's
// orientation, the identity for the Fig. 8 tracks): every packet is taken, none is a bad value,
// and the finger whose device table gives a tilt records in trace.csv the orientation sent
// followed by that tilt (10 deg about x).
TEST(UdpDevice, TheExampleClientSendsGfd2AndTheTraceHasTheOrientation) {
  const fs::path dir = freshFolder("gf_udp_gfd2");
  const nlohmann::json report =
      driveWithExampleClient(dir, " --set fingers.left.device.tilt_deg=10", "--seconds 0.5 --rate 1000 --gfd2");
  ASSERT_TRUE(report.is_object());
  EXPECT_GT(report["answered"].get<long>(), 0);
  const nlohmann::json summary = summaryOf(dir / "run");
  const nlohmann::json& socket = summary["udp_devices"]["sockets"].at(0);
  EXPECT_EQ(socket["bad_value"], 0);
  EXPECT_EQ(socket["wrong_size"], 0);
  EXPECT_EQ(socket["bad_magic"], 0);
  const CsvTable trace = readTrace(dir / "run");
  const double half = 5.0 * std::acos(-1.0) / 180.0;  // half of 10 deg
  EXPECT_NEAR(trace.column("left.dqw").back(), std::cos(half), 1e-6);
  EXPECT_NEAR(trace.column("left.dqx").back(), std::sin(half), 1e-6);
  EXPECT_EQ(std::count(trace.names.begin(), trace.names.end(), "right.dqw"), 0) << "an untilted UDP device is not traced";
}

}  // namespace
}  // namespace gf::app
