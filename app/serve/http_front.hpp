// The browser view's HTTP front (Boost.Beast on one Asio thread): it accepts connections, reads
// each request within bounds of size and time, refuses what is malformed, and hands whole,
// admitted requests to the server's routes. No connection can hold a thread: every read and
// write is asynchronous and under a deadline, so slow, idle or endless clients cost a slot
// each, never the service; slots are capped per address and overall, the oldest idle one
// giving way to a newcomer.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gf::app {

/// What one request and one connection may take. The defaults serve a page and a few scripts;
/// tests shorten the times.
struct HttpLimits {
  std::size_t header_bytes = 8192;  ///< request line and header fields, in all
  int header_fields = 64;           ///< header fields
  std::size_t body_bytes = 4096;    ///< body, whatever its framing (chunked included)
  /// A request, head and body, must arrive within this of its connection's start or of the
  /// previous answer (a keep-alive connection idle longer is closed with 408).
  std::chrono::milliseconds request_time{5000};
  /// An answer, or one part of a stream, must be taken by the client within this.
  std::chrono::milliseconds write_time{10000};
  int connections = 256;              ///< open at once, overall
  int connections_per_address = 32;   ///< open at once from one address
  int streams = 8;                    ///< open at once, overall (503 beyond)
  int streams_per_address = 2;        ///< open at once from one address (429 beyond)
};

/// A request whose head is read (and, once admitted, its body).
struct HttpRequest {
  std::string method;  ///< "GET", "POST", ...
  std::string path;    ///< the target without its query
  std::string token;   ///< the query's `token=` value ("" without one)
  std::string query;   ///< the target's query, after its '?' ("" without one)
  std::string host, origin, authorization;  ///< those header fields ("" when absent)
  std::string body;
  std::string address;  ///< the client's IP address
};

/// The value of `name=` in `query` (a target's query: pairs joined by '&'), "" without one.
std::string queryValue(std::string_view query, std::string_view name);

/// An answer: `body`, or `bytes` when set (shared, never copied).
struct HttpAnswer {
  int status = 200;
  std::string type = "text/plain";
  std::string body;
  std::shared_ptr<const std::vector<std::uint8_t>> bytes;
  std::vector<std::pair<std::string, std::string>> headers;  ///< extra fields
};

/// One part of a stream, written as `head`, `bytes`, `tail`; shared by every stream sent it.
struct StreamPart {
  std::string head;
  std::shared_ptr<const std::vector<std::uint8_t>> bytes;
  std::string tail;
};

/// One admitted request and its connection, as the routes see it.
class HttpExchange {
 public:
  virtual ~HttpExchange() = default;
  /// Answers the request (once). Any thread; the answer is written on the front's thread.
  virtual void answer(HttpAnswer answer) = 0;
  /// Makes the connection a stream: `head` (a whole response head) is written, then the parts
  /// sendPart() gives, until the client leaves. False (and a 429 or 503 answered) when the caps
  /// of streams are reached. Only inside the routes' dispatch call.
  virtual bool startStream(std::string head) = 0;
  /// Queues `part` on a stream: written when the one before is taken, replacing any part
  /// still waiting (a slow client gets the newest, never a backlog). Any thread.
  virtual void sendPart(std::shared_ptr<const StreamPart> part) = 0;
  /// False once the connection has closed. Any thread.
  virtual bool open() const = 0;
};

/// What the front did, for /server.json and summary.json.
struct HttpCounts {
  long connections = 0;   ///< accepted
  long open = 0;          ///< open now
  long refused = 0;       ///< turned away at accept: caps reached, nothing idle to close
  long evicted = 0;       ///< idle connections closed (408) to make room for a newcomer
  long timed_out = 0;     ///< requests that did not arrive in time (408)
  long malformed = 0;     ///< refused as bad HTTP (400)
  long too_large = 0;     ///< heads (431) or bodies (413) over the limits
  long streams_refused = 0;  ///< streams over the caps (429, 503)
};

class HttpFront {
 public:
  /// Before the body is read: an answer refuses the request (its body is never read), nullopt
  /// admits it. Front's thread; must not block.
  using Gate = std::function<std::optional<HttpAnswer>(const HttpRequest&)>;
  /// An admitted request: answer it through the exchange, now or later. Front's thread; must not
  /// block.
  using Dispatch = std::function<void(const HttpRequest&, const std::shared_ptr<HttpExchange>&)>;

  /// Binds `host`:`port` (0: any free port) now; throws std::runtime_error naming the address
  /// when it cannot. Serves on a thread of its own from start() to stop().
  HttpFront(const std::string& host, int port, const HttpLimits& limits, Gate gate, Dispatch dispatch);
  ~HttpFront();
  HttpFront(const HttpFront&) = delete;
  HttpFront& operator=(const HttpFront&) = delete;

  /// The port bound.
  int port() const;
  void start();
  /// Closes every connection, stops listening and joins the thread. Idempotent.
  void stop();
  /// Any thread.
  HttpCounts counts() const;

  struct Impl;

 private:
  std::shared_ptr<Impl> impl_;
};

}  // namespace gf::app
