// The server under the attacks a session of an hour meets, each bounded in count: bodies too
// large whatever their framing, heads too large, requests that never finish arriving, idle
// connections by the hundred, streams by the dozen, malformed framing, a flood of commands. In
// each, the attacker (raw sockets from 127.0.0.2, another loopback address) gets a 4xx answer
// and an authorised client (127.0.0.1) is still answered. Deadlines are shortened
// (HttpLimits::request_time 300 ms) so the attacks end quickly; nothing here measures time.
// docs/browser-view.md has the same attacks against a running session, with times and memory.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <future>
#include <string>
#include <vector>

#include "tests/app/serve/served_view.hpp"

// After Eigen: httplib.h brings <resolv.h>, whose `_res` macro breaks Eigen's headers after it.
#include <httplib.h>

namespace gf::app {
namespace {

using served::FedView;
using served::out;
using served::portOf;
using served::serve;

// A TCP connection to 127.0.0.1:`port` from `source`, written and read raw. Reads wait at most
// 60 s (a guard against a hang, not a measure).
class RawClient {
 public:
  RawClient(int port, const char* source = "127.0.0.2") : fd_(socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in from{};
    from.sin_family = AF_INET;
    inet_pton(AF_INET, source, &from.sin_addr);
    bind(fd_, reinterpret_cast<sockaddr*>(&from), sizeof from);
    const timeval guard{60, 0};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &guard, sizeof guard);
    setsockopt(fd_, SOL_SOCKET, SO_SNDTIMEO, &guard, sizeof guard);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(static_cast<std::uint16_t>(port));
    inet_pton(AF_INET, "127.0.0.1", &to.sin_addr);
    connected_ = connect(fd_, reinterpret_cast<sockaddr*>(&to), sizeof to) == 0;
  }
  ~RawClient() { close(fd_); }
  RawClient(const RawClient&) = delete;
  RawClient& operator=(const RawClient&) = delete;

  bool connected() const { return connected_; }
  /// False once the server has stopped taking bytes (it answered and closed).
  bool send(const std::string& bytes) {
    return ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size());
  }
  /// Everything the server sends until it closes (or `most` bytes).
  std::string readAll(std::size_t most = 1 << 16) {
    std::string got;
    char buffer[4096];
    for (ssize_t n; got.size() < most && (n = recv(fd_, buffer, sizeof buffer, 0)) > 0;) got.append(buffer, static_cast<std::size_t>(n));
    return got;
  }
  /// The status of the answer's first line (0: none).
  int status() { return statusOf(readAll()); }
  static int statusOf(const std::string& answer) {
    return answer.rfind("HTTP/1.1 ", 0) == 0 ? std::atoi(answer.c_str() + 9) : 0;
  }

 private:
  int fd_;
  bool connected_ = false;
};

HttpLimits shortLimits() {
  HttpLimits l;
  l.request_time = std::chrono::milliseconds(300);
  return l;
}

std::string head(int port, const std::string& line, const std::string& fields = "") {
  return line + "\r\nHost: 127.0.0.1:" + std::to_string(port) + "\r\n" + fields + "\r\n";
}

// The authorised client's check: /state.json answered 200 with the newest state (a JSON object).
void expectStateAnswered(int port, const std::string& token = "") {
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(60, 0);
  const auto res = client.Get(token.empty() ? "/state.json" : "/state.json?token=" + token);
  ASSERT_TRUE(res) << "the authorised client got no answer";
  EXPECT_EQ(res->status, 200);
  EXPECT_TRUE(nlohmann::json::parse(res->body).is_object());
}

// A chunked body is held to body_bytes like any other: 413 after the limit, never echoed, the
// rest never read.
TEST(ServeLoad, AChunkedBodyOverTheLimitIsRefusedUnread) {
  FedView fed(out("gf_serve_load_chunked"));
  std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1", "", shortLimits());
  const int port = portOf(*server);
  RawClient attacker(port);
  ASSERT_TRUE(attacker.send(head(port, "POST /command HTTP/1.1", "Transfer-Encoding: chunked\r\n")));
  const std::string chunk = "1000\r\n" + std::string(4096, 'x') + "\r\n";
  int sent = 0;
  while (sent < 256 && attacker.send(chunk)) ++sent;  // 1 MB at most; the server stops taking it
  expectStateAnswered(port);
  const std::string answer = attacker.readAll();
  EXPECT_EQ(RawClient::statusOf(answer), 413) << answer.substr(0, 200);
  EXPECT_EQ(answer.find("xxxx"), std::string::npos) << "the body was echoed back";
  EXPECT_LT(answer.size(), 400u);
  EXPECT_GE(server->statsJson()["too_large"].get<long>(), 1);
}

// Heads are bounded in bytes and in fields: 431, for a long field and for many short ones, and
// on a token server before the token is looked at.
TEST(ServeLoad, HeadsOverTheLimitsAreRefused) {
  FedView fed(out("gf_serve_load_heads"));
  std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1", "secret", shortLimits());
  const int port = portOf(*server);
  std::string many;
  for (int i = 0; i < 100; ++i) many += "X-F" + std::to_string(i) + ": 1\r\n";
  const std::vector<std::string> fields = {"X-Long: " + std::string(1 << 20, 'a') + "\r\n", many};
  for (const std::string& f : fields) {
    RawClient attacker(port);
    attacker.send(head(port, "GET /state.json HTTP/1.1", f));
    EXPECT_EQ(attacker.status(), 431);
  }
  expectStateAnswered(port, "secret");
  EXPECT_EQ(server->statsJson()["too_large"].get<long>(), 2);
}

// Without its token a request is refused at its head: a large body is never read (401, or 413
// when its Content-Length alone is over the limit).
TEST(ServeLoad, ATokenServerRefusesBeforeReadingABody) {
  FedView fed(out("gf_serve_load_token"));
  std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1", "secret", shortLimits());
  const int port = portOf(*server);
  for (const char* length : {"100", "52428800"}) {
    RawClient attacker(port);
    attacker.send(head(port, "POST /command HTTP/1.1", std::string("Content-Length: ") + length + "\r\n"));
    const int status = attacker.status();
    EXPECT_TRUE(status == 401 || status == 413) << length << ": " << status;
  }
  expectStateAnswered(port, "secret");
  EXPECT_GE(server->statsJson()["unauthorized"].get<long>(), 1);
}

// Requests that never finish arriving (slowloris) hold no one up and end with 408 when their
// time is up, on an open server and on a token server alike.
TEST(ServeLoad, RequestsThatNeverFinishArrivingEndWith408) {
  for (const std::string token : {"", "secret"}) {
    FedView fed(out("gf_serve_load_slow"));
    std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1", token, shortLimits());
    const int port = portOf(*server);
    std::vector<std::unique_ptr<RawClient>> slow;
    for (int i = 0; i < 8; ++i) {
      slow.push_back(std::make_unique<RawClient>(port));
      slow.back()->send("GET /state.json HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) + "\r\nX-Wait: ");
    }
    expectStateAnswered(port, token);
    for (auto& c : slow) EXPECT_EQ(c->status(), 408);
    EXPECT_EQ(server->statsJson()["timed_out"].get<long>(), 8);
  }
}

// Hundreds of idle connections from one address: past its cap the oldest idle one gives way
// (408) or the newcomer is refused (429); every one gets a 4xx, and a client of another address
// is answered at once.
TEST(ServeLoad, IdleConnectionsByTheHundredStarveNoOne) {
  FedView fed(out("gf_serve_load_idle"));
  std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1", "", shortLimits());
  const int port = portOf(*server);
  std::vector<std::unique_ptr<RawClient>> idle;
  for (int i = 0; i < 300; ++i) idle.push_back(std::make_unique<RawClient>(port));
  for (int i = 0; i < 3; ++i) expectStateAnswered(port);
  int refused = 0;
  for (auto& c : idle) {
    const int status = c->status();
    EXPECT_TRUE(status == 408 || status == 429) << status;
    refused += status == 408 || status == 429;
  }
  EXPECT_EQ(refused, 300);
  const nlohmann::json stats = server->statsJson();
  EXPECT_GT(stats["connections_evicted"].get<long>() + stats["connections_refused"].get<long>(), 0);
}

// Streams by the dozen from one address: two are served, the rest get 429; a client of another
// address still gets its stream and its state.
TEST(ServeLoad, StreamsByTheDozenLeaveRoomForThePage) {
  FedView fed(out("gf_serve_load_streams"));
  std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1", "", shortLimits());
  const int port = portOf(*server);
  std::vector<std::unique_ptr<RawClient>> streams;
  int ok = 0, refused = 0;
  for (int i = 0; i < 24; ++i) {
    streams.push_back(std::make_unique<RawClient>(port));
    streams.back()->send(head(port, "GET /stream.mjpg HTTP/1.1"));
  }
  for (auto& c : streams) {
    const std::string answer = c->readAll(512);  // a stream's head and first part, or a refusal
    const int status = RawClient::statusOf(answer);
    ok += status == 200;
    refused += status == 429;
  }
  EXPECT_EQ(ok, HttpLimits{}.streams_per_address);
  EXPECT_EQ(refused, 24 - ok);
  RawClient page(port, "127.0.0.1");
  page.send(head(port, "GET /stream.mjpg HTTP/1.1"));
  const std::string answer = page.readAll(512);
  EXPECT_EQ(RawClient::statusOf(answer), 200);
  EXPECT_NE(answer.find("Content-Type: image/jpeg"), std::string::npos) << "no frame on the page's stream";
  expectStateAnswered(port);
}

// Framing is strict: a Content-Length not a number, given twice, beside chunked, or a bare CR
// is 400; nothing of such a request reaches a route.
TEST(ServeLoad, MalformedFramingIsRefused) {
  FedView fed(out("gf_serve_load_framing"));
  std::unique_ptr<WebServer> server = serve(fed.view(), "127.0.0.1", "", shortLimits());
  const int port = portOf(*server);
  const std::string host = "Host: 127.0.0.1:" + std::to_string(port) + "\r\n";
  const std::vector<std::string> bad = {
      "POST /command HTTP/1.1\r\n" + host + "Content-Length: abc\r\n\r\nstate",
      "POST /command HTTP/1.1\r\n" + host + "Content-Length: 5\r\nContent-Length: 5\r\n\r\nstate",
      "POST /command HTTP/1.1\r\n" + host + "Content-Length: 5, 5\r\n\r\nstate",
      "POST /command HTTP/1.1\r\n" + host + "Content-Length: 5\r\nTransfer-Encoding: chunked\r\n\r\nstate",
      "GET /state.json HTTP/1.1\r\n" + host + "X-A: 1\rX-B: 2\r\n\r\n",
  };
  for (const std::string& request : bad) {
    RawClient attacker(port);
    attacker.send(request);
    EXPECT_EQ(attacker.status(), 400) << request;
  }
  EXPECT_EQ(server->statsJson()["commands"].get<long>(), 0) << "a malformed request reached /command";
  expectStateAnswered(port);
}

// Commands are answered in turn on a thread of their own: while one runs, the state is answered,
// and past kMaxCommandsWaiting the next is refused with 429.
TEST(ServeLoad, AFloodOfCommandsIsBounded) {
  FedView fed(out("gf_serve_load_commands"));
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  ServeOptions o;
  o.limits = shortLimits();
  WebServer server(o, fed.view(), [released](const std::string& line) {
    released.wait();
    return "ok " + line;
  });
  const int port = portOf(server);
  std::vector<std::unique_ptr<RawClient>> posts;
  for (int i = 0; i < kMaxCommandsWaiting + 4; ++i) {
    posts.push_back(std::make_unique<RawClient>(port, "127.0.0.3"));
    posts.back()->send(head(port, "POST /command HTTP/1.1", "Content-Length: 5\r\nConnection: close\r\n") + "state");
  }
  // Every post is taken or refused before the state is asked.
  while (server.statsJson()["requests"].get<long>() < kMaxCommandsWaiting + 4) std::this_thread::yield();
  expectStateAnswered(port);
  release.set_value();
  int ok = 0, refused = 0;
  for (auto& p : posts) {
    const int status = p->status();
    ok += status == 200;
    refused += status == 429;
  }
  EXPECT_EQ(ok, kMaxCommandsWaiting);
  EXPECT_EQ(refused, 4);
}

// A newcomer sees what is drawn now: frames drawn while nobody watched are not encoded, and the
// first /frame.jpg and the first part of a new stream are the frame drawn last, with its time
// and the move numbers its state shows.
TEST(ServeLoad, ANewViewerGetsTheFrameDrawnLast) {
  const SessionDesc session = loadSceneFile(resolveScenePath("live-view"));
  LiveView view(session, sessionCamera(session, ""), "live", out("gf_serve_load_fresh"), false);
  std::unique_ptr<WebServer> server = serve(view, "127.0.0.1");
  const render::Image image{64, 36, std::vector<std::uint8_t>(64 * 36 * 3, 90)};
  sim::Snapshot snap;
  for (int k = 1; k <= 30; ++k) {
    snap.time = 0.001 * k;
    snap.moves_taken = k / 2;  // the browser view's moves the state has taken and reached
    snap.moves_arrived = k / 3;
    view.frame(image, snap, 1.0f);
  }
  httplib::Client client("127.0.0.1", portOf(*server));
  client.set_read_timeout(60, 0);
  const auto frame = client.Get("/frame.jpg");
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->status, 200);
  EXPECT_EQ(frame->get_header_value("X-Frame"), "30");
  EXPECT_EQ(frame->get_header_value("X-Sim-Time"), "0.0300");
  EXPECT_EQ(frame->get_header_value("X-Moves-Taken"), "15");
  EXPECT_EQ(frame->get_header_value("X-Moves-Arrived"), "10");
  RawClient stream(portOf(*server), "127.0.0.1");
  stream.send(head(portOf(*server), "GET /stream.mjpg HTTP/1.1"));
  const std::string answer = stream.readAll(400);
  EXPECT_NE(answer.find("X-Frame: 30\r\n"), std::string::npos) << answer.substr(0, 300);
  EXPECT_NE(answer.find("X-Moves-Taken: 15\r\nX-Moves-Arrived: 10\r\n"), std::string::npos) << answer.substr(0, 300);
  EXPECT_LE(view.jpeg().stats().encoded, 2) << "frames were encoded while nobody watched";
}

// A token the user gave is never printed; a generated one is shown once, since only the server
// knows it.
TEST(ServeLoad, AGivenTokenIsNeverShown) {
  FedView fed(out("gf_serve_load_shown"));
  std::unique_ptr<WebServer> given = serve(fed.view(), "127.0.0.1", "secret123");
  EXPECT_EQ(given->shownUrl().find("secret123"), std::string::npos) << given->shownUrl();
  EXPECT_NE(given->shownUrl().find("token=***"), std::string::npos);
  given->stop();
  std::unique_ptr<WebServer> made = serve(fed.view(), "0.0.0.0");
  ASSERT_TRUE(made->tokenGenerated());
  EXPECT_EQ(made->shownUrl(), made->url());
}

}  // namespace
}  // namespace gf::app
