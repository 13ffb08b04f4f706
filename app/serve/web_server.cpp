#include "app/serve/web_server.hpp"

#include <httplib.h>

#include <arpa/inet.h>
#include <sys/socket.h>

#include <atomic>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <random>
#include <thread>

#include "app/scene/input_error.hpp"

namespace gf::app {
namespace {

using Clock = std::chrono::steady_clock;
constexpr char kBoundary[] = "gfframe";
// A stream with no new frame for this long writes nothing and checks its client again; after
// kStreamResend without a frame it sends the newest again, so a client that hung up is found
// (an idle `live` session draws nothing) and its place freed.
constexpr std::chrono::milliseconds kStreamPoll{500};
constexpr std::chrono::seconds kStreamResend{2};

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

struct WebServer::Impl {
  ServeOptions options;
  LiveView& view;
  CommandHandler command;
  bool generated = false;
  httplib::Server server;
  std::thread thread;
  RequestRate limit;
  std::atomic<int> streams{0};
  std::atomic<long> served{0}, unauthorized{0}, limited{0}, foreign{0}, busy{0}, stream_frames{0};
  std::atomic<long> commands{0}, answered{0};  // posted to /command; answered of them
  std::atomic<bool> stopping{false};

  Impl(const ServeOptions& o, LiveView& v, CommandHandler c) : options(o), view(v), command(std::move(c)) {}

  // Requests served and refused, streams, and the commands posted: `commands_running` are taken
  // and not yet answered (under `live`, the one being run and those waiting behind it).
  nlohmann::json stats() const {
    const long done = answered.load(), taken = commands.load();  // in this order: never fewer taken
    return {{"url", "http://" + options.host + ":" + std::to_string(options.port) + "/"},
            {"token", !options.token.empty()},
            {"requests", served.load()},
            {"unauthorized", unauthorized.load()},
            {"rate_limited", limited.load()},
            {"foreign", foreign.load()},
            {"streams_refused", busy.load()},
            {"streams_open", streams.load()},
            {"stream_frames_sent", stream_frames.load()},
            {"commands", taken},
            {"commands_running", taken - done}};
  }

  bool authorized(const httplib::Request& req) const {
    if (options.token.empty()) return true;
    if (req.has_param("token") && sameSecret(req.get_param_value("token"), options.token)) return true;
    return sameSecret(req.get_header_value("Authorization"), "Bearer " + options.token);
  }

  // A page of another site must not steer or read a session on loopback through the visitor's
  // browser: on loopback the Host must be this server's (no DNS rebinding), and a request a page
  // sends with an Origin must come from this server's own.
  bool sameSite(const httplib::Request& req) const {
    const std::string port = std::string(":").append(std::to_string(options.port));  // (GCC 12: no ":" + s)
    const std::string host = req.get_header_value("Host");
    if (isLoopback(options.host) && host != options.host + port && host != std::string("localhost").append(port)) {
      return false;
    }
    const std::string origin = req.get_header_value("Origin");
    return origin.empty() || origin == std::string("http://").append(host);
  }

  httplib::Server::HandlerResponse refuse(httplib::Response& res, int status, const char* text, std::atomic<long>& count) {
    ++count;
    res.status = status;
    res.set_content(text, "text/plain");
    return httplib::Server::HandlerResponse::Handled;
  }

  httplib::Server::HandlerResponse gate(const httplib::Request& req, httplib::Response& res) {
    ++served;
    if (!limit.allow(req.remote_addr, Clock::now())) return refuse(res, 429, "429: too many requests\n", limited);
    if (!authorized(req)) {
      return refuse(res, 401, "401: this server needs its token (?token=... or Authorization: Bearer ...)\n",
                    unauthorized);
    }
    if (!sameSite(req)) return refuse(res, 403, "403: not from this server's own page or address\n", foreign);
    res.set_header("Cache-Control", "no-store");
    return httplib::Server::HandlerResponse::Unhandled;
  }

  // One part of the MJPEG stream: the newest frame after `last`, or nothing after kStreamPoll
  // (the newest again after kStreamResend without one).
  bool streamPart(long& last, Clock::time_point& sent, httplib::DataSink& sink) {
    const render::JpegFrame f = view.jpeg().waitNewer(last, kStreamPoll);
    if (stopping.load() || view.jpeg().closed()) return false;
    if (!f.bytes) return sink.is_writable();
    if (f.number <= last && Clock::now() - sent < kStreamResend) return sink.is_writable();
    last = f.number;
    sent = Clock::now();
    char head[200];
    const int n = std::snprintf(head, sizeof head,
                                "--%s\r\nContent-Type: image/jpeg\r\nContent-Length: %zu\r\nX-Frame: %ld\r\n"
                                "X-Sim-Time: %.4f\r\n\r\n",
                                kBoundary, f.bytes->size(), f.number, f.time);
    if (!sink.write(head, static_cast<std::size_t>(n))) return false;
    if (!sink.write(reinterpret_cast<const char*>(f.bytes->data()), f.bytes->size())) return false;
    ++stream_frames;
    return sink.write("\r\n", 2);
  }

  void stream(httplib::Response& res) {
    if (streams.fetch_add(1) >= kMaxStreams) {
      --streams;
      ++busy;
      res.status = 503;
      res.set_content("503: " + std::to_string(kMaxStreams) + " streams are open already\n", "text/plain");
      return;
    }
    auto last = std::make_shared<std::pair<long, Clock::time_point>>(0, Clock::now());
    res.set_content_provider(
        std::string("multipart/x-mixed-replace; boundary=") + kBoundary,
        [this, last](std::size_t, httplib::DataSink& sink) { return streamPart(last->first, last->second, sink); },
        [this](bool) { --streams; });
  }

  void frame(httplib::Response& res) {
    // A frame drawn after the request (the encoder skips frames nobody waits for).
    const render::JpegFrame before = view.jpeg().newest();
    render::JpegFrame f = view.jpeg().waitNewer(before.number, std::chrono::milliseconds(500));
    if (f.number == before.number) f = view.jpeg().waitNewer(0, std::chrono::milliseconds(2000));
    if (!f.bytes) {
      res.status = 503;
      res.set_content("503: no frame drawn yet\n", "text/plain");
      return;
    }
    res.set_content(reinterpret_cast<const char*>(f.bytes->data()), f.bytes->size(), "image/jpeg");
  }

  void routes() {
    server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) { return gate(req, res); });
    server.Get("/", [](const httplib::Request&, httplib::Response& res) { res.set_content(webPage(), "text/html; charset=utf-8"); });
    server.Get("/scene.json", [this](const httplib::Request&, httplib::Response& res) {
      res.set_content(view.sceneJson().dump(), "application/json");
    });
    server.Get("/state.json", [this](const httplib::Request&, httplib::Response& res) {
      res.set_content(view.stateText(), "application/json");
    });
    server.Get("/server.json", [this](const httplib::Request&, httplib::Response& res) {
      res.set_content(stats().dump(), "application/json");
    });
    server.Get("/stream.mjpg", [this](const httplib::Request&, httplib::Response& res) { stream(res); });
    server.Get("/frame.jpg", [this](const httplib::Request&, httplib::Response& res) { frame(res); });
    server.Post("/command", [this](const httplib::Request& req, httplib::Response& res) {
      if (req.body.find('\n') != std::string::npos && req.body.find('\n') + 1 < req.body.size()) {
        res.status = 400;
        res.set_content("error: one command per request\n", "text/plain");
        return;
      }
      std::string line = req.body;
      while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
      ++commands;
      const std::string answer = command(line);
      ++answered;
      if (answer.rfind("error", 0) == 0) res.status = 400;
      res.set_content(answer + "\n", "text/plain");
    });
  }
};

WebServer::WebServer(const ServeOptions& options, LiveView& view, CommandHandler command)
    : impl_(std::make_unique<Impl>(options, view, std::move(command))) {
  Impl& s = *impl_;
  if (!isLoopback(s.options.host) && s.options.token.empty()) {
    s.options.token = generatedToken();
    s.generated = true;
  }
  // SO_REUSEADDR only: httplib's default adds SO_REUSEPORT, with which a second run would share the
  // port (the kernel splitting connections between them) instead of being told it is in use.
  s.server.set_socket_options([](int sock) {
    const int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  s.server.set_payload_max_length(kMaxRequestBytes);
  s.server.set_read_timeout(5, 0);
  s.server.set_write_timeout(5, 0);
  s.server.set_keep_alive_timeout(2);  // an idle browser connection holds stop() up to this long
  s.routes();
  if (s.options.port == 0) {
    s.options.port = s.server.bind_to_any_port(s.options.host);
    if (s.options.port < 0) s.options.port = 0;
  } else if (!s.server.bind_to_port(s.options.host, s.options.port)) {
    s.options.port = 0;
  }
  if (s.options.port <= 0) {
    throw std::runtime_error("--serve: cannot listen on " + options.host + ":" + std::to_string(options.port) +
                             " (in use, or not an address of this machine)");
  }
  s.thread = std::thread([&s] {
    pthread_setname_np(pthread_self(), "gf-http");
    s.server.listen_after_bind();
  });
  // httplib's stop() does nothing before its loop runs: wait for it (bounded), so a server
  // stopped at once (a later start-up step failing) stops.
  for (int i = 0; i < 5000 && !s.server.is_running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

WebServer::~WebServer() { stop(); }

std::string WebServer::url() const {
  const Impl& s = *impl_;
  std::string u = "http://" + s.options.host + ":" + std::to_string(s.options.port) + "/";
  return s.options.token.empty() ? u : u + "?token=" + s.options.token;
}

bool WebServer::loopback() const { return isLoopback(impl_->options.host); }

bool WebServer::tokenGenerated() const { return impl_->generated; }

void WebServer::stop() {
  Impl& s = *impl_;
  if (s.stopping.exchange(true)) return;
  s.view.jpeg().close();  // wakes every stream, which then ends
  s.server.stop();
  if (s.thread.joinable()) s.thread.join();
}

nlohmann::json WebServer::statsJson() const { return impl_->stats(); }

}  // namespace gf::app
