// The browser view's server in-process, without GL: a LiveView fed frames by a thread standing in
// for the render thread, and the HTTP server in front of it, talked to over loopback with
// cpp-httplib's client. What the server promises: the token off loopback, bounded requests, a
// stream that drops frames for a slow reader and ends when the server stops, and commands
// answered as `live` answers them. The command parsing, the steered device and the scene's
// `web` devices are checked here too; the page in a browser is tests/browser/page_test.py.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/stat.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "app/scene/data_folder.hpp"
#include "app/scene/input_error.hpp"
#include "app/scene/scene_file.hpp"
#include "app/serve/live_view.hpp"
#include "app/device/steered_device.hpp"
#include "app/serve/web_server.hpp"
#include "app/live/live_command.hpp"
#include "app/session/session.hpp"
#include "render/frames/jpeg_stream.hpp"
#include "tests/app/run_helpers.hpp"
#include "tests/app/serve/served_view.hpp"
#include "tests/scratch.hpp"

// After Eigen: httplib.h brings <resolv.h>, whose `_res` macro breaks Eigen's headers after it.
#include <httplib.h>

namespace gf::app {
namespace {

namespace fs = std::filesystem;
using served::FedView;
using served::out;
using served::portOf;
using served::serve;

TEST(Serve, ParsesPortsAndHostsAndNamesTheOptionItRefuses) {
  EXPECT_EQ(parseServe("8080", "").host, "127.0.0.1");
  EXPECT_EQ(parseServe("8080", "").port, 8080);
  EXPECT_EQ(parseServe("localhost:0", "").host, "127.0.0.1");
  EXPECT_EQ(parseServe("0.0.0.0:9000", "abc").token, "abc");
  for (const char* bad : {"", "x", "70000", "1.2.3:80", "host:80", "80:", "-1"}) {
    try {
      parseServe(bad, "");
      ADD_FAILURE() << bad << " was taken";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--serve"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(parseServe("80", "a b"), InputError);
}

// Beyond loopback every request needs the token: one is made when none is given, and a request
// without it, or with another, gets 401 (the test talks to 127.0.0.1 only).
TEST(Serve, AServerBeyondLoopbackRefusesEveryRequestWithoutItsToken) {
  FedView fed(out("gf_serve_token"));
  std::unique_ptr<WebServer> server = serve(fed.view(), "0.0.0.0");
  EXPECT_TRUE(server->tokenGenerated());
  EXPECT_FALSE(server->loopback());
  const std::string url = server->url();
  const std::string token = url.substr(url.find("?token=") + 7);
  ASSERT_GE(token.size(), 32u);
  httplib::Client client("127.0.0.1", portOf(*server));
  for (const char* path : {"/", "/state.json", "/scene.json", "/frame.jpg", "/stream.mjpg", "/no-such-page"}) {
    EXPECT_EQ(client.Get(path)->status, 401) << path;
    EXPECT_EQ(client.Get(std::string(path) + "?token=wrong")->status, 401) << path;
  }
  EXPECT_EQ(client.Post("/command", "state", "text/plain")->status, 401);
  EXPECT_EQ(client.Get("/scene.json?token=" + token)->status, 200);
  EXPECT_EQ(client.Get("/", {{"Authorization", "Bearer " + token}})->status, 200);
  const auto answer = client.Post("/command?token=" + token, "move index 0 0.1 0", "text/plain");
  EXPECT_EQ(answer->body, "ok move index 0 0.1 0\n");
  EXPECT_GE(server->statsJson()["unauthorized"].get<long>(), 13);
}

// On loopback without a token, another site's page cannot use the visitor's browser: a request
// naming another host (DNS rebinding) or sent from another origin is refused.
TEST(Serve, ALoopbackServerRefusesOtherSitesPages) {
  FedView fed(out("gf_serve_csrf"));
  std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1");
  const int port = portOf(*server);
  httplib::Client client("127.0.0.1", port);
  EXPECT_EQ(client.Get("/scene.json")->status, 200);
  EXPECT_EQ(client.Get("/scene.json", {{"Host", "localhost:" + std::to_string(port)}})->status, 200);
  EXPECT_EQ(client.Get("/scene.json", {{"Host", "evil.example:" + std::to_string(port)}})->status, 403);
  const std::string own = "http://127.0.0.1:" + std::to_string(port);
  EXPECT_EQ(client.Post("/command", {{"Origin", own}}, "state", "text/plain")->status, 200);
  EXPECT_EQ(client.Post("/command", {{"Origin", "http://evil.example"}}, "record start", "text/plain")->status, 403);
  EXPECT_EQ(server->statsJson()["foreign"].get<long>(), 2);
}

// A reader gets the newest frame drawn, never a backlog: frames pushed while nobody waits are not
// encoded, the newest of them is kept, and the next reader gets it at once.
TEST(Serve, AReaderGetsTheNewestFrameDrawnNeverABacklog) {
  render::JpegStream stream;
  const render::Image image{16, 16, std::vector<std::uint8_t>(16 * 16 * 3, 100)};
  stream.push(image, 1, 0.001);  // the first frame is encoded whoever waits
  EXPECT_EQ(stream.waitNewer(0, std::chrono::seconds(30)).number, 1);
  for (long k = 2; k <= 10; ++k) stream.push(image, k, 0.001 * static_cast<double>(k), k / 2, k / 3);  // nobody waits
  EXPECT_EQ(stream.stats().encoded, 1) << "frames were encoded while nobody watched";
  const render::JpegFrame newest = stream.waitNewer(0, std::chrono::seconds(30));
  EXPECT_EQ(newest.number, 10) << "a newcomer was not given the frame drawn last";
  EXPECT_DOUBLE_EQ(newest.time, 0.010);
  EXPECT_EQ(newest.moves_taken, 5) << "the frame's move marks did not come with it";
  EXPECT_EQ(newest.moves_arrived, 3);
  long got = 0;
  std::thread reader([&] { got = stream.waitNewer(10, std::chrono::seconds(30)).number; });
  while (stream.waiting() == 0) std::this_thread::yield();
  stream.push(image, 11, 0.011);
  reader.join();
  EXPECT_EQ(got, 11);
  EXPECT_EQ(stream.stats().encoded, 3) << "frames 2..9 were encoded for nobody";
  EXPECT_EQ(stream.stats().pushed, 11);
}

// A port in use is an error naming it, not a port shared with the other server.
TEST(Serve, APortInUseIsRefused) {
  FedView fed(out("gf_serve_port"));
  std::unique_ptr<WebServer> first = serve(fed.view(), "127.0.0.1");
  ServeOptions again;
  again.port = portOf(*first);
  try {
    WebServer second(again, fed.view(), [](const std::string&) { return std::string("ok"); });
    ADD_FAILURE() << "a second server listens on port " << again.port;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot listen on 127.0.0.1:" + std::to_string(again.port)), std::string::npos)
        << e.what();
  }
}

// The page is one document: nothing from disk or the network (no src= or href= of another host).
TEST(Serve, ThePageIsSelfContained) {
  const std::string& page = webPage();
  EXPECT_NE(page.find("<img id=\"frame\""), std::string::npos);
  for (const char* outside : {"http://", "https://", "src=\"/", "<link ", "import "}) {
    EXPECT_EQ(page.find(outside), std::string::npos) << outside;
  }
  FedView fed(out("gf_serve_page"));
  std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1");
  httplib::Client client("127.0.0.1", portOf(*server));
  const auto res = client.Get("/");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(res->body, page);
  EXPECT_EQ(client.Get("/etc/passwd")->status, 404);
  EXPECT_EQ(client.Get("/../CMakeLists.txt")->status, 404);
}

// Requests are bounded: a body over HttpLimits::body_bytes is refused, one command per request.
TEST(Serve, RequestsAreBoundedInSize) {
  FedView fed(out("gf_serve_bounds"));
  std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1");
  httplib::Client client("127.0.0.1", portOf(*server));
  EXPECT_EQ(client.Post("/command", std::string(HttpLimits{}.body_bytes + 1, 'x'), "text/plain")->status, 413);
  EXPECT_EQ(client.Post("/command", "state\nstate\n", "text/plain")->status, 400);
  EXPECT_EQ(client.Post("/command", "state\n", "text/plain")->status, 200);
}

// Each client address gets kRequestBurst requests at once, then kRequestsPerSecond; the others
// keep their own.
TEST(Serve, RequestsAreBoundedInRatePerClient) {
  RequestRate rate;
  const RequestRate::Clock::time_point t0{};
  int taken = 0;
  for (int i = 0; i < static_cast<int>(kRequestBurst) + 10; ++i) taken += rate.allow("a", t0);
  EXPECT_EQ(taken, static_cast<int>(kRequestBurst));
  EXPECT_TRUE(rate.allow("b", t0)) << "another client has its own bucket";
  const auto later = t0 + std::chrono::milliseconds(100);  // 30 tokens back at 300 a second
  taken = 0;
  for (int i = 0; i < 100; ++i) taken += rate.allow("a", later);
  EXPECT_EQ(taken, static_cast<int>(kRequestsPerSecond * 0.1));
  const auto much_later = t0 + std::chrono::seconds(100);  // refilled to the burst, not beyond
  taken = 0;
  for (int i = 0; i < 2 * static_cast<int>(kRequestBurst); ++i) taken += rate.allow("a", much_later);
  EXPECT_EQ(taken, static_cast<int>(kRequestBurst));
}

// Reads `parts` JPEG parts of /stream.mjpg; returns their X-Frame numbers.
std::vector<long> readStream(httplib::Client& client, int parts) {
  std::vector<long> frames;
  std::string buffer;
  client.Get("/stream.mjpg", [&](const char* data, std::size_t n) {
    buffer.append(data, n);
    for (std::size_t at; (at = buffer.find("X-Frame: ")) != std::string::npos;) {
      const std::size_t end = buffer.find("\r\n", at);
      if (end == std::string::npos) break;
      frames.push_back(std::stol(buffer.substr(at + 9, end - at - 9)));
      buffer.erase(0, end);
    }
    return static_cast<int>(frames.size()) < parts;  // false: the client hangs up mid-stream
  });
  return frames;
}

// The stream sends each frame once, newest first; at most HttpLimits::streams_per_address from
// one address at once, and a client that hangs up mid-stream gives its place back.
TEST(Serve, StreamsSendNewerFramesAndFreeTheirPlaceWhenTheClientLeaves) {
  FedView fed(out("gf_serve_stream"));
  std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1");
  const int kMaxStreams = HttpLimits{}.streams_per_address;
  for (int round = 0; round < 3; ++round) {  // more clients than places, one after the other
    std::vector<std::thread> readers;
    std::vector<std::vector<long>> got(kMaxStreams);
    for (int i = 0; i < kMaxStreams; ++i) {
      readers.emplace_back([&, i] {
        httplib::Client client("127.0.0.1", portOf(*server));
        got[static_cast<std::size_t>(i)] = readStream(client, 3);
      });
    }
    for (std::thread& t : readers) t.join();
    // The server sees each hang-up at its next write, then gives the place back.
    while (server->statsJson()["streams_open"].get<int>() > 0) std::this_thread::yield();
    for (const std::vector<long>& frames : got) {
      ASSERT_GE(frames.size(), 3u);  // a chunk may carry more than the parts asked for
      for (std::size_t k = 1; k < frames.size(); ++k) EXPECT_LT(frames[k - 1], frames[k]);
    }
  }
  EXPECT_EQ(server->statsJson()["streams_refused"].get<long>(), 0);
}

// Stopping the server ends open streams at once: stop() returns, and so do the readers. One more
// stream from the same address than its cap is refused with 429.
TEST(Serve, StoppingTheServerEndsOpenStreams) {
  const int kMaxStreams = HttpLimits{}.streams_per_address;
  FedView fed(out("gf_serve_stop"));
  std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1");
  const int port = portOf(*server);
  std::atomic<int> streaming{0};  // readers whose stream has sent them a part: each holds a place
  std::vector<std::thread> readers;
  for (int i = 0; i < kMaxStreams; ++i) {
    readers.emplace_back([&] {
      httplib::Client client("127.0.0.1", port);
      bool first = true;
      client.Get("/stream.mjpg", [&](const char*, std::size_t) {
        if (first) ++streaming;
        first = false;
        return true;  // never hangs up on its own
      });
    });
  }
  httplib::Client extra("127.0.0.1", port);
  // Every reader, not just some, streams before the extra asks: a reader still connecting could
  // otherwise leave its place to the extra.
  while (streaming.load() < kMaxStreams) {
    std::this_thread::yield();
  }
  // Every place is taken (the readers above run until the server stops).
  const auto refused = extra.Get("/stream.mjpg");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 429);
  server->stop();
  for (std::thread& t : readers) t.join();
  EXPECT_FALSE(extra.Get("/scene.json")) << "the server no longer listens";
}

// Recording writes the frames drawn from `record start` to `record stop` as PNGs, numbered on.
TEST(Serve, RecordingWritesTheFramesBetweenStartAndStop) {
  const std::string dir = out("gf_serve_record");
  {
    FedView fed(dir);
    EXPECT_EQ(fed.view().record(true).rfind("ok recording frames to ", 0), 0u);
    while (fed.view().statsJson()["frames_recorded"].get<long>() < 5) std::this_thread::yield();
    EXPECT_EQ(fed.view().record(false).rfind("ok recording stopped: ", 0), 0u);
    fed.view().finish();
  }
  long pngs = 0;
  for (const auto& e : fs::directory_iterator(fs::path(dir) / "frames")) pngs += e.path().extension() == ".png";
  EXPECT_GE(pngs, 5);
  EXPECT_TRUE(fs::exists(fs::path(dir) / "frames" / "000000.png"));
}

// A steered device follows its track until the first move, then goes straight to each target
// over the time given, from where it was.
TEST(Serve, ASteeredDeviceGoesStraightToEachTargetFromWhereItIs) {
  sim::DeviceTrack track;
  track.keyframes = {{0.0, sim::Vec3(0, 0.1, 0)}, {1.0, sim::Vec3(0.1, 0.1, 0)}};
  track.interpolation = sim::Interpolation::kLinear;
  SteeredDevice d(track, true);
  EXPECT_NEAR(d.sample(0.5).position.x(), 0.05, 1e-12);
  d.moveTo(sim::Vec3(0.05, 0.0, 0.0), 0.1);
  const sim::DeviceSample at_start = d.sample(0.6);  // taken now, from where its track is: (0.06, 0.1, 0)
  EXPECT_NEAR((at_start.position - sim::Vec3(0.06, 0.1, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((at_start.velocity - sim::Vec3(-0.1, -1.0, 0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(d.sample(0.65).position.y(), 0.05, 1e-12);
  EXPECT_NEAR((d.sample(0.8).position - sim::Vec3(0.05, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(d.sample(0.8).velocity, sim::Vec3::Zero());
  d.moveTo(sim::Vec3(0, 0, 0), 0.0);
  EXPECT_EQ(d.sample(0.801).position, sim::Vec3::Zero());
  EXPECT_EQ(d.moves(), 2);
}

// A move counts once when taken and once when its device reaches the target (at once for 0 s):
// the steps whose state is published at once as a viewer's input (ServedRun::afterStep, RenderThread::publishLatest).
TEST(Serve, ASteeredDeviceCountsEachMoveTakenAndArrived) {
  sim::DeviceTrack track;
  track.keyframes = {{0.0, sim::Vec3(0, 0.1, 0)}};
  SteeredDevice d(track, true);
  d.sample(0.1);
  EXPECT_EQ(d.moves(), 0);
  EXPECT_EQ(d.arrivals(), 0);
  d.moveTo(sim::Vec3(0.05, 0.1, 0.0), 0.03);
  d.sample(0.2);
  EXPECT_EQ(d.moves(), 1);
  EXPECT_EQ(d.arrivals(), 0);  // gliding
  d.sample(0.229);
  EXPECT_EQ(d.arrivals(), 0);
  d.sample(0.23);
  EXPECT_EQ(d.arrivals(), 1);  // there
  d.sample(0.5);
  EXPECT_EQ(d.arrivals(), 1);  // once
  d.moveTo(sim::Vec3(0.0, 0.1, 0.0), 0.0);
  d.sample(0.6);
  EXPECT_EQ(d.moves(), 2);
  EXPECT_EQ(d.arrivals(), 2);
}

// The marks a frame carries to the page (moveMarks): moves numbered across two fingers' devices;
// a move counts as taken (reached) only when it and every earlier one are, whichever finger made it; a
// move posted over one not yet taken counts as taken with it, and a move replaced (before or
// during its glide) as reached with the one that replaced it.
TEST(Serve, MoveMarksSayWhichNumberedMovesAStateHasTakenAndReached) {
  sim::DeviceTrack track;
  track.keyframes = {{0.0, sim::Vec3(0, 0.1, 0)}};
  std::vector<std::unique_ptr<SteeredDevice>> d;
  d.push_back(std::make_unique<SteeredDevice>(track, true));
  d.push_back(std::make_unique<SteeredDevice>(track, true));
  const auto marks = [&] { const MoveMarks m = moveMarks(d); return std::pair(m.taken, m.arrived); };
  const auto step = [&](double t) { for (auto& x : d) x->sample(t); };
  step(0.1);
  EXPECT_EQ(marks(), std::pair(0L, 0L));  // nothing moved yet
  d[0]->moveTo(sim::Vec3(0.05, 0.1, 0.0), 0.03, 1);
  EXPECT_EQ(marks(), std::pair(0L, 0L));  // posted, not yet taken
  step(0.2);
  EXPECT_EQ(marks(), std::pair(1L, 0L));  // taken, gliding
  d[1]->moveTo(sim::Vec3(0.0, 0.1, 0.05), 0.0, 2);
  step(0.21);
  EXPECT_EQ(marks(), std::pair(2L, 0L));  // 2 is there at once, but 1 still glides
  step(0.23);
  EXPECT_EQ(marks(), std::pair(2L, 2L));  // both there
  d[0]->moveTo(sim::Vec3(0.01, 0.1, 0.0), 0.05, 3);
  d[1]->sample(0.25);  // a step in which only the other finger's device is sampled (or takes a move)
  EXPECT_EQ(marks(), std::pair(2L, 2L));  // 3 posted, not taken
  d[0]->moveTo(sim::Vec3(0.02, 0.1, 0.0), 0.05, 4);  // replaces 3 before a step takes it
  step(0.3);
  EXPECT_EQ(marks(), std::pair(4L, 2L));
  d[0]->moveTo(sim::Vec3(0.03, 0.1, 0.0), 0.05, 5);
  step(0.32);  // 4 cut short by 5: it is not reached until 5 is
  EXPECT_EQ(marks(), std::pair(5L, 2L));
  step(0.4);
  EXPECT_EQ(marks(), std::pair(5L, 5L));
  d[0]->moveTo(sim::Vec3(0.0, 0.1, 0.0), 0.05, 6);
  d[1]->moveTo(sim::Vec3(0.0, 0.1, 0.0), 0.0, 7);
  d[1]->sample(0.45);  // 7 taken and there before 6 is taken
  EXPECT_EQ(marks(), std::pair(5L, 5L));
  step(0.46);
  EXPECT_EQ(marks(), std::pair(7L, 5L));
  EXPECT_EQ(d[0]->moves(), 4);  // 1, 4, 5 and 6: 3 was never sampled
}

// A steered device keeps its track's orientation (a web device's tilt): the moves are positions.
TEST(Serve, ASteeredDeviceKeepsItsTracksOrientation) {
  const sim::Quat tilt(Eigen::AngleAxisd(0.5, sim::Vec3::UnitX()));
  sim::DeviceTrack track;
  track.keyframes = {{0.0, sim::Vec3(0, 0.1, 0), tilt}};
  SteeredDevice d(track, true);
  EXPECT_EQ(d.sample(0.1).orientation.coeffs(), tilt.coeffs());
  d.moveTo(sim::Vec3(0.05, 0.0, 0.0), 0.1);
  EXPECT_EQ(d.sample(0.15).orientation.coeffs(), tilt.coeffs());
  EXPECT_EQ(d.sample(0.5).orientation.coeffs(), tilt.coeffs());
}

// The live protocol's lines: each checked whole, with the error's words.
TEST(Serve, LiveCommandsAreCheckedWhole) {
  const SessionDesc s = loadSceneFile(resolveScenePath("live-view"));
  using K = LiveCommand::Kind;
  EXPECT_EQ(parseLiveCommand("record start", s.scene).kind, K::kRecord);
  EXPECT_FALSE(parseLiveCommand("record stop", s.scene).on);
  EXPECT_EQ(parseLiveCommand("  # a comment", s.scene).kind, K::kNone);
  const LiveCommand m = parseLiveCommand("move thumb 0 0.1 0.02 0.5", s.scene);
  EXPECT_EQ(m.finger, 1);
  EXPECT_EQ(m.seconds, 0.5);
  const auto error = [&](const std::string& line) {
    try {
      parseLiveCommand(line, s.scene);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("taken");
  };
  EXPECT_EQ(error("record pause"), "record: expected start or stop, got 'pause'");
  EXPECT_EQ(error("move index 0 0 2000"), "move: each coordinate must be within ±1000.000000 m");
  EXPECT_EQ(error("move index 0 0 0 -1"), "move: SECONDS must be in 0..1e6");
  EXPECT_EQ(error("snapshot .."), "snapshot: NAME must not contain '/'");
  EXPECT_NE(error("set fingers.index.n_sgo=1000").find("fingers.index.n_sgo"), std::string::npos);
  EXPECT_EQ(error("set fingers.pinky.n_sgo=4"), "no finger called 'pinky'");
}

// `web = true` is a device of its own: alone, true, with `start` only; a run needs --serve to
// follow it (without, it warns and the finger stays), and --serve needs --realtime.
TEST(Serve, AWebDeviceIsCheckedInTheSceneAndTheRunSaysWhatItNeeds) {
  const std::string base = std::string(GF_SOURCE_DIR) + "/assets/scenes/live-view.toml";
  const SessionDesc s = loadSceneFile(base);
  ASSERT_EQ(s.web_devices.size(), 2u);
  EXPECT_EQ(s.scene.fingers[static_cast<std::size_t>(s.web_devices[0].finger)].device.sample(3.0).position,
            sim::Vec3(-0.1, 0.11, 0.0));
  const auto refused = [&](const std::string& set) {
    try {
      loadSceneFile(base, std::vector<std::string>{set});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("taken");
  };
  EXPECT_NE(refused("fingers.index.device.web=false").find("expected true"), std::string::npos);
  EXPECT_NE(refused("fingers.index.device.channel=1").find("belongs to a UDP device"), std::string::npos);
  EXPECT_NE(refused("fingers.index.device.udp=0").find("give exactly one of keyframes, csv, udp and web"),
            std::string::npos);
  SessionOptions o;
  o.out_dir = out("gf_serve_needs_realtime");
  o.progress = false;
  o.serve = parseServe("0", "");
  try {
    runSession(s, o);
    ADD_FAILURE() << "--serve without --realtime ran";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--realtime"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(fs::path(o.out_dir) / "summary.json")) << "refused before anything is written";
}

// Polls frames and the state until the state's time is past `t` (each look after a new frame; a
// 429, polled faster than the server takes, is asked again).
void waitForStateAfter(httplib::Client& client, double t) {
  for (;;) {
    client.Get("/frame.jpg");
    const auto state = client.Get("/state.json");
    ASSERT_TRUE(state);
    if (state->status == 429) continue;
    const nlohmann::json j = nlohmann::json::parse(state->body);
    if (j.contains("t") && j["t"].get<double>() > t) return;
  }
}

// The answer to `command`, sent again while refused with 429 (an address's burst of requests
// used up: it is back within milliseconds).
std::string postCommand(httplib::Client& client, const char* command) {
  for (;;) {
    const auto res = client.Post("/command", command, "text/plain");
    if (!res) return "no answer";
    if (res->status != 429) return res->body;
  }
}

// Waits until the server runs at least `n` commands (/server.json's commands_running).
bool commandsRunning(httplib::Client& client, long n) {
  for (;;) {
    const auto stats = client.Get("/server.json");
    if (!stats) return false;
    if (stats->status == 429) continue;
    if (nlohmann::json::parse(stats->body)["commands_running"].get<long>() >= n) return true;
  }
}

// `live --serve`: the page's commands and standard input's run in turn on one session; `quit`
// comes only from standard input; the end of input does not end the session, Ctrl-C does.
TEST(Serve, LiveTakesThePagesCommandsInTurnWithStandardInput) {
  const fs::path dir = out("gf_serve_live");
  fs::create_directories(dir);
  const fs::path fifo = dir / "stdin";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  // Both of its outputs come back on the pipe (stdout to /dev/stderr, which is the pipe).
  test::Child child = test::start(test::kBin + " live live-view --serve 127.0.0.1:0 --out " + (dir / "out").string() +
                                      " < " + fifo.string(),
                                  "/dev/stderr");
  test::KillGroupOnExit guard{child.pid};
  std::FILE* input = std::fopen(fifo.c_str(), "w");  // opens once the child's shell opens it
  ASSERT_NE(input, nullptr);
  const std::string ready = test::lineWith(child.lines, "ok ready, serving http://127.0.0.1:");
  ASSERT_FALSE(ready.empty());
  const int port = std::stoi(ready.substr(ready.find("127.0.0.1:") + 10));
  httplib::Client client("127.0.0.1", port);
  const auto stepped = client.Post("/command", "step 100", "text/plain");
  ASSERT_TRUE(stepped);
  EXPECT_EQ(stepped->status, 200);
  EXPECT_NE(stepped->body.find("\"t\":0.1"), std::string::npos) << stepped->body;
  // The step is drawn before it is answered: a newcomer's frame is of t = 0.1 s.
  const auto frame = client.Get("/frame.jpg");
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->get_header_value("X-Sim-Time"), "0.1000");
  const auto quit = client.Post("/command", "quit", "text/plain");
  EXPECT_EQ(quit->status, 400);
  EXPECT_EQ(quit->body.rfind("error: quit: only on the session's standard input", 0), 0u) << quit->body;
  EXPECT_EQ(client.Post("/command", "\rquit", "text/plain")->status, 400) << "any whitespace before it";
  std::fputs("step 50\n", input);
  std::fflush(input);
  const std::string answer = test::lineWith(child.lines, "ok {");
  EXPECT_NE(answer.find("\"t\":0.15"), std::string::npos) << "stdin's step follows the page's: " << answer;
  // A frame of t = 0.15 s is drawn and its state served (each look after a new frame: the
  // address's burst of requests is kept for the commands below).
  ASSERT_NO_FATAL_FAILURE(waitForStateAfter(client, 0.149));
  std::fclose(input);  // end of input: the session goes on for the page
  EXPECT_FALSE(test::lineWith(child.lines, "ok input ended; serving until Ctrl-C").empty());
  // The polling above may have used this address's burst of requests: a refused (429) command
  // was not taken and is sent again; it is back within milliseconds.
  EXPECT_EQ(postCommand(client, "state").rfind("ok {", 0), 0u);
  // Ctrl-C while the page has a long step running and another command waiting: the step stops,
  // both are answered, and the session ends (it used to wait for ever on the waiting one). Each
  // is sent once the server has taken the one before (/server.json's commands_running).
  std::string long_step, waiting;
  std::thread first([&] {
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(120, 0);
    long_step = postCommand(c, "step 10000000");
  });
  const bool one = commandsRunning(client, 1);
  std::thread second([&] {
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(120, 0);
    waiting = postCommand(c, "state");
  });
  const bool both = one && commandsRunning(client, 2);
  kill(-child.pid, SIGINT);
  first.join();
  second.join();
  const test::Ended ended = test::finishLines(child);
  guard.done = true;
  EXPECT_TRUE(both);
  EXPECT_EQ(ended.status, 130);
  // Each is answered: run (the step stopped at the signal) or refused as the session ended.
  for (const std::string& a : {long_step, waiting}) {
    EXPECT_TRUE(a.rfind("ok {", 0) == 0 || a.rfind("error: the session has ended", 0) == 0) << a;
  }
}

}  // namespace
}  // namespace gf::app
