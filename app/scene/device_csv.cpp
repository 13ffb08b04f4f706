// A recorded device path: CSV t,x,y,z played back with linear interpolation.
#include "app/scene/scene_file.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "app/scene/input_error.hpp"
#include "sim/settings.hpp"

namespace gf::app {

namespace fs = std::filesystem;
using sim::Vec3;

sim::DeviceTrack readDeviceCsv(const std::string& path) {
  // A device, a pipe or /dev/zero would be read without end.
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec)) {
    throw InputError(path, 0, 0, "", "the device CSV is not a regular file");
  }
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, 0, "", "cannot open the device CSV");
  sim::DeviceTrack d;
  d.interpolation = sim::Interpolation::kLinear;
  std::string line;
  int number = 0;
  std::vector<int> lines;  // file line of each keyframe
  constexpr const char* kColumns[] = {"t", "x", "y", "z"};
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1) {
      if (line != "t,x,y,z") throw InputError(path, 1, 0, "header", "expected the header row t,x,y,z");
      continue;
    }
    if (line.empty()) continue;
    double v[4];
    std::size_t pos = 0;
    for (int i = 0; i < 4; ++i) {
      const std::size_t end = std::min(line.find(',', pos), line.size());
      const std::string cell = line.substr(pos, end - pos);
      char* stop = nullptr;
      v[i] = std::strtod(cell.c_str(), &stop);
      if (cell.empty() || *stop != '\0' || !std::isfinite(v[i])) {
        throw InputError(path, number, 0, kColumns[i], "expected a finite number, got '" + cell + "'");
      }
      if ((i < 3) != (end < line.size())) throw InputError(path, number, 0, kColumns[i], "expected 4 columns");
      pos = end + 1;
    }
    d.keyframes.push_back({v[0], Vec3(v[1], v[2], v[3])});
    lines.push_back(number);
  }
  if (d.keyframes.empty()) throw InputError(path, number, 0, "", "no sample after the header");
  if (const std::optional<sim::FieldError> e = sim::validateTrack(d)) {
    throw InputError(path, lines[static_cast<std::size_t>(e->index)], 0, e->field == "keyframes.t" ? "t" : "x,y,z",
                     e->reason);
  }
  return d;
}

}  // namespace gf::app
