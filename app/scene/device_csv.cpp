// A recorded device path: CSV t,x,y,z (or t,x,y,z,qw,qx,qy,qz with an orientation) played back
// with linear interpolation.
#include "app/scene/scene_file.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "app/scene/input_error.hpp"
#include "sim/scene/settings.hpp"

namespace gf::app {

namespace fs = std::filesystem;
using sim::Vec3;

namespace {

constexpr const char* kColumns[] = {"t", "x", "y", "z", "qw", "qx", "qy", "qz"};
constexpr const char* kPositionHeader = "t,x,y,z";
constexpr const char* kOrientedHeader = "t,x,y,z,qw,qx,qy,qz";

// One data row of `count` finite numbers; a bad cell or a wrong count names its line, its
// column (1-based, of the cell's first character) and the column's name.
std::vector<double> readRow(const std::string& path, int number, const std::string& line, int count) {
  std::vector<double> v(static_cast<std::size_t>(count));
  std::size_t pos = 0;
  for (int i = 0; i < count; ++i) {
    const std::size_t end = std::min(line.find(',', pos), line.size());
    const std::string cell = line.substr(pos, end - pos);
    const int column = static_cast<int>(pos) + 1;
    char* stop = nullptr;
    v[static_cast<std::size_t>(i)] = std::strtod(cell.c_str(), &stop);
    if (cell.empty() || *stop != '\0' || !std::isfinite(v[static_cast<std::size_t>(i)])) {
      throw InputError(path, number, column, kColumns[i], "expected a finite number, got '" + cell + "'");
    }
    if ((i + 1 < count) != (end < line.size())) {
      throw InputError(path, number, column, kColumns[i], "expected " + std::to_string(count) + " columns");
    }
    pos = end + 1;
  }
  return v;
}

// A row's qw, qx, qy, qz: a unit quaternion within kOrientationTolerance, normalised.
sim::Quat rowOrientation(const std::string& path, int number, const std::string& line, const std::vector<double>& v) {
  const sim::Quat q(v[4], v[5], v[6], v[7]);
  if (!(std::abs(q.norm() - 1.0) <= kOrientationTolerance)) {
    int column = 1;
    for (int commas = 0; commas < 4; ++column) commas += line[static_cast<std::size_t>(column - 1)] == ',' ? 1 : 0;
    throw InputError(path, number, column, "qw,qx,qy,qz",
                     "must be a unit quaternion (|q| within " + sim::numberText(kOrientationTolerance) +
                         " of 1), got |q| = " + sim::numberText(q.norm()));
  }
  return q.normalized();
}

}  // namespace

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
  int number = 0, count = 4;
  std::vector<int> lines;  // file line of each keyframe
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1) {
      if (line != kPositionHeader && line != kOrientedHeader) {
        throw InputError(path, 1, 1, "header", "expected the header row t,x,y,z or t,x,y,z,qw,qx,qy,qz");
      }
      count = line == kOrientedHeader ? 8 : 4;
      continue;
    }
    if (line.empty()) continue;
    const std::vector<double> v = readRow(path, number, line, count);
    sim::DeviceTrack::Keyframe k{v[0], Vec3(v[1], v[2], v[3])};
    if (count == 8) k.orientation = rowOrientation(path, number, line, v);
    d.keyframes.push_back(k);
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
