#include "app/device/udp_device.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <utility>

#include <arpa/inet.h>
#include <pthread.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "app/scene/scene_file.hpp"
#include "app/device/device_protocol.hpp"
#include "app/process/interrupt.hpp"

namespace gf::app {
namespace {

// "1 packet", "2 packets" (`plural`: when adding an s will not do).
std::string counted(long n, const std::string& noun, const std::string& plural = "") {
  return std::to_string(n) + " " + (n == 1 ? noun : plural.empty() ? noun + "s" : plural);
}

// Counts of things by kind: {2, "wrong size"}.
using Counts = std::vector<std::pair<long, const char*>>;

// The counts that are not zero, "2 wrong size, 1 bad magic"; `none` when all are.
std::string nonZero(const Counts& counts, const char* none = "none") {
  std::string out;
  for (const auto& [n, kind] : counts) {
    if (n != 0) out.append(out.empty() ? "" : ", ").append(std::to_string(n)).append(" ").append(kind);
  }
  return out.empty() ? none : out;
}

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f s", s);
  return text;
}

// 127.x.x.x: only programs on this machine can reach it.
bool isLoopback(const std::string& host) {
  in_addr a{};
  return inet_pton(AF_INET, host.c_str(), &a) == 1 && (ntohl(a.s_addr) >> 24) == 127;
}

}  // namespace

struct UdpDeviceBridge::Socket {
  int fd = -1;
  std::string host;
  int requested_port = 0;                      // as the scene gives it (0: any)
  std::string field;                           // the first finger's udp field, for errors
  int port = 0;                                // bound
  std::array<Device*, 256> by_channel{};       // the finger reading each channel
  double polled_at = std::numeric_limits<double>::quiet_NaN();
  long datagrams = 0, kernel_drops = 0, wrong_size = 0, bad_magic = 0, bad_value = 0, unknown_channel = 0, receive_errors = 0;

  ~Socket() {
    if (fd >= 0) close(fd);
  }
  // Reads what has arrived (at most kMaxDatagramsPerStep datagrams), once per step time t.
  void poll(double t);
  // After the run: what has arrived is read and dropped, counting nothing (the run's figures
  // stand as its last step left them).
  void drain() {
    std::array<std::uint8_t, DevicePacket::kOrientedSize + 1> buffer;
    for (int n = 0; n < kMaxDatagramsPerStep && recv(fd, buffer.data(), buffer.size(), MSG_DONTWAIT) >= 0; ++n) {
    }
  }
  std::string address() const { return host + ":" + std::to_string(port); }
  // The datagrams rejected before their channel was known, by kind.
  Counts rejected() const {
    return {{wrong_size, "wrong size"}, {bad_magic, "bad magic"}, {bad_value, "bad value"},
            {unknown_channel, "for a channel no finger reads"}};
  }
};

class UdpDeviceBridge::Device final : public sim::DeviceSource {
 public:
  Device(const UdpDeviceDesc& desc, std::string finger, double max_force, double dt, Socket& socket)
      : link_(desc, max_force), dt_(dt), channel_(desc.channel), finger_(std::move(finger)), socket_(socket) {}

  sim::DeviceSample sample(double t) override {
    socket_.poll(t);
    return link_.sample(t);
  }

  sim::Vec3 feedback(double t, const sim::DeviceFeedback& f) override {
    last_ = f;
    replied_at_ = t;
    const DeviceReply r = link_.reply(t, f);
    live_taken_.store(link_.counters().taken, std::memory_order_relaxed);
    live_flags_.store((link_.stale() ? 1 : 0) | (link_.ramping() ? 2 : 0), std::memory_order_relaxed);
    live_gain_.store(static_cast<float>(link_.gain()), std::memory_order_relaxed);
    if (!link_.heard()) return link_.sentInScene();  // no one to answer yet
    send(r, peer_);
    // Senders another one displaced: their force fades to zero, and they keep hearing so.
    for (int i = 0; i < link_.displacedCount(); ++i) {
      const DeviceReply d = link_.displacedReply(i, t);
      if (const sockaddr_in* to = addressOf(link_.displaced(i).sender)) send(d, *to);
    }
    return link_.sentInScene();
  }

  // A valid packet of this device's channel, read at step time t from `from`: the replies go
  // to the sender of the newest packet taken; one it displaced keeps its address.
  void take(const DevicePacket& p, double t, const sockaddr_in& from) {
    const long takeovers = link_.counters().takeovers;
    const std::uint64_t last = senderOf(peer_);
    if (!link_.take(p, t, senderOf(from))) return;
    if (link_.counters().takeovers != takeovers) {
      std::copy(former_.begin() + 1, former_.end(), former_.begin());  // the oldest goes
      former_.back() = {last, peer_};
    }
    peer_ = from;
  }

  // After the run: replies after t fade the last step's force out (DeviceLink::endAt); packets
  // are no longer taken, and the replies are counted apart.
  void endAt(double t) {
    link_.endAt(t);
    run_replies_ = replies_;
  }
  // The ending's step before time t: nothing is taken; the reply after it, the last step's
  // feedback (its touching, radius and SGOs too) with the force fading.
  void answerEnding(double t) {
    socket_.drain();
    link_.sample(t);
    feedback(t + dt_, last_);
  }
  double repliedAt() const { return replied_at_; }
  long endingReplies() const { return run_replies_ >= 0 ? replies_ - run_replies_ : 0; }

  const Socket& socket() const { return socket_; }
  const DeviceLink& link() const { return link_; }
  const std::string& finger() const { return finger_; }
  int channel() const { return channel_; }
  long replies() const { return run_replies_ >= 0 ? run_replies_ : replies_; }  // the run's
  long sendErrors() const { return send_errors_; }
  std::string field() const { return "fingers." + finger_ + ".device"; }
  // The link as of the last step, for a watcher on another thread.
  nlohmann::json liveJson() const {
    const int flags = live_flags_.load(std::memory_order_relaxed);
    return {{"finger", finger_},
            {"address", socket_.address()},
            {"channel", channel_},
            {"packets", live_taken_.load(std::memory_order_relaxed)},
            {"stale", (flags & 1) != 0},
            {"ramping", (flags & 2) != 0},
            {"gain", live_gain_.load(std::memory_order_relaxed)}};
  }

  nlohmann::json json(const std::string& address, double dt) const {
    const DeviceLink::Counters& c = link_.counters();
    return {{"finger", finger_},
            {"address", address},
            {"channel", channel_},
            {"packets_taken", c.taken},
            {"out_of_order", c.out_of_order},
            {"lost", c.lost},
            {"out_of_range", c.out_of_range},
            {"superseded", c.superseded},
            {"first_packet_s", link_.heard() ? nlohmann::json(std::round(link_.firstPacketTime() * 1e9) / 1e9)
                                             : nlohmann::json(nullptr)},
            {"last_seq", link_.lastSeq()},
            {"buttons", link_.buttons()},
            {"stale_periods", c.stale_periods},
            {"stale_s", static_cast<double>(c.stale_steps) * dt},
            {"takeovers", c.takeovers},
            {"displaced_replies", c.displaced_replies},
            {"replies_sent", replies()},
            {"ending_replies", endingReplies()},
            {"send_errors", send_errors_}};
  }

 private:
  static std::uint64_t senderOf(const sockaddr_in& a) {
    return (std::uint64_t{ntohl(a.sin_addr.s_addr)} << 16) | ntohs(a.sin_port);
  }
  const sockaddr_in* addressOf(std::uint64_t sender) const {
    for (const auto& [key, address] : former_) {
      if (key == sender && address.sin_family == AF_INET) return &address;
    }
    return nullptr;
  }
  void send(const DeviceReply& r, const sockaddr_in& to) {
    std::array<std::uint8_t, DeviceReply::kSize> bytes;
    encodeDeviceReply(r, bytes);
    const ssize_t sent = sendto(socket_.fd, bytes.data(), bytes.size(), MSG_DONTWAIT,
                                reinterpret_cast<const sockaddr*>(&to), sizeof to);
    if (sent == static_cast<ssize_t>(bytes.size())) ++replies_;
    else ++send_errors_;
  }

  DeviceLink link_;
  const double dt_;           // s: the haptic step
  sim::DeviceFeedback last_;  // the last step's, which the ending fades out
  double replied_at_ = 0.0;   // s: the last reply's step time
  long run_replies_ = -1;     // the replies the run's steps sent (-1: the run goes on)
  std::atomic<long> live_taken_{0};
  std::atomic<int> live_flags_{1};  // bit 0 stale, bit 1 ramping
  std::atomic<float> live_gain_{0.0f};
  const int channel_;
  const std::string finger_;
  Socket& socket_;
  sockaddr_in peer_{};
  // The addresses of senders displaced (twice DeviceLink's, so none it still answers is lost).
  std::array<std::pair<std::uint64_t, sockaddr_in>, 2 * DeviceLink::kMaxDisplaced> former_{};
  long replies_ = 0, send_errors_ = 0;
};

void UdpDeviceBridge::Socket::poll(double t) {
  if (polled_at == t) return;
  polled_at = t;
  // One byte more than a packet, so a longer datagram shows as one (MSG_TRUNC gives its length);
  // the control message carries the kernel's count of datagrams dropped on a full buffer.
  std::array<std::uint8_t, DevicePacket::kOrientedSize + 1> buffer;
  alignas(cmsghdr) std::array<char, CMSG_SPACE(sizeof(std::uint32_t))> control;
  for (int n = 0; n < kMaxDatagramsPerStep; ++n) {
    sockaddr_in from{};
    iovec io{buffer.data(), buffer.size()};
    msghdr message{};
    message.msg_name = &from;
    message.msg_namelen = sizeof from;
    message.msg_iov = &io;
    message.msg_iovlen = 1;
    message.msg_control = control.data();
    message.msg_controllen = control.size();
    const ssize_t size = recvmsg(fd, &message, MSG_DONTWAIT | MSG_TRUNC);
    if (size < 0) {
      if (errno == EINTR) continue;
      if (errno != EAGAIN && errno != EWOULDBLOCK) ++receive_errors;
      return;
    }
    for (cmsghdr* c = CMSG_FIRSTHDR(&message); c; c = CMSG_NXTHDR(&message, c)) {
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
        std::uint32_t dropped = 0;
        std::memcpy(&dropped, CMSG_DATA(c), sizeof dropped);
        kernel_drops = std::max<long>(kernel_drops, dropped);
      }
    }
    ++datagrams;
    DevicePacket p;
    const auto length = std::min(static_cast<std::size_t>(size), buffer.size());
    switch (parseDevicePacket(std::span<const std::uint8_t>(buffer.data(), length), p)) {
      case PacketError::kSize: ++wrong_size; continue;
      case PacketError::kMagic: ++bad_magic; continue;
      case PacketError::kBadValue: ++bad_value; continue;
      case PacketError::kNone: break;
    }
    Device* d = p.channel < by_channel.size() ? by_channel[p.channel] : nullptr;
    if (!d) {
      ++unknown_channel;
      continue;
    }
    d->take(p, t, from);
  }
}

UdpDeviceBridge::UdpDeviceBridge(const SessionDesc& session)
    : sources_(session.scene.fingers.size(), nullptr), dt_(1.0 / session.scene.world.haptic_rate_hz),
      name_(session.scene.name) {
  for (const UdpDeviceDesc& d : session.udp_devices) {
    longest_ramp_ = std::max(longest_ramp_, d.force_ramp);
    const sim::FingerDesc& finger = session.scene.fingers[static_cast<std::size_t>(d.finger)];
    const std::string field = "fingers." + finger.name + ".device.udp";
    const auto fail = [&](const std::string& at, const std::string& why) {
      throw InputError(d.file, d.line, d.column, at, why);
    };
    Socket* socket = nullptr;
    for (const std::unique_ptr<Socket>& s : sockets_) {
      if (s->requested_port != d.port) continue;
      if (s->host == d.host) {
        socket = s.get();  // fingers giving one address share its socket (port 0: one free port)
      } else if (d.port != 0) {
        fail(field, d.host + ":" + std::to_string(d.port) + " and " + s->field + " (" + s->host + ":" +
                        std::to_string(d.port) + ") cannot both listen on port " + std::to_string(d.port) +
                        ": give both the same address, and each finger its own channel");
      }
    }
    if (!socket) {
      auto s = std::make_unique<Socket>();
      s->host = d.host;
      s->requested_port = d.port;
      s->field = field;
      sockaddr_in address{};
      address.sin_family = AF_INET;
      address.sin_port = htons(static_cast<std::uint16_t>(d.port));
      if (inet_pton(AF_INET, d.host.c_str(), &address.sin_addr) != 1) fail(field, "'" + d.host + "' is not an IPv4 address");
      s->fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
      if (s->fd < 0 || bind(s->fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
        fail(field, "cannot listen on " + d.host + ":" + std::to_string(d.port) + ": " + std::strerror(errno));
      }
      // Room for bursts (the kernel caps it at net.core.rmem_max), and the kernel's count of
      // datagrams dropped when the buffer is full anyway.
      const int buffer = kReceiveBufferBytes, on = 1;
      setsockopt(s->fd, SOL_SOCKET, SO_RCVBUF, &buffer, sizeof buffer);
      setsockopt(s->fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on);
      socklen_t size = sizeof address;
      getsockname(s->fd, reinterpret_cast<sockaddr*>(&address), &size);
      s->port = ntohs(address.sin_port);
      socket = sockets_.emplace_back(std::move(s)).get();
    }
    if (socket->by_channel[static_cast<std::size_t>(d.channel)]) {
      fail("fingers." + finger.name + ".device.channel",
           "channel " + std::to_string(d.channel) + " of " + d.host + ":" + std::to_string(socket->port) +
               " already drives another finger; give each finger on one port its own channel");
    }
    auto device = std::make_unique<Device>(d, finger.name, finger.coupling.max_force, dt_, *socket);
    socket->by_channel[static_cast<std::size_t>(d.channel)] = device.get();
    sources_[static_cast<std::size_t>(d.finger)] = device.get();
    devices_.push_back(std::move(device));
  }
}

// The run never said it ended (it threw): its devices fade from their last replies, unless
// none is told a force.
UdpDeviceBridge::~UdpDeviceBridge() {
  try {
    // Before endRun no other thread touches the links; after it, the ending's thread does.
    if (!ended_ && !toldNothing()) {
      double t = 0.0;
      for (const std::unique_ptr<Device>& d : devices_) t = std::max(t, d->repliedAt());
      endRun(t);
    }
    awaitFade(false, {});
    stopEnding();
  } catch (const std::exception& e) {  // no thread to be had: the devices are told nothing more
    std::fprintf(stderr, "%s: the UDP devices' force could not fade out: %s\n", name_.c_str(), e.what());
  }
}

void UdpDeviceBridge::endRun(double t) {
  if (ended_ || devices_.empty()) return;
  ended_ = true;
  for (const std::unique_ptr<Device>& d : devices_) d->endAt(t);
  const SignalsBlocked quiet;  // Ctrl-C and SIGTERM stay the run's thread's
  try {
    ending_ = std::thread([this, t] { answerWhileEnding(t); });
  } catch (const std::exception& e) {  // the outputs still get written; the devices hear no more
    std::fprintf(stderr, "%s: warning: the UDP devices' force cannot fade out (%s): the last step's stands\n",
                 name_.c_str(), e.what());
  }
}

// One step time after another in real time, as the loop's: the first reply a step after the
// run's last.
void UdpDeviceBridge::answerWhileEnding(double t) {
  pthread_setname_np(pthread_self(), "gf-udp-end");
  using Clock = std::chrono::steady_clock;
  const auto tick = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(dt_));
  auto next = Clock::now() + tick;
  std::unique_lock lock(ending_mutex_);
  while (!ending_changed_.wait_until(lock, next, [&] { return stop_ending_; })) {
    for (const std::unique_ptr<Device>& d : devices_) d->answerEnding(t);
    t += dt_;
    ending_changed_.notify_all();
    next += tick;
    if (Clock::now() > next + 10 * tick) next = Clock::now();  // far behind (a busy machine): no burst
  }
}

void UdpDeviceBridge::awaitFade(bool say, const std::function<bool()>& cut_short) {
  if (!ending_.joinable()) return;
  std::unique_lock lock(ending_mutex_);
  const auto told_nothing = [this] { return toldNothing(); };
  if (told_nothing()) return;
  // The fade: the gain's force_ramp, then the rate limit's (at most as long again), and room
  // for a busy machine.
  const double most = 2.0 * longest_ramp_ + 20.0 * dt_ + 0.5;
  if (say) {
    lock.unlock();  // stderr may block: the devices are answered meanwhile
    std::fprintf(stderr, "%s: fading the UDP devices' force to zero (at most %.1f s)\n", name_.c_str(), most);
    lock.lock();
  }
  // In slices, so that `cut_short` is looked at while the fade goes on.
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(most);
  while (!told_nothing() && std::chrono::steady_clock::now() < until && !(cut_short && cut_short())) {
    ending_changed_.wait_for(lock, std::chrono::milliseconds(20), told_nothing);
  }
}

bool UdpDeviceBridge::toldNothing() const {
  return std::all_of(devices_.begin(), devices_.end(), [](const auto& d) { return d->link().toldNothing(); });
}

void UdpDeviceBridge::stopEnding() {
  if (!ending_.joinable()) return;
  {
    const std::lock_guard lock(ending_mutex_);
    stop_ending_ = true;
  }
  ending_changed_.notify_all();
  ending_.join();
}

std::string UdpDeviceBridge::address(int finger) const {
  for (const std::unique_ptr<Device>& d : devices_) {
    if (d.get() == sources_[static_cast<std::size_t>(finger)]) return d->socket().host + ":" + std::to_string(d->socket().port);
  }
  return "";
}

nlohmann::json UdpDeviceBridge::liveJson() const {
  nlohmann::json out = nlohmann::json::array();
  for (const std::unique_ptr<Device>& d : devices_) out.push_back(d->liveJson());
  return out;
}

nlohmann::json UdpDeviceBridge::json() const {
  const std::lock_guard lock(ending_mutex_);  // the ending's thread may be answering
  nlohmann::json sockets = nlohmann::json::array(), fingers = nlohmann::json::array();
  for (const std::unique_ptr<Socket>& s : sockets_) {
    sockets.push_back({{"address", s->host + ":" + std::to_string(s->port)},
                       {"datagrams", s->datagrams},
                       {"kernel_drops", s->kernel_drops},
                       {"wrong_size", s->wrong_size},
                       {"bad_magic", s->bad_magic},
                       {"bad_value", s->bad_value},
                       {"unknown_channel", s->unknown_channel},
                       {"receive_errors", s->receive_errors}});
  }
  for (const std::unique_ptr<Device>& d : devices_) {
    fingers.push_back(d->json(d->socket().host + ":" + std::to_string(d->socket().port), dt_));
  }
  return {{"sockets", sockets}, {"fingers", fingers}};
}

std::vector<std::string> UdpDeviceBridge::bindWarnings() const {
  std::vector<std::string> warnings;
  for (const std::unique_ptr<Socket>& s : sockets_) {
    if (isLoopback(s->host)) continue;
    std::string fingers;
    int count = 0;
    for (const std::unique_ptr<Device>& d : devices_) {
      if (&d->socket() == s.get()) fingers.append(count++ == 0 ? "" : ", ").append(d->field());
    }
    const bool one = count == 1;
    const std::string where =
        s->host == "0.0.0.0" ? "every interface (" + s->address() + ")" : s->address() + ", beyond loopback";
    warnings.push_back(fingers + (one ? " listens on " : " listen on ") + where +
                       ": anyone who can reach this machine on UDP port " + std::to_string(s->port) +
                       (one ? " can drive the finger and is sent its" : " can drive the fingers and is sent their") +
                       " forces; give 127.0.0.1 unless the device program runs on another machine");
  }
  return warnings;
}

std::vector<std::string> UdpDeviceBridge::report() const {
  const std::lock_guard lock(ending_mutex_);  // the ending's thread may be answering
  std::vector<std::string> lines;
  for (const std::unique_ptr<Device>& d : devices_) {
    const Socket& s = d->socket();
    const DeviceLink::Counters& c = d->link().counters();
    // Taken, and what became of the others: this channel's, then the whole socket's.
    std::string line = d->field() + " (" + s.address() + ", channel " + std::to_string(d->channel()) + "): " +
                       counted(c.taken, "packet") + " taken";
    const std::string taken =
        nonZero({{c.lost, "lost"}, {c.superseded, "superseded"}, {c.takeovers, "from a new sender"}}, "");
    if (!taken.empty()) line += " (" + taken + ")";
    line += "; rejected on its channel: " + nonZero({{c.out_of_order, "out of order"}, {c.out_of_range, "out of range"}});
    line += "; its socket read " + counted(s.datagrams, "datagram") + ", rejected: " + nonZero(s.rejected());
    const std::string lost =
        nonZero({{s.kernel_drops, "dropped by the kernel (buffer full)"}, {s.receive_errors, "receive errors"}}, "");
    if (!lost.empty()) line += ", " + lost;
    // Then how long it was stale, and what was sent back.
    line += "; stale " + seconds(static_cast<double>(c.stale_steps) * dt_) + " (" +
            counted(c.stale_periods, "dropout") + "); " + counted(d->replies(), "reply", "replies") + " sent";
    if (d->endingReplies() > 0) line += " and " + std::to_string(d->endingReplies()) + " after the last step (flagged ending)";
    if (d->sendErrors() > 0) line += ", " + counted(d->sendErrors(), "send error");
    lines.push_back(std::move(line));
  }
  return lines;
}

std::vector<std::string> UdpDeviceBridge::runWarnings() const {
  const std::lock_guard lock(ending_mutex_);  // the ending's thread may be answering
  std::vector<std::string> warnings;
  for (const std::unique_ptr<Device>& d : devices_) {
    const Socket& s = d->socket();
    const DeviceLink::Counters& c = d->link().counters();
    if (c.taken > 0) continue;
    const std::string at = s.address() + ", channel " + std::to_string(d->channel());
    if (s.datagrams == 0) {  // never heard: stale at every step, so its stale time is the run's
      warnings.push_back(d->field() + ": no packet came to " + s.address() + " in the run's " +
                         seconds(static_cast<double>(c.stale_steps) * dt_) +
                         ": the finger stayed at its start; is the device program running and sending to " + at + "?");
      continue;
    }
    // Datagrams came and none was taken for this finger: what became of them.
    Counts why = s.rejected();
    why.emplace_back(c.out_of_range, "out of range");
    long others = 0;  // valid packets of the other fingers' channels on this socket
    for (const std::unique_ptr<Device>& o : devices_) {
      const DeviceLink::Counters& oc = o->link().counters();
      if (o != d && &o->socket() == &s) others += oc.taken + oc.out_of_order + oc.out_of_range;
    }
    why.emplace_back(others, "for the other fingers' channels");
    warnings.push_back(d->field() + ": took none of the " + counted(s.datagrams, "datagram") + " read on " + s.address() +
                       " (channel " + std::to_string(d->channel()) + "): " + nonZero(why) +
                       (s.bad_magic > 0 ? " (packets of this protocol start with the bytes \"GFD1\")" : "") +
                       "; the finger stayed at its start");
  }
  return warnings;
}

}  // namespace gf::app
