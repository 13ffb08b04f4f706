// A 6-DOF device over UDP: the documented GFD2 layout (GFD1's 48 bytes, then the orientation as
// four f32), the datagrams refused, and the orientation a DeviceLink hands the World (the
// device's tilt after it; held while stale; a GFD1 packet keeping its stream's).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "app/runs/trace.hpp"
#include "app/scene/scene_file.hpp"
#include "app/device/device_protocol.hpp"
#include "sim/world/world.hpp"
#include "tests/app/device/wire_bytes.hpp"

namespace gf::app {
namespace {

using sim::Quat;
using sim::Vec3;

constexpr double kHapticStep = 0.001;  // s: the haptic step of these tests

using gf::test::putF64;
using gf::test::putU32;
using gf::test::putF32;

// A GFD2 datagram: "GFD2", seq 7, channel 1, buttons 2, time 3.5, position, then w, x, y, z.
std::vector<std::uint8_t> orientedBytes(std::uint32_t magic, float w, float x, float y, float z) {
  std::vector<std::uint8_t> b;
  putU32(b, magic);
  putU32(b, 7);
  putU32(b, 1);
  putU32(b, 2);
  putF64(b, 3.5);
  for (double c : {0.01, -0.02, 0.03}) putF64(b, c);
  for (float c : {w, x, y, z}) putF32(b, c);
  return b;
}

Quat about(const Vec3& axis, double degrees) {
  return Quat(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis.normalized()));
}

DevicePacket packet(std::uint32_t seq, double time, const Quat* orientation) {
  DevicePacket p;
  p.seq = seq;
  p.time = time;
  p.position = Vec3(0.0, 0.1, 0.0);
  p.oriented = orientation != nullptr;
  if (orientation) p.orientation = *orientation;
  return p;
}

// docs/device-protocol.md: GFD2 is GFD1's fields at the same offsets, then w, x, y, z (f32) at
// 48, 52, 56, 60: 64 bytes, encoded and parsed back the same.
TEST(DeviceProtocolOrientation, AGfd2PacketIsReadAsDocumented) {
  const float h = static_cast<float>(std::sqrt(0.5));
  const std::vector<std::uint8_t> b = orientedBytes(0x32444647, h, 0.0f, h, 0.0f);
  ASSERT_EQ(b.size(), DevicePacket::kOrientedSize);
  ASSERT_EQ(DevicePacket::kOrientedSize, 64u);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "GFD2");
  DevicePacket p;
  ASSERT_EQ(parseDevicePacket(b, p), PacketError::kNone);
  EXPECT_TRUE(p.oriented);
  EXPECT_EQ(p.seq, 7u);
  EXPECT_EQ(p.channel, 1u);
  EXPECT_EQ(p.buttons, 2u);
  EXPECT_EQ(p.time, 3.5);
  EXPECT_EQ(p.position, Vec3(0.01, -0.02, 0.03));
  EXPECT_LT(p.orientation.angularDistance(about(Vec3::UnitY(), 90.0)), 1e-6);
  std::array<std::uint8_t, DevicePacket::kOrientedSize> again;
  encodeOrientedDevicePacket(p, again);
  EXPECT_TRUE(std::equal(again.begin(), again.end(), b.begin()));
  // The first 48 bytes with GFD1's magic are the same packet without its orientation.
  std::vector<std::uint8_t> gfd1(b.begin(), b.begin() + 48);
  gfd1[3] = '1';
  DevicePacket q;
  ASSERT_EQ(parseDevicePacket(gfd1, q), PacketError::kNone);
  EXPECT_FALSE(q.oriented);
  EXPECT_EQ(q.orientation.coeffs(), Quat::Identity().coeffs());
  EXPECT_EQ(q.position, p.position);
}

// A GFD2 orientation that is not finite or is further than 0.001 from unit length is a bad value;
// the size picks the magic expected (64 bytes of GFD1 are foreign, as 48 of GFD2 are).
TEST(DeviceProtocolOrientation, BadOrientationsAndMismatchedSizesAreRefused) {
  DevicePacket p;
  p.seq = 99;
  EXPECT_EQ(parseDevicePacket(orientedBytes(0x32444647, 2.0f, 0.0f, 0.0f, 0.0f), p), PacketError::kBadValue);
  EXPECT_EQ(parseDevicePacket(orientedBytes(0x32444647, 0.0f, 0.0f, 0.0f, 0.0f), p), PacketError::kBadValue);
  EXPECT_EQ(parseDevicePacket(orientedBytes(0x32444647, std::nanf(""), 0.0f, 0.0f, 0.0f), p), PacketError::kBadValue);
  EXPECT_EQ(parseDevicePacket(orientedBytes(0x32444647, 1.0f, HUGE_VALF, 0.0f, 0.0f), p), PacketError::kBadValue);
  EXPECT_EQ(parseDevicePacket(orientedBytes(0x31444647, 1.0f, 0.0f, 0.0f, 0.0f), p), PacketError::kMagic);
  std::vector<std::uint8_t> longer = orientedBytes(0x32444647, 1.0f, 0.0f, 0.0f, 0.0f);
  longer.push_back(0);
  EXPECT_EQ(parseDevicePacket(longer, p), PacketError::kSize);
  EXPECT_EQ(p.seq, 99u);  // untouched
  // Within the tolerance: taken, normalised.
  ASSERT_EQ(parseDevicePacket(orientedBytes(0x32444647, 1.0005f, 0.0f, 0.0f, 0.0f), p), PacketError::kNone);
  EXPECT_NEAR(p.orientation.norm(), 1.0, 1e-12);
}

// The link hands on the newest GFD2 orientation followed by the device's tilt, holds it while
// stale, keeps it through GFD1 packets of the same stream, and starts a new stream (after a
// dropout) from the tilt alone; a GFD1-only device is the identity.
TEST(DeviceLinkOrientation, TheSampleCarriesTheOrientationThenTheTilt) {
  UdpDeviceDesc d;
  d.stale_after = 0.05;
  d.tilt = about(Vec3::UnitX(), 30.0);
  DeviceLink link(d);
  EXPECT_LT(link.sample(0.0).orientation.angularDistance(d.tilt), 1e-12) << "before any packet: the tilt";
  const Quat yaw = about(Vec3::UnitY(), 40.0);
  link.take(packet(1, 0.0, &yaw), 0.0);
  EXPECT_LT(link.sample(0.0).orientation.angularDistance(yaw * d.tilt), 1e-6);
  link.take(packet(2, 0.001, nullptr), 0.001);  // GFD1 in the same stream: position only
  const Quat fresh = link.sample(0.001).orientation;
  EXPECT_LT(fresh.angularDistance(yaw * d.tilt), 1e-6);
  const Quat held = link.sample(0.1).orientation;
  EXPECT_TRUE(link.stale());
  EXPECT_EQ(held.coeffs(), fresh.coeffs()) << "held while stale";
  link.take(packet(3, 0.2, nullptr), 0.2);  // a new stream after the dropout, GFD1
  EXPECT_LT(link.sample(0.2).orientation.angularDistance(d.tilt), 1e-12);

  DeviceLink plain(UdpDeviceDesc{});
  plain.take(packet(1, 0.0, nullptr), 0.0);
  EXPECT_EQ(plain.sample(0.0).orientation.coeffs(), Quat::Identity().coeffs());
}

// Through the scene (tilt_deg about tilt_axis), the link and a World step: the World's device
// orientation is the packet's followed by the tilt.
TEST(DeviceLinkOrientation, TheOrientationReachesTheWorldsDevice) {
  const SessionDesc session = parseSceneText(
      "name = \"box\"\nduration = 1.0\neffects = [\"gravity\", \"friction\", \"god_finger\"]\n"
      "[bodies.ground]\nshape = \"plane\"\n"
      "[fingers.f]\nn_sgo = 8\n[fingers.f.device]\nudp = 0\nstart = [0, 0.2, 0]\n"
      "tilt_deg = 45\ntilt_axis = [0, 0, 1]\n",
      "box.toml", "");
  const UdpDeviceDesc& d = session.udp_devices.at(0);
  EXPECT_LT(d.tilt.angularDistance(about(Vec3::UnitZ(), 45.0)), 1e-12);
  EXPECT_TRUE(deviceGivesOrientation(session.scene.fingers[0])) << "a tilted UDP device is traced as 6-DOF";
  DeviceLink link(d);
  sim::World world(session.scene);
  std::vector<sim::DeviceSample> samples(1);
  const Quat pitch = about(Vec3::UnitX(), -20.0);
  for (long k = 0; k < 10; ++k) {
    const double t = static_cast<double>(k) * kHapticStep;
    link.take(packet(static_cast<std::uint32_t>(k + 1), t, &pitch), t);
    samples[0] = link.sample(t);
    world.step(kHapticStep, samples);
  }
  EXPECT_LT(world.deviceOrientation(0).angularDistance(pitch * d.tilt), 1e-6);
}

// trace.csv records a device's orientation (.dqw .dqx .dqy .dqz, last) only when its track turns:
// a 3-DOF scene's columns stay as they were.
TEST(DeviceTraceOrientation, OnlyASixDofDeviceAddsItsOrientationColumns) {
  const std::string scene =
      "name = \"s\"\nduration = 0.1\neffects = [\"gravity\"]\n[bodies.ground]\nshape = \"plane\"\n"
      "[fingers.a]\n[fingers.a.device]\nkeyframes = [{ t = 0, p = [0, 0.1, 0] }]\n"
      "[fingers.b]\n[fingers.b.device]\nkeyframes = [{ t = 0, p = [0.1, 0.1, 0], q = KEY_Q }]\n";
  const auto with = [&](const std::string& q) {
    std::string text = scene;
    text.replace(text.find("KEY_Q"), 5, q);
    return parseSceneText(text, "s.toml", "");
  };
  const std::vector<std::string> flat = traceColumns(with("[1, 0, 0, 0]").scene);
  EXPECT_EQ(flat.back(), "a+b.overlap_mm2") << "an identity q is a 3-DOF device: nothing after the fingers' overlap";
  const std::vector<std::string> turned = traceColumns(with("[0.7071, 0.7071, 0, 0]").scene);
  ASSERT_EQ(turned.size(), flat.size() + 4);
  EXPECT_EQ(std::vector<std::string>(turned.end() - 4, turned.end()),
            (std::vector<std::string>{"b.dqw", "b.dqx", "b.dqy", "b.dqz"}));
  EXPECT_TRUE(std::equal(flat.begin(), flat.end(), turned.begin())) << "the other columns do not move";
}

}  // namespace
}  // namespace gf::app
