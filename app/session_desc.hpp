// What a scene file describes beyond the physics: recordings and cameras. Read-only once loaded.
#pragma once

#include <string>
#include <vector>

#include "app/expectations.hpp"
#include "render/view_desc.hpp"
#include "sim/scene_desc.hpp"

namespace gf::app {

/// What a session writes besides summary.json.
struct RecordSettings {
  bool trace = true;                         ///< trace.csv, one row per haptic step
  std::vector<double> contact_times;         ///< s: contacts/t<time>.json at these times
  std::vector<std::string> force_bodies;     ///< forces.csv: non-gravity force on these bodies
  /// forces.png: the y force on the first force body against time, this scene with god-fingers
  /// and again with every finger a god-object (the paper's Fig. 8)
  bool force_chart = false;
  /// The chart's title; empty: "<scene name>: y force on <body> (N, gravity removed)".
  std::string force_chart_title;
};

/// How the scene is drawn: the render effects and the [render] table.
struct ViewSettings {
  bool patch_highlight = false;  ///< effect: contact patches, SGOs, normals, force arrows
  bool shadows = false;          ///< effect: soft shadows from the key light
  bool overlay = false;          ///< effect: the ImGui overlay
  int width = 1280;              ///< frame size (pixels, up to 1920 x 1080)
  int height = 720;
  render::Antialiasing antialiasing = render::Antialiasing::kFxaa;
  int msaa_samples = 4;          ///< samples with antialiasing = "msaa" (2..8)
  std::vector<render::WidgetAction> actions;  ///< scripted overlay input, by time
};

/// A camera for the renderer (one is rendered per output stream).
using CameraDesc = render::Camera;

/// A loaded scene file: the physics description plus what to record and how to look at it.
struct SessionDesc {
  sim::SceneDesc scene;
  std::string summary;       ///< one line for `godfinger list`
  std::string source;        ///< the file it came from ("" for scenes made in code)
  std::vector<std::string> overrides;  ///< the --set FIELD=VALUE applied, in order
  RecordSettings record;
  ExpectDesc expect;  ///< [expect]: what the run must show
  ViewSettings view;
  std::vector<CameraDesc> cameras;
};

}  // namespace gf::app
