// What a run says about its UDP devices (UdpDeviceBridge::report, runWarnings, bindWarnings):
// the end-of-run line per device on stderr, and the warnings on stderr and in summary.json when
// a device sent nothing, when everything it sent was rejected, and when a socket listens beyond
// loopback. Each run either ends by its own (short) duration with nothing sent, or is driven in
// lockstep (the garbage is known read once the reply to a valid packet sent after it is back)
// and stopped with Ctrl-C: nothing depends on how fast either side runs.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <string>
#include <vector>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "app/device/device_protocol.hpp"
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


// One finger on any free loopback port; `duration` s.
std::string oneFinger(const std::string& duration) {
  return "name = \"udp-report\"\nduration = " + duration + R"(
effects = ["gravity", "god_finger", "force_feedback"]
[bodies.ground]
shape = "plane"
[fingers.finger]
[fingers.finger.device]
udp = "127.0.0.1:0"
start = [0, 0.05, 0]
[record]
trace = false
)";
}

// Two fingers on one socket: `sync` (channel 0) paces the test, `mute` (channel 1) gets garbage.
const std::string kTwoFingers = R"(name = "udp-report"
duration = 600.0
effects = ["gravity", "god_finger", "force_feedback"]
[bodies.ground]
shape = "plane"
[fingers.sync.device]
udp = "127.0.0.1:0"
start = [-0.05, 0.05, 0]
stale_after = 1.0
[fingers.mute.device]
udp = "127.0.0.1:0"
channel = 1
start = [0.05, 0.05, 0]
[record]
trace = false
)";

// A run of `scene` written into `dir`, its stderr read line by line.
Child startRun(const fs::path& dir, const std::string& scene, const std::string& options = "") {
  {
    std::ofstream(dir / "scene.toml") << scene;
  }
  return start(kBin + " run " + (dir / "scene.toml").string() + " --realtime --quiet " + options + " --out " +
                   (dir / "run").string(),
               (dir / "stdout.txt").string());
}

// The first line containing `text` (empty when none does), and how many do.
std::string firstWith(const std::vector<std::string>& lines, const std::string& text) {
  for (const std::string& l : lines) {
    if (l.find(text) != std::string::npos) return l;
  }
  return "";
}
long countWith(const std::vector<std::string>& lines, const std::string& text) {
  return std::count_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; });
}

TEST(UdpDeviceReport, ADeviceThatNeverSendsIsWarnedAboutAndTheRunStillExitsZero) {
  const fs::path dir = freshFolder("gf_udp_report_silent");
  Child child = startRun(dir, oneFinger("0.2"));
  ASSERT_GT(child.pid, 0);
  KillGroupOnExit stop{child.pid};
  const Ended run = finishLines(child);
  stop.done = true;
  EXPECT_EQ(run.status, 0) << "a run without packets is still a valid run";
  const std::string listening = firstWith(run.lines, "listening on 127.0.0.1:");
  const int port = portOf(listening.substr(0, listening.find(',')));
  ASSERT_GT(port, 0);
  const std::string address = "127.0.0.1:" + std::to_string(port);

  // The end-of-run line: nothing taken, nothing rejected, stale all along, no reply.
  const std::string report = firstWith(run.lines, "fingers.finger.device (" + address + ", channel 0): ");
  ASSERT_FALSE(report.empty());
  EXPECT_NE(report.find("0 packets taken; rejected on its channel: none; its socket read 0 datagrams, rejected: none; "
                        "stale 0.200 s (0 dropouts); 0 replies sent"),
            std::string::npos)
      << report;

  // The warning, on stderr and in summary.json; nothing about the address (loopback).
  const std::string warning = "fingers.finger.device: no packet came to " + address + " in the run's 0.200 s";
  EXPECT_EQ(countWith(run.lines, "udp-report: warning: " + warning), 1);
  EXPECT_EQ(countWith(run.lines, "every interface"), 0);
  const nlohmann::json summary = summaryOf(dir / "run");
  ASSERT_EQ(summary["warnings"].size(), 1u) << summary["warnings"].dump();
  EXPECT_EQ(summary["warnings"][0].get<std::string>().rfind(warning, 0), 0u) << summary["warnings"][0];
  EXPECT_EQ(summary["udp_devices"]["fingers"][0]["packets_taken"], 0);
}

TEST(UdpDeviceReport, ADeviceWhosePacketsAreAllRejectedIsWarnedAboutWithTheCounts) {
  const fs::path dir = freshFolder("gf_udp_report_rejected");
  Child child = startRun(dir, kTwoFingers);
  ASSERT_GT(child.pid, 0);
  KillGroupOnExit stop{child.pid};
  const std::string listening = lineWith(child.lines, "listening on 127.0.0.1:");
  const int port = portOf(listening.substr(0, listening.find(',')));
  ASSERT_GT(port, 0) << "the run did not say where it listens";
  const std::string address = "127.0.0.1:" + std::to_string(port);

  // Channel 1 gets only garbage: three of another protocol version, one short, one not finite.
  const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  const sockaddr_in server = loopback(port);
  const auto send = [&](const std::uint8_t* bytes, std::size_t size) {
    sendto(fd, bytes, size, 0, reinterpret_cast<const sockaddr*>(&server), sizeof server);
  };
  for (std::uint32_t seq = 0; seq < 3; ++seq) {
    std::vector<std::uint8_t> bytes = packetBytes(seq, 1, Vec3(0.05, 0.05, 0.0));
    bytes[3] = '2';  // "GFD2"
    send(bytes.data(), bytes.size());
  }
  send(packetBytes(3, 1, Vec3(0.05, 0.05, 0.0)).data(), 47);
  send(packetBytes(4, 1, Vec3(std::nan(""), 0.05, 0.0)).data(), DevicePacket::kSize);
  // Then one valid packet on channel 0: once its reply is back, the garbage before it was read.
  send(packetBytes(7, 0, Vec3(-0.05, 0.05, 0.0)).data(), DevicePacket::kSize);
  bool echoed = false;
  for (pollfd p{fd, POLLIN, 0}; !echoed && poll(&p, 1, kGuardMs) == 1;) {
    std::array<std::uint8_t, 128> buffer;
    const ssize_t size = recv(fd, buffer.data(), buffer.size(), 0);
    DeviceReply r;
    echoed = size > 0 && parseDeviceReply(std::span<const std::uint8_t>(buffer.data(), static_cast<std::size_t>(size)), r) &&
             r.channel == 0 && r.seq == 7;
  }
  close(fd);
  ASSERT_TRUE(echoed) << "no reply echoed the valid packet";
  kill(-child.pid, SIGINT);
  const Ended run = finishLines(child);
  stop.done = true;
  EXPECT_EQ(run.status, 130);

  // The end-of-run lines: the socket's rejections on both, the taken packet on sync's.
  const std::string socket = "its socket read 6 datagrams, rejected: 1 wrong size, 3 bad magic, 1 bad value;";
  const std::string sync = firstWith(run.lines, "fingers.sync.device (" + address + ", channel 0): 1 packet taken; ");
  const std::string mute = firstWith(run.lines, "fingers.mute.device (" + address + ", channel 1): 0 packets taken; ");
  ASSERT_FALSE(sync.empty());
  ASSERT_FALSE(mute.empty());
  EXPECT_NE(sync.find(socket), std::string::npos) << sync;
  EXPECT_NE(mute.find(socket), std::string::npos) << mute;
  EXPECT_NE(mute.find("; 0 replies sent"), std::string::npos) << mute;

  // One warning, for mute, naming what its datagrams were rejected for.
  const std::string warning = "fingers.mute.device: took none of the 6 datagrams read on " + address +
                              " (channel 1): 1 wrong size, 3 bad magic, 1 bad value, 1 for the other fingers' channels";
  EXPECT_EQ(countWith(run.lines, "udp-report: warning: " + warning), 1);
  const nlohmann::json summary = summaryOf(dir / "run");
  ASSERT_EQ(summary["warnings"].size(), 1u) << summary["warnings"].dump();
  EXPECT_EQ(summary["warnings"][0].get<std::string>().rfind(warning, 0), 0u) << summary["warnings"][0];
}

TEST(UdpDeviceReport, ASocketListeningBeyondLoopbackIsWarnedAboutWhenBound) {
  const fs::path dir = freshFolder("gf_udp_report_everywhere");
  // Port 0 on every interface, and nothing sent: no one else is talked to.
  Child child = startRun(dir, oneFinger("0.05"), "--set fingers.finger.device.udp=0.0.0.0:0");
  ASSERT_GT(child.pid, 0);
  KillGroupOnExit stop{child.pid};
  const Ended run = finishLines(child);
  stop.done = true;
  EXPECT_EQ(run.status, 0);
  const std::string listening = firstWith(run.lines, "listening on 0.0.0.0:");
  const int port = portOf(listening.substr(0, listening.find(',')));
  ASSERT_GT(port, 0);
  const std::string warning = "fingers.finger.device listens on every interface (0.0.0.0:" + std::to_string(port) +
                              "): anyone who can reach this machine on UDP port " + std::to_string(port) +
                              " can drive the finger";
  // Said when bound, right after where it listens (before the run), and kept in summary.json.
  ASSERT_GE(run.lines.size(), 2u);
  EXPECT_EQ(run.lines[0], listening);
  EXPECT_NE(run.lines[1].find("udp-report: warning: " + warning), std::string::npos) << run.lines[1];
  const nlohmann::json summary = summaryOf(dir / "run");
  ASSERT_EQ(summary["warnings"].size(), 2u) << summary["warnings"].dump();  // and it sent nothing
  EXPECT_EQ(summary["warnings"][0].get<std::string>().rfind(warning, 0), 0u) << summary["warnings"][0];
  EXPECT_NE(summary["warnings"][1].get<std::string>().find("no packet came to 0.0.0.0:"), std::string::npos);
}

}  // namespace
}  // namespace gf::app
