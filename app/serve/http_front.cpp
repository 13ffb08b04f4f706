#include "app/serve/http_front.hpp"

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include <pthread.h>

#include <array>
#include <list>
#include <map>
#include <thread>

namespace gf::app {
namespace {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace bhttp = boost::beast::http;
using tcp = net::ip::tcp;
using ErrorCode = boost::system::error_code;
using Millis = std::chrono::milliseconds;

// After a refusal the connection is shut for sending and drained this long (and this much) before
// it is closed, so a client still sending its body reads the answer instead of a reset.
constexpr Millis kLinger{1000};
constexpr std::size_t kLingerBytes = 1 << 20;

std::string reasonPhrase(int status) {
  const beast::string_view r = bhttp::obsolete_reason(bhttp::int_to_status(static_cast<unsigned>(status)));
  return std::string(r.data(), r.size());
}

HttpAnswer plain(int status, std::string text) {
  HttpAnswer a;
  a.status = status;
  a.body = std::move(text);
  return a;
}

std::string headOf(const HttpAnswer& a, std::size_t length, bool keep_alive) {
  std::string h = "HTTP/1.1 " + std::to_string(a.status) + " " + reasonPhrase(a.status) + "\r\n";
  h += "Content-Type: " + a.type + "\r\nContent-Length: " + std::to_string(length) + "\r\nCache-Control: no-store\r\n";
  for (const auto& [field, value] : a.headers) h += field + ": " + value + "\r\n";
  h += keep_alive ? "Connection: keep-alive\r\n\r\n" : "Connection: close\r\n\r\n";
  return h;
}

}  // namespace

std::string queryValue(std::string_view query, std::string_view name) {
  while (!query.empty()) {
    const std::size_t amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    if (pair.size() > name.size() && pair.substr(0, name.size()) == name && pair[name.size()] == '=') {
      return std::string(pair.substr(name.size() + 1));
    }
    if (amp == std::string_view::npos) break;
    query.remove_prefix(amp + 1);
  }
  return "";
}

namespace {

// Writes `status` with `text` at once (a small answer an empty send buffer takes whole; nothing is
// waited for) and closes `socket`.
void answerAndClose(tcp::socket& socket, int status, const std::string& text) {
  const std::string out = headOf(plain(status, text), text.size(), false) + text;
  ErrorCode ignored;
  socket.non_blocking(true, ignored);
  socket.write_some(net::buffer(out), ignored);
  socket.shutdown(tcp::socket::shutdown_both, ignored);
  socket.close(ignored);
}

std::string fieldText(const bhttp::request_parser<bhttp::string_body>::value_type& m, bhttp::field f) {
  const auto it = m.find(f);
  return it == m.end() ? std::string() : std::string(it->value());
}

}  // namespace

class Connection;

struct HttpFront::Impl {
  HttpLimits limits;
  Gate gate;
  Dispatch dispatch;
  net::io_context io{1};
  tcp::acceptor acceptor{io};
  net::steady_timer accept_retry{io};
  std::thread thread;
  bool stopping = false;  // front's thread: no new connection or request; answers being written finish
  net::steady_timer drain_timer{io};
  std::atomic<bool> stopped{false};
  // Front's thread only: the connections, oldest first, and how many each address has open.
  std::list<std::weak_ptr<Connection>> connections;
  std::map<std::string, int> per_address, streams_per_address;
  int streams = 0;
  std::atomic<long> accepted{0}, open{0}, refused{0}, evicted{0}, timed_out{0}, malformed{0}, too_large{0},
      streams_refused{0};

  void accept();
  void admit(tcp::socket socket);
  bool evictOldestIdle(const std::string* address);
  void forget(Connection& c);
  void beginStop();
  void stopIfDrained();
  void closeAll();
};

class Connection final : public HttpExchange, public std::enable_shared_from_this<Connection> {
 public:
  enum class State { kWaiting, kBusy, kStream, kLinger, kClosed };

  Connection(tcp::socket socket, HttpFront::Impl& front, std::string address)
      : front_(front), socket_(std::move(socket)), timer_(front.io), address_(std::move(address)) {}

  std::list<std::weak_ptr<Connection>>::iterator where;  // in front_.connections
  const std::string& address() const { return address_; }
  bool idle() const { return state_ == State::kWaiting; }
  bool busy() const { return state_ == State::kBusy; }
  bool streaming() const { return streaming_; }

  // Waits for the next request: its head, then (once admitted) its body, within request_time.
  void readRequest() {
    if (front_.stopping) return closeNow();
    state_ = State::kWaiting;
    parser_.emplace();
    parser_->header_limit(static_cast<std::uint32_t>(front_.limits.header_bytes));
    parser_->body_limit(front_.limits.body_bytes);
    arm(front_.limits.request_time);
    bhttp::async_read_header(socket_, buffer_, *parser_,
                             [self = shared_from_this()](ErrorCode ec, std::size_t) { self->onHead(ec); });
  }

  // Answers `status` at once (a small text the socket's empty send buffer takes whole) and closes.
  void refuseNow(int status, const std::string& text) {
    if (state_ == State::kClosed) return;
    answerAndClose(socket_, status, text);
    closeNow();  // the bookkeeping; the socket is closed already
  }

  void closeNow() {
    if (state_ == State::kClosed) return;
    state_ = State::kClosed;
    open_.store(false);
    ErrorCode ignored;
    socket_.shutdown(tcp::socket::shutdown_both, ignored);
    socket_.close(ignored);
    disarm();
    front_.forget(*this);
  }

  void answer(HttpAnswer a) override {
    net::post(front_.io, [self = shared_from_this(), a = std::move(a)]() mutable {
      if (self->state_ == State::kBusy) self->write(a, self->keep_alive_ && a.status < 400);
    });
  }

  bool startStream(std::string head) override {
    const int mine = front_.streams_per_address[address_];
    if (mine >= front_.limits.streams_per_address || front_.streams >= front_.limits.streams) {
      ++front_.streams_refused;
      const bool per_address = mine >= front_.limits.streams_per_address;
      write(plain(per_address ? 429 : 503,
                  std::to_string(per_address ? front_.limits.streams_per_address : front_.limits.streams) +
                      (per_address ? " streams are open from your address already\n" : " streams are open already\n")),
            false);
      return false;
    }
    ++front_.streams_per_address[address_];
    ++front_.streams;
    streaming_ = true;
    state_ = State::kStream;
    auto part = std::make_shared<StreamPart>();
    part->head = std::move(head);
    writePart(part);
    watchForClose();
    return true;
  }

  void sendPart(std::shared_ptr<const StreamPart> part) override {
    net::post(front_.io, [self = shared_from_this(), part = std::move(part)]() mutable {
      if (self->state_ != State::kStream) return;
      if (self->writing_) self->next_ = std::move(part);
      else self->writePart(std::move(part));
    });
  }

  bool open() const override { return open_.load(); }

 private:
  void arm(Millis within) {
    timer_.expires_after(within);
    timer_.async_wait([self = shared_from_this(), generation = ++generation_](ErrorCode ec) {
      if (!ec && generation == self->generation_) self->expired();
    });
  }
  void disarm() {
    ++generation_;
    timer_.cancel();
  }

  void expired() {
    if (state_ != State::kWaiting) return closeNow();
    ++front_.timed_out;
    refuseNow(408, "408: the request did not arrive within " + std::to_string(front_.limits.request_time.count()) +
                       " ms\n");
  }

  // A read that failed: the client left, or sent what HTTP or the limits do not allow.
  void failed(ErrorCode ec) {
    if (state_ == State::kClosed) return;
    if (ec == bhttp::error::header_limit || ec == bhttp::error::buffer_overflow) {
      ++front_.too_large;
      return refuse(431, "431: the request's head is over " + std::to_string(front_.limits.header_bytes) + " bytes\n");
    }
    if (ec == bhttp::error::body_limit) {
      ++front_.too_large;
      return refuse(413, "413: the request's body is over " + std::to_string(front_.limits.body_bytes) + " bytes\n");
    }
    if (ec.category() == bhttp::make_error_code(bhttp::error::end_of_stream).category() && ec != bhttp::error::end_of_stream &&
        ec != bhttp::error::partial_message) {
      ++front_.malformed;
      return refuse(400, "400: " + ec.message() + "\n");
    }
    closeNow();
  }

  void onHead(ErrorCode ec) {
    if (ec) return failed(ec);
    if (state_ != State::kWaiting) return;
    const auto& m = parser_->get();
    int fields = 0, lengths = 0;
    bool length_digits = true;
    for (const auto& f : m) {
      ++fields;
      if (f.name() != bhttp::field::content_length) continue;
      ++lengths;
      for (char ch : f.value()) length_digits = length_digits && ch >= '0' && ch <= '9';
    }
    if (fields > front_.limits.header_fields) {
      ++front_.too_large;
      return refuse(431, "431: over " + std::to_string(front_.limits.header_fields) + " header fields\n");
    }
    if (lengths > 1 || !length_digits) {
      ++front_.malformed;
      return refuse(400, "400: Content-Length must be given once, as one number\n");
    }
    request_ = HttpRequest{};
    request_.method = std::string(m.method_string());
    const std::string_view target(m.target().data(), m.target().size());
    request_.path = std::string(target.substr(0, target.find('?')));
    const std::size_t q = target.find('?');
    request_.query = q == std::string_view::npos ? "" : std::string(target.substr(q + 1));
    request_.token = queryValue(request_.query, "token");
    request_.host = fieldText(m, bhttp::field::host);
    request_.origin = fieldText(m, bhttp::field::origin);
    request_.authorization = fieldText(m, bhttp::field::authorization);
    request_.address = address_;
    if (std::optional<HttpAnswer> no = front_.gate(request_)) return refuse(*no);
    keep_alive_ = m.keep_alive();
    if (parser_->is_done()) return handle();
    if (beast::iequals(fieldText(m, bhttp::field::expect), "100-continue")) {
      static const std::string kContinue = "HTTP/1.1 100 Continue\r\n\r\n";
      net::async_write(socket_, net::buffer(kContinue), [self = shared_from_this()](ErrorCode e, std::size_t) {
        if (e) return self->closeNow();
        self->readBody();
      });
      return;
    }
    readBody();
  }

  void readBody() {
    if (state_ != State::kWaiting) return;
    bhttp::async_read(socket_, buffer_, *parser_, [self = shared_from_this()](ErrorCode ec, std::size_t) {
      if (ec) return self->failed(ec);
      if (self->state_ == State::kWaiting) self->handle();
    });
  }

  void handle() {
    disarm();
    state_ = State::kBusy;
    request_.body = std::move(parser_->get().body());
    front_.dispatch(request_, shared_from_this());
  }

  void refuse(int status, const std::string& text) { refuse(plain(status, text)); }
  void refuse(const HttpAnswer& a) {
    state_ = State::kBusy;
    write(a, false);
  }

  // Writes `a` within write_time; then the next request, or a lingering close.
  void write(const HttpAnswer& a, bool keep_alive) {
    if (state_ == State::kClosed) return;
    auto part = std::make_shared<StreamPart>();
    const std::size_t length = a.bytes ? a.bytes->size() : a.body.size();
    part->head = headOf(a, length, keep_alive);
    if (a.bytes) part->bytes = a.bytes;
    else part->tail = a.body;
    arm(front_.limits.write_time);
    net::async_write(socket_, buffersOf(*part), [self = shared_from_this(), part, keep_alive](ErrorCode ec, std::size_t) {
      if (self->state_ == State::kClosed) return;
      if (ec || self->front_.stopping) {
        self->closeNow();
        return self->front_.stopIfDrained();
      }
      if (keep_alive) return self->readRequest();
      self->lingerClose();
    });
  }

  void lingerClose() {
    state_ = State::kLinger;
    ErrorCode ignored;
    socket_.shutdown(tcp::socket::shutdown_send, ignored);
    arm(kLinger);
    drain();
  }
  void drain() {
    socket_.async_read_some(net::buffer(scratch_), [self = shared_from_this()](ErrorCode ec, std::size_t n) {
      if (self->state_ != State::kLinger) return;
      self->drained_ += n;
      if (ec || self->drained_ > kLingerBytes) return self->closeNow();
      self->drain();
    });
  }

  static std::array<net::const_buffer, 3> buffersOf(const StreamPart& p) {
    return {net::buffer(p.head), p.bytes ? net::buffer(*p.bytes) : net::const_buffer(), net::buffer(p.tail)};
  }

  void writePart(std::shared_ptr<const StreamPart> part) {
    writing_ = true;
    arm(front_.limits.write_time);
    net::async_write(socket_, buffersOf(*part), [self = shared_from_this(), part](ErrorCode ec, std::size_t) {
      if (self->state_ != State::kStream) return;
      if (ec) return self->closeNow();
      self->writing_ = false;
      self->disarm();
      if (self->next_) self->writePart(std::exchange(self->next_, nullptr));
    });
  }

  // A stream's client sends nothing more; a read ending tells it has left.
  void watchForClose() {
    socket_.async_read_some(net::buffer(scratch_), [self = shared_from_this()](ErrorCode ec, std::size_t) {
      if (self->state_ != State::kStream) return;
      if (ec) return self->closeNow();
      self->watchForClose();
    });
  }

  HttpFront::Impl& front_;
  tcp::socket socket_;
  net::steady_timer timer_;
  unsigned long generation_ = 0;  // of the armed deadline; a stale one is ignored
  beast::flat_buffer buffer_{16384};
  std::optional<bhttp::request_parser<bhttp::string_body>> parser_;
  std::string address_;
  HttpRequest request_;
  State state_ = State::kWaiting;
  bool keep_alive_ = false;
  bool streaming_ = false;
  bool writing_ = false;
  std::shared_ptr<const StreamPart> next_;
  std::size_t drained_ = 0;
  std::array<char, 4096> scratch_{};
  std::atomic<bool> open_{true};
};

void HttpFront::Impl::accept() {
  acceptor.async_accept([this](ErrorCode ec, tcp::socket socket) {
    if (stopping) return;
    if (!ec) {
      admit(std::move(socket));
      return accept();
    }
    // Out of descriptors, or the like: try again shortly rather than spin.
    accept_retry.expires_after(Millis(20));
    accept_retry.async_wait([this](ErrorCode e) {
      if (!e && !stopping) accept();
    });
  });
}

// A new connection, within the caps: the oldest idle one (of its address, then of all) gives way
// to it; with nothing idle to close, it is refused.
void HttpFront::Impl::admit(tcp::socket socket) {
  ++accepted;
  ErrorCode ec;
  const tcp::endpoint peer = socket.remote_endpoint(ec);
  if (ec) return;
  const std::string address = peer.address().to_string();
  auto refuseNew = [&](int status, const char* text) {
    ++refused;
    answerAndClose(socket, status, text);
  };
  const auto mine = per_address.find(address);
  if (mine != per_address.end() && mine->second >= limits.connections_per_address && !evictOldestIdle(&address)) {
    return refuseNew(429, "429: too many connections from your address\n");
  }
  if (open.load() >= limits.connections && !evictOldestIdle(nullptr)) {
    return refuseNew(503, "503: too many connections\n");
  }
  auto c = std::make_shared<Connection>(std::move(socket), *this, address);
  c->where = connections.insert(connections.end(), c);
  ++per_address[address];
  ++open;
  c->readRequest();
}

bool HttpFront::Impl::evictOldestIdle(const std::string* address) {
  for (const std::weak_ptr<Connection>& w : connections) {
    const std::shared_ptr<Connection> c = w.lock();
    if (!c || !c->idle() || (address && c->address() != *address)) continue;
    ++evicted;
    c->refuseNow(408, "408: closed to make room for another connection\n");
    return true;
  }
  return false;
}

void HttpFront::Impl::forget(Connection& c) {
  connections.erase(c.where);
  if (--per_address[c.address()] <= 0) per_address.erase(c.address());
  if (c.streaming()) {
    --streams;
    if (--streams_per_address[c.address()] <= 0) streams_per_address.erase(c.address());
  }
  --open;
}

// Stops taking connections and requests; the answers being made or written get up to kLinger to
// go out, then every connection closes.
void HttpFront::Impl::beginStop() {
  stopping = true;
  ErrorCode ignored;
  acceptor.close(ignored);
  accept_retry.cancel();
  std::vector<std::shared_ptr<Connection>> quiet;
  for (const std::weak_ptr<Connection>& w : connections) {
    if (const std::shared_ptr<Connection> c = w.lock(); c && !c->busy()) quiet.push_back(c);
  }
  for (const std::shared_ptr<Connection>& c : quiet) c->closeNow();
  drain_timer.expires_after(kLinger);
  drain_timer.async_wait([this](ErrorCode ec) {
    if (ec) return;
    closeAll();
    io.stop();
  });
  stopIfDrained();
}

void HttpFront::Impl::stopIfDrained() {
  if (!stopping || !connections.empty()) return;
  drain_timer.cancel();
  io.stop();
}

void HttpFront::Impl::closeAll() {
  stopping = true;
  ErrorCode ignored;
  acceptor.close(ignored);
  accept_retry.cancel();
  while (!connections.empty()) {
    const std::shared_ptr<Connection> c = connections.front().lock();
    if (c) c->closeNow();
    else connections.pop_front();
  }
}

HttpFront::HttpFront(const std::string& host, int port, const HttpLimits& limits, Gate gate, Dispatch dispatch)
    : impl_(std::make_shared<Impl>()) {
  Impl& s = *impl_;
  s.limits = limits;
  s.gate = std::move(gate);
  s.dispatch = std::move(dispatch);
  ErrorCode ec;
  const net::ip::address address = net::ip::make_address(host, ec);
  const tcp::endpoint endpoint(address, static_cast<unsigned short>(port));
  if (!ec) s.acceptor.open(endpoint.protocol(), ec);
  // SO_REUSEADDR only (no SO_REUSEPORT): a second run on the port is told it is in use.
  if (!ec) s.acceptor.set_option(net::socket_base::reuse_address(true), ec);
  if (!ec) s.acceptor.bind(endpoint, ec);
  if (!ec) s.acceptor.listen(net::socket_base::max_listen_connections, ec);
  if (ec) {
    throw std::runtime_error("--serve: cannot listen on " + host + ":" + std::to_string(port) + " (" + ec.message() +
                             ")");
  }
}

HttpFront::~HttpFront() { stop(); }

int HttpFront::port() const {
  ErrorCode ec;
  return impl_->acceptor.local_endpoint(ec).port();
}

void HttpFront::start() {
  Impl& s = *impl_;
  s.accept();
  s.thread = std::thread([&s] {
    pthread_setname_np(pthread_self(), "gf-http");
    s.io.run();
  });
}

void HttpFront::stop() {
  Impl& s = *impl_;
  if (s.stopped.exchange(true)) return;
  net::post(s.io, [&s] { s.beginStop(); });
  if (s.thread.joinable()) s.thread.join();
  s.closeAll();  // the thread has ended: what is left closes here
}

HttpCounts HttpFront::counts() const {
  const Impl& s = *impl_;
  return {s.accepted.load(), s.open.load(),      s.refused.load(),  s.evicted.load(),
          s.timed_out.load(), s.malformed.load(), s.too_large.load(), s.streams_refused.load()};
}

}  // namespace gf::app
