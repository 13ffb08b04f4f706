#include "app/runs/trace.hpp"

#include <atomic>
#include <charconv>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace gf::app {

void appendNumber(std::string& out, double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f.write(text.data(), static_cast<std::streamsize>(text.size()));
    f.close();
    if (!f) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);  // no half file left behind
      throw std::runtime_error(path + ": cannot write (disk full?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error(path + ": cannot replace: " + ec.message());
}

namespace {
// Room past a full block for the row that fills it, so rows of up to this length never reallocate.
constexpr std::size_t kRowMargin = 64 * 1024;
}  // namespace

struct StreamedFile::Writer {
  std::string path, tmp;
  std::ofstream out;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::unique_ptr<std::string>> full;   // owner -> writer
  std::vector<std::unique_ptr<std::string>> free;  // writer -> owner, emptied, capacity kept
  bool closing = false;
  std::atomic<bool> failed{false};  // set by the writer, seen by the owner at its next hand-over
  bool closed = false;
  std::thread thread;

  void run() {
    for (;;) {
      std::unique_ptr<std::string> next;
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return !full.empty() || closing; });
        if (full.empty()) return;
        next = std::move(full.front());
        full.pop_front();
      }
      if (!failed) {
        out.write(next->data(), static_cast<std::streamsize>(next->size()));
        if (!out) failed = true;  // read by the owner only after join()
      }
      next->clear();
      std::lock_guard lock(mutex);
      free.push_back(std::move(next));
    }
  }
};

StreamedFile::StreamedFile(std::string path) : writer_(std::make_unique<Writer>()) {
  Writer& w = *writer_;
  w.path = std::move(path);
  w.tmp = w.path + ".tmp";
  w.out.open(w.tmp, std::ios::binary | std::ios::trunc);
  if (!w.out) throw std::runtime_error(w.tmp + ": cannot create");
  for (int i = 0; i < 3; ++i) {
    auto spare = std::make_unique<std::string>();
    spare->reserve(kBlockBytes + kRowMargin);
    w.free.push_back(std::move(spare));
  }
  block_ = std::move(w.free.back());
  w.free.pop_back();
  w.thread = std::thread([&w] { w.run(); });
}

StreamedFile::~StreamedFile() {
  try {
    close();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "[godfinger] %s\n", e.what());
  }
}

void StreamedFile::handOverFull() {
  // A write that failed (a full disk) stops the owner now, not at close().
  if (writer_->failed.load(std::memory_order_relaxed)) throw std::runtime_error(writer_->path + ": cannot write (disk full?)");
  handOver();
}

void StreamedFile::handOver() {
  Writer& w = *writer_;
  std::unique_ptr<std::string> next;
  {
    std::lock_guard lock(w.mutex);
    w.full.push_back(std::move(block_));
    if (!w.free.empty()) {
      next = std::move(w.free.back());
      w.free.pop_back();
    }
  }
  w.changed.notify_one();
  if (!next) {  // the writer is behind (a slow disk): one more block rather than a wait
    next = std::make_unique<std::string>();
    next->reserve(kBlockBytes + kRowMargin);
  }
  block_ = std::move(next);
}

void StreamedFile::close() {
  Writer& w = *writer_;
  if (w.closed) return;
  w.closed = true;
  if (!block_->empty()) handOver();
  {
    std::lock_guard lock(w.mutex);
    w.closing = true;
  }
  w.changed.notify_one();
  w.thread.join();
  w.out.close();
  if (w.failed || !w.out) {
    std::error_code ignored;
    std::filesystem::remove(w.tmp, ignored);
    throw std::runtime_error(w.path + ": cannot write (disk full?); its rows could not be kept");
  }
  std::error_code ec;
  std::filesystem::rename(w.tmp, w.path, ec);
  if (ec) throw std::runtime_error(w.path + ": cannot replace: " + ec.message());
}

std::vector<std::string> traceColumns(const sim::SceneDesc& d) {
  std::vector<std::string> out = {"t"};
  for (const sim::BodyDesc& b : d.bodies) {
    if (b.mass <= 0.0) continue;
    for (const char* c : {".px", ".py", ".pz", ".qx", ".qy", ".qz", ".qw"}) out.push_back(b.name + c);
  }
  for (const sim::FingerDesc& f : d.fingers) {
    for (const char* c : {".fx", ".fy", ".fz", ".n_sgo", ".r", ".px", ".py", ".pz", ".dx", ".dy", ".dz"}) out.push_back(f.name + c);
  }
  for (const sim::BodyDesc& b : d.bodies) {
    if (b.mass <= 0.0) continue;
    for (const char* c : {".vx", ".vy", ".vz", ".wx", ".wy", ".wz"}) out.push_back(b.name + c);
  }
  return out;
}

TraceWriter::TraceWriter(const sim::World& world, const std::string& path) : file_(path) {
  const sim::SceneDesc& d = world.desc();
  for (std::size_t b = 0; b < d.bodies.size(); ++b) {
    if (d.bodies[b].mass > 0.0) dynamic_bodies_.push_back(static_cast<int>(b));
  }
  std::string& text = file_.block();
  for (const std::string& column : traceColumns(d)) {
    if (!text.empty()) text += ',';
    text += column;
  }
  text += '\n';
  file_.rowDone();
}

void TraceWriter::record(const sim::World& world) {
  std::string& text = file_.block();
  appendNumber(text, world.time());
  for (int b : dynamic_bodies_) {
    const sim::Pose p = world.bodyPose(b);
    for (double x : {p.position.x(), p.position.y(), p.position.z(), p.orientation.x(),
                     p.orientation.y(), p.orientation.z(), p.orientation.w()}) {
      text += ',';
      appendNumber(text, x);
    }
  }
  for (int f = 0; f < static_cast<int>(world.desc().fingers.size()); ++f) {
    const sim::Vec3 force = world.couplingForce(f), proxy = world.proxyPosition(f), device = world.devicePosition(f);
    for (double x : {force.x(), force.y(), force.z(), double(world.sgoCount(f)), world.contactRadius(f), proxy.x(),
                     proxy.y(), proxy.z(), device.x(), device.y(), device.z()}) {
      text += ',';
      appendNumber(text, x);
    }
  }
  for (int b : dynamic_bodies_) {
    const sim::Vec3 v = world.bodyLinearVelocity(b), w = world.bodyAngularVelocity(b);
    for (double x : {v.x(), v.y(), v.z(), w.x(), w.y(), w.z()}) {
      text += ',';
      appendNumber(text, x);
    }
  }
  text += '\n';
  file_.rowDone();
}

}  // namespace gf::app
