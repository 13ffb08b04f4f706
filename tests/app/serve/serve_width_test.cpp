// The browser view's frames at the width a watcher shows them (`?width=`): the server's answer,
// the widest watcher's width for all, and the newest frame encoded again for a new width. The
// page's side is tests/browser/page_test.py; the shrinking itself tests/render/shrink_test.cpp.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "app/serve/live_view.hpp"
#include "app/serve/web_server.hpp"
#include "render/frames/jpeg_stream.hpp"
#include "tests/app/serve/served_view.hpp"

// After Eigen: httplib.h brings <resolv.h>, whose `_res` macro breaks Eigen's headers after it.
#include <httplib.h>

namespace gf::app {
namespace {

using served::FedView;
using served::out;
using served::portOf;
using served::serve;

// A baseline JPEG's width and height, from its SOF0 segment (0, 0 without one).
std::pair<int, int> jpegSize(const std::string& bytes) {
  for (std::size_t i = 0; i + 8 < bytes.size(); ++i) {
    if (static_cast<unsigned char>(bytes[i]) == 0xff && static_cast<unsigned char>(bytes[i + 1]) == 0xc0) {
      const auto byte = [&](std::size_t k) { return static_cast<int>(static_cast<unsigned char>(bytes[k])); };
      return {byte(i + 7) * 256 + byte(i + 8), byte(i + 5) * 256 + byte(i + 6)};
    }
  }
  return {0, 0};
}

// A watcher may ask for frames `width=` pixels across (the page asks for the width it shows them
// at): frames are shrunk to the widest any watcher waiting asks for, the frame's own when one asks
// for none; a width that is not a whole number within 16..4096 is refused.
TEST(Serve, FramesComeAtTheWidthAWatcherAsksFor) {
  FedView fed(out("gf_serve_width"));  // 64 x 36 frames
  std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1");
  httplib::Client client("127.0.0.1", portOf(*server));
  const auto size = [&](const std::string& path) {
    for (;;) {
      const auto res = client.Get(path);
      if (!res) return std::pair<int, int>{-1, -1};
      if (res->status == 429) continue;  // the address's burst used up: back within milliseconds
      if (res->status != 200) return std::pair<int, int>{res->status, 0};
      return jpegSize(res->body);
    }
  };
  // The first frame asked for at a width may be one encoded before the width was asked for.
  const auto settled = [&](const std::string& path, std::pair<int, int> want) {
    for (int k = 0; k < 20; ++k) {
      if (size(path) == want) return true;
    }
    return false;
  };
  EXPECT_TRUE(settled("/frame.jpg?width=32", {32, 18}));
  EXPECT_TRUE(settled("/frame.jpg?width=1000", {64, 36}));  // wider than the frame: as drawn
  EXPECT_TRUE(settled("/frame.jpg?width=32", {32, 18}));
  EXPECT_TRUE(settled("/frame.jpg", {64, 36}));  // no width: as drawn
  // Two watchers at once: the widest sets the frames' width. A stream showing them 40 wide
  // (factor 1) stays open while a frame is asked for at 20 (factor 3 alone: 22 x 12).
  std::atomic<bool> done{false};
  std::thread watcher([&] {
    httplib::Client other("127.0.0.1", portOf(*server));
    other.Get("/stream.mjpg?width=40", [&](const char*, std::size_t) { return !done.load(); });
  });
  while (server->statsJson()["streams_open"].get<long>() < 1) std::this_thread::yield();
  for (int k = 0; k < 5; ++k) EXPECT_EQ(size("/frame.jpg?width=20"), (std::pair<int, int>{64, 36})) << k;
  done.store(true);
  watcher.join();
  while (server->statsJson()["streams_open"].get<long>() > 0) std::this_thread::yield();
  EXPECT_TRUE(settled("/frame.jpg?width=20", {22, 12}));
  // (An empty `width=` is no width: the frame's own. A good one on /stream.mjpg would stream.)
  for (const char* bad : {"width=abc", "width=8", "width=5000", "width=32x", "width=-32", "width=+32"}) {
    const auto res = client.Get(std::string("/frame.jpg?") + bad);
    ASSERT_TRUE(res) << bad;
    EXPECT_EQ(res->status, 400) << bad;
    const auto stream = client.Get(std::string("/stream.mjpg?") + bad);
    ASSERT_TRUE(stream) << bad;
    EXPECT_EQ(stream->status, 400) << bad;
  }
}

// A new width with no newer frame drawn (a `live` session between commands): the newest frame
// is encoded again at it, so a page resized between steps gets the frame at its new width; a
// reader never gets a frame of another width than the one set.
TEST(Serve, ANewWidthEncodesTheNewestFrameAgain) {
  render::JpegStream stream;
  render::Image image{64, 36, std::vector<std::uint8_t>(64 * 36 * 3, 100)};
  stream.push(image, 1, 0.001, 1, 1);
  const auto frame = [&] {
    const render::JpegFrame f = stream.waitNewer(0, std::chrono::seconds(30));
    return std::make_tuple(f.number, jpegSize(std::string(f.bytes->begin(), f.bytes->end())), f.moves_taken);
  };
  EXPECT_EQ(frame(), std::make_tuple(1L, std::pair<int, int>{64, 36}, 1L));
  stream.setWidth(32);
  EXPECT_EQ(frame(), std::make_tuple(1L, std::pair<int, int>{32, 18}, 1L));
  stream.setWidth(21);  // 64 / 3 = 21.3: a third, 22 x 12 with the edge blocks
  EXPECT_EQ(frame(), std::make_tuple(1L, std::pair<int, int>{22, 12}, 1L));
  stream.setWidth(0);
  EXPECT_EQ(frame(), std::make_tuple(1L, std::pair<int, int>{64, 36}, 1L));
  stream.setWidth(40);  // the same factor, 1: nothing to encode again
  EXPECT_EQ(frame(), std::make_tuple(1L, std::pair<int, int>{64, 36}, 1L));
  EXPECT_EQ(stream.stats().encoded, 4);
  stream.setWidth(32);
  stream.push(image, 2, 0.002, 2, 2);  // a newer frame: encoded at the width set
  EXPECT_EQ(frame(), std::make_tuple(2L, std::pair<int, int>{32, 18}, 2L));
}

}  // namespace
}  // namespace gf::app
