#include "app/serve/web_server.hpp"

#include <arpa/inet.h>
#include <sys/socket.h>

#include <atomic>
#include <condition_variable>
#include <deque>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <mutex>
#include <optional>
#include <vector>
#include <random>
#include <thread>

#include "app/scene/input_error.hpp"

namespace gf::app {
namespace {

using Clock = std::chrono::steady_clock;
constexpr char kBoundary[] = "gfframe";
// How long the frame pump waits for a newer frame before it looks at its watchers again, and how
// long a /frame.jpg request waits for a first frame before 503.
constexpr std::chrono::milliseconds kFramePoll{100};
constexpr std::chrono::milliseconds kFrameWait{2500};
// The answer to a command that comes, or still waits, when the session ends.
constexpr char kEnded[] = "error: the session has ended";

// Equal strings, in a time that does not depend on where they differ.
bool sameSecret(const std::string& a, const std::string& b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i % std::max<std::size_t>(1, b.size())]);
  return diff == 0;
}

bool isLoopback(const std::string& host) { return host == "localhost" || host.rfind("127.", 0) == 0; }

std::string generatedToken() {
  std::random_device random;
  char text[33];
  for (int i = 0; i < 4; ++i) std::snprintf(text + 8 * i, 9, "%08x", random());
  return text;
}

}  // namespace

bool RequestRate::allow(const std::string& client, Clock::time_point now) {
  std::lock_guard lock(mutex_);
  if (buckets_.size() > 256) buckets_.clear();  // many addresses: start again rather than grow
  auto [it, fresh] = buckets_.try_emplace(client, Bucket{kRequestBurst, now});
  Bucket& b = it->second;
  if (!fresh && now > b.at) {
    b.tokens = std::min(kRequestBurst, b.tokens + kRequestsPerSecond * std::chrono::duration<double>(now - b.at).count());
    b.at = now;
  }
  if (b.tokens < 1.0) return false;
  b.tokens -= 1.0;
  return true;
}

std::string tokenOrEnvironment(const std::string& given) {
  const char* environment = std::getenv("GODFINGER_TOKEN");
  return given.empty() && environment ? environment : given;
}

std::vector<std::string> redactedToken(std::vector<std::string> argv) {
  for (std::size_t i = 0; i < argv.size(); ++i) {
    if (argv[i] == "--token" && i + 1 < argv.size()) argv[i + 1] = "***";
    if (argv[i].rfind("--token=", 0) == 0) argv[i] = "--token=***";
  }
  return argv;
}

ServeOptions parseServe(const std::string& serve, const std::string& token) {
  ServeOptions o;
  const std::size_t colon = serve.rfind(':');
  const std::string port_text = colon == std::string::npos ? serve : serve.substr(colon + 1);
  if (colon != std::string::npos) o.host = serve.substr(0, colon);
  if (o.host == "localhost") o.host = "127.0.0.1";
  in_addr address{};
  if (inet_pton(AF_INET, o.host.c_str(), &address) != 1) {
    throw commandLineError("--serve",
                     "'" + o.host + "' is not an IPv4 address (such as 127.0.0.1, or 0.0.0.0 for every interface)");
  }
  int port = -1;
  const auto [end, error] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (error != std::errc() || end != port_text.data() + port_text.size() || port < 0 || port > 65535) {
    throw commandLineError("--serve",
                     "expected [HOST:]PORT with PORT a whole number in 0..65535 (0: any free port), got '" + serve + "'");
  }
  o.port = port;
  for (char c : token) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') {
      throw commandLineError("--token", "use letters, digits, '-', '_' and '.' only");
    }
  }
  o.token = token;
  return o;
}

namespace {

HttpAnswer textAnswer(int status, std::string text, std::string type = "text/plain") {
  HttpAnswer a;
  a.status = status;
  a.body = std::move(text);
  a.type = std::move(type);
  return a;
}

}  // namespace

struct WebServer::Impl {
  ServeOptions options;
  LiveView& view;
  CommandHandler command;
  bool generated = false;
  RequestRate limit;
  std::atomic<long> served{0}, unauthorized{0}, limited{0}, foreign{0}, stream_frames{0};
  std::atomic<long> commands{0}, answered{0};  // posted to /command; answered of them
  std::atomic<bool> stopping{false};
  // The frames' watchers: streams and /frame.jpg requests, fed by the pump thread.
  struct Stream {
    std::weak_ptr<HttpExchange> exchange;
    long sent = 0;  // the newest frame's number sent it
    int width = 0;  // its `width=` (0: the frame's own)
  };
  struct FrameWaiter {
    std::shared_ptr<HttpExchange> exchange;
    Clock::time_point until;
    int width = 0;
  };
  mutable std::mutex frames_mutex;
  std::condition_variable frames_changed;
  std::vector<Stream> streams;
  std::vector<FrameWaiter> frame_waiters;
  bool fresh_wanted = false;  // a newcomer needs the newest frame drawn, not the next one
  std::thread pump;
  // The commands, answered in turn on a thread of their own.
  std::mutex commands_mutex;
  std::condition_variable commands_changed;
  std::deque<std::pair<std::string, std::shared_ptr<HttpExchange>>> command_queue;
  std::thread commander;
  std::unique_ptr<HttpFront> front;

  Impl(const ServeOptions& o, LiveView& v, CommandHandler c) : options(o), view(v), command(std::move(c)) {}

  // Requests served and refused, the front's counts, streams, and the commands posted:
  // `commands_running` are taken and not yet answered (the one being run and those behind it).
  nlohmann::json stats() const {
    const long done = answered.load(), taken = commands.load();  // in this order: never fewer taken
    const HttpCounts c = front ? front->counts() : HttpCounts{};
    return {{"url", "http://" + options.host + ":" + std::to_string(options.port) + "/"},
            {"token", !options.token.empty()},
            {"requests", served.load()},
            {"unauthorized", unauthorized.load()},
            {"rate_limited", limited.load()},
            {"foreign", foreign.load()},
            {"connections", c.connections},
            {"connections_open", c.open},
            {"connections_refused", c.refused},
            {"connections_evicted", c.evicted},
            {"timed_out", c.timed_out},
            {"malformed", c.malformed},
            {"too_large", c.too_large},
            {"streams_refused", c.streams_refused},
            {"streams_open", streamsOpen()},
            {"stream_frames_sent", stream_frames.load()},
            {"commands", taken},
            {"commands_running", taken - done}};
  }

  long streamsOpen() const {
    std::lock_guard lock(frames_mutex);
    long n = 0;
    for (const Stream& s : streams) {
      const std::shared_ptr<HttpExchange> x = s.exchange.lock();
      n += x && x->open();
    }
    return n;
  }

  bool authorized(const HttpRequest& req) const {
    if (options.token.empty()) return true;
    if (!req.token.empty() && sameSecret(req.token, options.token)) return true;
    return sameSecret(req.authorization, "Bearer " + options.token);
  }

  // A page of another site must not steer or read a session on loopback through the visitor's
  // browser: on loopback the Host must be this server's (no DNS rebinding), and a request a page
  // sends with an Origin must come from this server's own.
  bool sameSite(const HttpRequest& req) const {
    const std::string port = std::string(":").append(std::to_string(options.port));  // (GCC 12: no ":" + s)
    if (isLoopback(options.host) && req.host != options.host + port && req.host != std::string("localhost").append(port)) {
      return false;
    }
    return req.origin.empty() || req.origin == std::string("http://").append(req.host);
  }

  // Before a body is read: the rate, the token, the site.
  std::optional<HttpAnswer> gate(const HttpRequest& req) {
    ++served;
    if (!limit.allow(req.address, Clock::now())) {
      ++limited;
      return textAnswer(429, "429: too many requests\n");
    }
    if (!authorized(req)) {
      ++unauthorized;
      return textAnswer(401, "401: this server needs its token (?token=... or Authorization: Bearer ...)\n");
    }
    if (!sameSite(req)) {
      ++foreign;
      return textAnswer(403, "403: not from this server's own page or address\n");
    }
    return std::nullopt;
  }

  void dispatch(const HttpRequest& req, const std::shared_ptr<HttpExchange>& x) {
    if (req.path == "/command") {
      if (req.method != "POST") return x->answer(textAnswer(405, "405: POST a command\n"));
      return postCommand(req.body, x);
    }
    if (req.method != "GET") return x->answer(textAnswer(405, "405: only GET here\n"));
    if (req.path == "/") return x->answer(textAnswer(200, webPage(), "text/html; charset=utf-8"));
    if (req.path == "/scene.json") return x->answer(textAnswer(200, view.sceneJson().dump(), "application/json"));
    if (req.path == "/state.json") return x->answer(textAnswer(200, view.stateText(), "application/json"));
    if (req.path == "/server.json") return x->answer(textAnswer(200, stats().dump(), "application/json"));
    if (req.path == "/stream.mjpg" || req.path == "/frame.jpg") {
      const std::optional<int> width = watchWidth(req);
      if (!width) return x->answer(textAnswer(400, "400: width must be a whole number of pixels, 16..4096\n"));
      return req.path == "/stream.mjpg" ? startStream(x, *width) : waitForFrame(x, *width);
    }
    x->answer(textAnswer(404, "404: no such page\n"));
  }

  void postCommand(const std::string& body, const std::shared_ptr<HttpExchange>& x) {
    const std::size_t newline = body.find('\n');
    if (newline != std::string::npos && newline + 1 < body.size()) {
      return x->answer(textAnswer(400, "error: one command per request\n"));
    }
    std::string line = body;
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    std::lock_guard lock(commands_mutex);
    if (stopping.load()) return x->answer(textAnswer(503, std::string(kEnded) + "\n"));
    if (commands.load() - answered.load() >= kMaxCommandsWaiting) {
      return x->answer(textAnswer(429, "429: " + std::to_string(kMaxCommandsWaiting) + " commands are waiting already\n"));
    }
    ++commands;
    command_queue.emplace_back(std::move(line), x);
    commands_changed.notify_one();
  }

  void runCommands() {
    pthread_setname_np(pthread_self(), "gf-http-cmd");
    std::unique_lock lock(commands_mutex);
    for (;;) {
      commands_changed.wait(lock, [&] { return stopping.load() || !command_queue.empty(); });
      if (stopping.load()) {  // those still waiting are answered, never left hanging
        for (auto& [line, x] : command_queue) x->answer(textAnswer(503, std::string(kEnded) + "\n"));
        answered += static_cast<long>(command_queue.size());
        command_queue.clear();
        return;
      }
      auto [line, x] = std::move(command_queue.front());
      command_queue.pop_front();
      lock.unlock();
      const std::string answer = command(line);
      ++answered;
      x->answer(textAnswer(answer.rfind("error", 0) == 0 ? 400 : 200, answer + "\n"));
      lock.lock();
    }
  }

  // A watcher's `width=`, the pixels across it shows frames at: 0 without one, none when it is
  // not a whole number within 16..4096.
  static std::optional<int> watchWidth(const HttpRequest& req) {
    const std::string text = queryValue(req.query, "width");
    if (text.empty()) return 0;
    int width = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), width);
    if (error != std::errc() || end != text.data() + text.size() || width < 16 || width > 4096) return std::nullopt;
    return width;
  }

  // Frames lock held: the width frames are encoded at, the widest any watcher asks for (the
  // frame's own when one asks for no width), so that none gets fewer pixels than it shows.
  int wantedWidth() const {
    int widest = 0;
    bool full = false;
    const auto want = [&](int w) { full = full || w == 0, widest = std::max(widest, w); };
    for (const Stream& s : streams) want(s.width);
    for (const FrameWaiter& w : frame_waiters) want(w.width);
    return full ? 0 : widest;
  }

  void startStream(const std::shared_ptr<HttpExchange>& x, int width) {
    const std::string head = std::string("HTTP/1.1 200 OK\r\nContent-Type: multipart/x-mixed-replace; boundary=") +
                             kBoundary + "\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n";
    if (!x->startStream(head)) return;
    std::lock_guard lock(frames_mutex);
    streams.push_back({x, 0, width});
    fresh_wanted = true;
    frames_changed.notify_one();
  }

  void waitForFrame(const std::shared_ptr<HttpExchange>& x, int width) {
    std::lock_guard lock(frames_mutex);
    if (static_cast<int>(frame_waiters.size()) >= kMaxFrameWaiters) {
      return x->answer(textAnswer(429, "429: " + std::to_string(kMaxFrameWaiters) + " frame requests wait already\n"));
    }
    frame_waiters.push_back({x, Clock::now() + kFrameWait, width});
    fresh_wanted = true;
    frames_changed.notify_one();
  }

  // The fields a frame carries, on /frame.jpg and on each part of the stream.
  static std::vector<std::pair<std::string, std::string>> frameFields(const render::JpegFrame& f) {
    char time[32];
    std::snprintf(time, sizeof time, "%.4f", f.time);
    return {{"X-Frame", std::to_string(f.number)}, {"X-Sim-Time", time},
            {"X-Moves-Taken", std::to_string(f.moves_taken)}, {"X-Moves-Arrived", std::to_string(f.moves_arrived)}};
  }

  static std::shared_ptr<const StreamPart> partOf(const render::JpegFrame& f) {
    auto part = std::make_shared<StreamPart>();
    part->head = std::string("--") + kBoundary + "\r\nContent-Type: image/jpeg\r\nContent-Length: " +
                 std::to_string(f.bytes->size()) + "\r\n";
    for (const auto& [name, value] : frameFields(f)) part->head += name + ": " + value + "\r\n";
    part->head += "\r\n";
    part->bytes = f.bytes;
    part->tail = "\r\n";
    return part;
  }

  // Frames lock held: `f` to every stream not sent it yet and to every waiting /frame.jpg; the
  // waiters whose time is up get 503.
  void deliver(const render::JpegFrame& f) {
    std::shared_ptr<const StreamPart> part;
    for (Stream& s : streams) {
      const std::shared_ptr<HttpExchange> x = s.exchange.lock();
      if (!f.bytes || !x || s.sent >= f.number) continue;
      if (!part) part = partOf(f);
      x->sendPart(part);
      s.sent = f.number;
      ++stream_frames;
    }
    const Clock::time_point now = Clock::now();
    std::erase_if(frame_waiters, [&](const FrameWaiter& w) {
      if (f.bytes) {
        HttpAnswer a;
        a.type = "image/jpeg";
        a.bytes = f.bytes;
        a.headers = frameFields(f);
        w.exchange->answer(std::move(a));
        return true;
      }
      if (now < w.until) return false;
      w.exchange->answer(textAnswer(503, "503: no frame drawn yet\n"));
      return true;
    });
  }

  // The pump: while anyone watches, the newest frame encoded, handed to the watchers.
  void pumpFrames() {
    pthread_setname_np(pthread_self(), "gf-http-frames");
    long last = 0;
    std::unique_lock lock(frames_mutex);
    while (!stopping.load()) {
      std::erase_if(streams, [](const Stream& s) {
        const std::shared_ptr<HttpExchange> x = s.exchange.lock();
        return !x || !x->open();
      });
      if (streams.empty() && frame_waiters.empty()) {
        frames_changed.wait(lock);
        continue;
      }
      const bool fresh = std::exchange(fresh_wanted, false);
      view.jpeg().setWidth(wantedWidth());
      lock.unlock();
      const render::JpegFrame f = view.jpeg().waitNewer(fresh ? 0 : last, kFramePoll);
      lock.lock();
      if (stopping.load()) break;
      deliver(f);
      last = std::max(last, f.number);
    }
    for (const FrameWaiter& w : frame_waiters) w.exchange->answer(textAnswer(503, "503: the server is stopping\n"));
    frame_waiters.clear();
  }

  void stop() {
    if (stopping.exchange(true)) return;
    view.jpeg().close();  // wakes the pump
    {
      std::scoped_lock lock(frames_mutex, commands_mutex);
      frames_changed.notify_all();
      commands_changed.notify_all();
    }
    // The pump and the commands answer what waits; the front then writes those answers out.
    if (pump.joinable()) pump.join();
    if (commander.joinable()) commander.join();
    if (front) front->stop();
    // The exchanges go before the front that made them.
    streams.clear();
    frame_waiters.clear();
    command_queue.clear();
  }
};

WebServer::WebServer(const ServeOptions& options, LiveView& view, CommandHandler command)
    : impl_(std::make_unique<Impl>(options, view, std::move(command))) {
  Impl& s = *impl_;
  if (!isLoopback(s.options.host) && s.options.token.empty()) {
    s.options.token = generatedToken();
    s.generated = true;
  }
  s.front = std::make_unique<HttpFront>(
      s.options.host, s.options.port, s.options.limits, [&s](const HttpRequest& r) { return s.gate(r); },
      [&s](const HttpRequest& r, const std::shared_ptr<HttpExchange>& x) { s.dispatch(r, x); });
  s.options.port = s.front->port();
  s.pump = std::thread([&s] { s.pumpFrames(); });
  s.commander = std::thread([&s] { s.runCommands(); });
  s.front->start();
}

WebServer::~WebServer() { stop(); }

std::string WebServer::url() const {
  const Impl& s = *impl_;
  std::string u = "http://" + s.options.host + ":" + std::to_string(s.options.port) + "/";
  return s.options.token.empty() ? u : u + "?token=" + s.options.token;
}

std::string WebServer::shownUrl() const {
  const Impl& s = *impl_;
  if (s.options.token.empty() || s.generated) return url();
  return "http://" + s.options.host + ":" + std::to_string(s.options.port) + "/?token=***";
}

bool WebServer::loopback() const { return isLoopback(impl_->options.host); }

int WebServer::port() const { return impl_->options.port; }

const std::string& WebServer::token() const { return impl_->options.token; }

bool WebServer::tokenGenerated() const { return impl_->generated; }

void WebServer::stop() { impl_->stop(); }

nlohmann::json WebServer::statsJson() const { return impl_->stats(); }

}  // namespace gf::app
