// Scene files (TOML) into descriptions, with command-line overrides (--set), and recorded device
// paths. The format is documented field by field in assets/scenes/README.md.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "app/scene/input_error.hpp"
#include "app/scene/session_desc.hpp"

namespace gf::app {

/// Loads a scene file and applies `overrides` ("fields.path=VALUE", VALUE in TOML syntax or a
/// bare string) before validation. Mesh and device CSV paths are relative to the file. Loads
/// every mesh once to check it. Throws InputError.
SessionDesc loadSceneFile(const std::string& path, std::span<const std::string> overrides = {});

/// Same as loadSceneFile, from text; `source_name` names it in errors and `base_dir` resolves
/// relative paths.
SessionDesc parseSceneText(const std::string& text, const std::string& source_name,
                           const std::string& base_dir, std::span<const std::string> overrides = {});

/// A device orientation given as a quaternion (a keyframe's q, a CSV row's qw..qz) may be off
/// unit length by this much (four hand-written decimals are); it is then normalised, and
/// refused beyond.
inline constexpr double kOrientationTolerance = 1e-3;

/// Reads a recorded device path: CSV with a header row "t,x,y,z" (s, m) or
/// "t,x,y,z,qw,qx,qy,qz" (with the device's orientation, a unit quaternion within
/// kOrientationTolerance), strictly increasing times; played back with linear interpolation
/// (the orientation slerped). Throws InputError naming file, line, column and column name.
sim::DeviceTrack readDeviceCsv(const std::string& path);

}  // namespace gf::app
