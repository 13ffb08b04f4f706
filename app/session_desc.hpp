// What a scene file describes beyond the physics: recordings and cameras. Read-only once loaded.
#pragma once

#include <string>
#include <vector>

#include "sim/scene_desc.hpp"

namespace gf::app {

/// What a session writes besides summary.json.
struct RecordSettings {
  bool trace = true;                         ///< trace.csv, one row per haptic step
  std::vector<double> contact_times;         ///< s: contacts/t<time>.json at these times
  std::vector<std::string> force_bodies;     ///< forces.csv: non-gravity force on these bodies
};

/// A camera for the renderer (one is rendered per output stream).
struct CameraDesc {
  std::string name;
  sim::Vec3 position = sim::Vec3(0.3, 0.25, 0.4);  ///< m
  sim::Vec3 target = sim::Vec3::Zero();            ///< m: the point looked at
  double fov_deg = 40.0;                           ///< vertical field of view (degrees)
};

/// A loaded scene file: the physics description plus what to record and how to look at it.
struct SessionDesc {
  sim::SceneDesc scene;
  std::string summary;       ///< one line for `godfinger list`
  std::string source;        ///< the file it came from ("" for built-in scenes)
  std::vector<std::string> overrides;  ///< the --set FIELD=VALUE applied, in order
  RecordSettings record;
  std::vector<CameraDesc> cameras;
};

}  // namespace gf::app
