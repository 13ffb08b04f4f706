// Fuzzes the `live` command interpreter (app::runLive) on the bundled press-box scene: the input
// is the command stream. At most kMaxSteps haptic steps per input (an input asking for more is
// skipped, so no input can run for long); snapshots go to a scratch folder of this process.
// Every line must get an "ok" or "error:" answer; nothing may escape runLive.
#include <unistd.h>

#include <charconv>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "app/session/live.hpp"

namespace {

namespace fs = std::filesystem;

constexpr long kMaxSteps = 200;

// The haptic steps the input's "step" lines ask for, read as live.cpp reads them (whole words;
// a bad count is an error that steps nothing), or kMaxSteps + 1 once over the limit.
long requestedSteps(const std::string& input) {
  std::istringstream lines(input);
  long total = 0;
  for (std::string line; std::getline(lines, line) && total <= kMaxSteps;) {
    std::istringstream split(line);
    std::vector<std::string> w;
    for (std::string word; split >> word;) w.push_back(word);
    if (w.empty() || w[0] != "step") continue;
    if (w.size() == 1) {
      ++total;
      continue;
    }
    long n = 0;
    const auto [end, ec] = std::from_chars(w[1].data(), w[1].data() + w[1].size(), n);
    if (ec == std::errc() && n > 0) total += std::min(n, kMaxSteps + 1);
  }
  return total;
}

fs::path scratchDir() {
  const fs::path shm = "/dev/shm";
  const fs::path dir = (fs::is_directory(shm) ? shm : fs::temp_directory_path()) /
                       ("gf-fuzz-live-" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  if (requestedSteps(input) > kMaxSteps) return -1;  // too long a run: not kept in the corpus
  static const fs::path dir = scratchDir();
  gf::app::LiveOptions options;
  options.scene_path = GF_SOURCE_DIR "/assets/scenes/press-box.toml";
  options.out_dir = dir.string();
  std::istringstream in(input);
  std::ostringstream out;
  gf::app::runLive(options, in, out);
  fs::remove_all(dir / "contacts");
  return 0;
}
