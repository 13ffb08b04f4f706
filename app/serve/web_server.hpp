// The browser view's HTTP server: the page, the frames as MJPEG, the newest state, and `live`
// commands, behind the bounded front of http_front.hpp. It reads a LiveView and hands command
// lines to the session's handler on a thread of its own; it never touches the haptic thread.
// Loopback unless a host is given; any other address needs a token, checked before a body is
// read. No file is served from disk.
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/serve/http_front.hpp"
#include "app/serve/live_view.hpp"

namespace gf::app {

/// Where and how `--serve [HOST:]PORT` listens.
struct ServeOptions {
  std::string host = "127.0.0.1";  ///< IPv4 address, or "localhost"
  int port = 0;                    ///< 0: any free port (the bound one is printed)
  /// Required from every request (`?token=` or `Authorization: Bearer`) when not empty. A bind
  /// beyond loopback without one gets a generated token.
  std::string token;
  HttpLimits limits;  ///< what a request and a connection may take
  /// An experiment's participant page (app/experiment/web_participant.hpp): what its panel shows
  /// (phase, instruction, trial, block, time limit, the last result), in /scene.json as
  /// `participant`. Null: the full browser view. With one, the page shows no setting and no
  /// condition (the fingers' models and settings are left out of /state.json too), and the
  /// server takes no `set`, `record` or `snapshot`.
  nlohmann::json participant;
  /// With a participant page: answers the commands of its phase ("ready", "answers ...") before
  /// the `live` ones are looked at; nullopt passes a line on. Called on a server thread.
  std::function<std::optional<std::string>(const std::string& line)> participant_command;
};

/// Parses `--serve`'s value ("8080", "127.0.0.1:8080", "0.0.0.0:8080") and `--token`. Throws
/// InputError naming the option when it is not legal.
ServeOptions parseServe(const std::string& serve, const std::string& token);

/// `--token`'s value, or $GODFINGER_TOKEN when it is empty (a token in the environment is not
/// shown by `ps` to other users).
std::string tokenOrEnvironment(const std::string& given);
/// The command line with `--token`'s value replaced by "***" (summary.json records it).
std::vector<std::string> redactedToken(std::vector<std::string> argv);

/// Requests one client may make a second, and in a burst, before it gets 429.
inline constexpr double kRequestsPerSecond = 300.0, kRequestBurst = 600.0;
/// Commands taken and not yet answered (the one running and those behind it); one more gets 429.
inline constexpr int kMaxCommandsWaiting = 16;
/// Requests for /frame.jpg waiting for a frame; one more gets 429.
inline constexpr int kMaxFrameWaiters = 16;

/// Token buckets per client address: kRequestsPerSecond, in bursts of kRequestBurst. Any thread.
class RequestRate {
 public:
  using Clock = std::chrono::steady_clock;
  /// Whether `client` may make a request at `now` (it then takes one token).
  bool allow(const std::string& client, Clock::time_point now);

 private:
  struct Bucket {
    double tokens;
    Clock::time_point at;
  };
  std::mutex mutex_;
  std::map<std::string, Bucket> buckets_;
};

class WebServer {
 public:
  /// Answers one `live` command line exactly as standard input would ("ok ..." or "error:
  /// ..."), from a server thread.
  using CommandHandler = std::function<std::string(const std::string& line)>;
  /// Binds now (throws std::runtime_error naming the address when it cannot) and serves on a
  /// thread of its own until stop().
  WebServer(const ServeOptions& options, LiveView& view, CommandHandler command);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  /// "http://HOST:PORT/", with "?token=..." when a token is required.
  std::string url() const;
  /// What to print: url(), but a token the user gave (--token, $GODFINGER_TOKEN) as "***"; a
  /// generated one is shown, once, since nobody else knows it.
  std::string shownUrl() const;
  bool loopback() const;
  /// The port bound (the one given, or the free one taken for port 0).
  int port() const;
  /// The token every request needs ("" for none): the given one or the generated one.
  const std::string& token() const;
  /// Generated (not given) token, printed once at the start.
  bool tokenGenerated() const;
  /// Ends every stream, stops listening, joins the threads. Idempotent; never waits on the
  /// haptic thread.
  void stop();
  /// Requests served, refused (401, 403, 429), the front's counts (connections, evicted, timed
  /// out, malformed, too large), streams, stream frames sent and commands posted (and not yet
  /// answered), for summary.json and `GET /server.json`. Any thread.
  nlohmann::json statsJson() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// The page: one self-contained HTML document (no file from disk or the network).
const std::string& webPage();

}  // namespace gf::app
