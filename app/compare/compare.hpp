// `godfinger compare`: the same scene and device tracks run once per contact model (offline,
// each a `godfinger run` process), then one video whose frames hold a panel per model (same
// camera, labelled with the model, its settings and its step time; three or four in a 2 x 2
// grid) above a chart of a trace quantity for every model (a line style and marker per model),
// with a cursor at the frame's time and that time beside it; summary.json per model and one
// compare.json with the headline measures side by side.
#pragma once

#include <string>
#include <vector>

#include "render/chart/compare_view.hpp"
#include "render/frames/image.hpp"

namespace gf::app {

struct CompareOptions {
  std::string scene;                   ///< scene file or bundled scene name
  /// 1..4 models, each a `contact_model` name, or god_finger_3dof (a god-finger with
  /// pad_model "disc") or god_finger_6dof (pad_model "oriented")
  std::vector<std::string> models;
  std::vector<std::string> overrides;  ///< --set for every run
  double duration = 0.0;               ///< s; 0: the scene's
  std::string out;                     ///< folder (default compare-SCENE)
  std::string video;                   ///< MP4 of the comparison; empty: none
  bool frames = false;                 ///< out/frames/000000.png ... (always when there is no video)
  bool keep_run_frames = false;        ///< keep each run's own frames (out/MODEL/frames)
  std::string camera;                  ///< the scene's camera (default its first)
  /// The chart's quantity: of `body`, "rotation" (the angle it turned since the start, deg: a
  /// rolling ball's keeps growing), "tilt" (its y axis from upright, 0 to 180 deg), "height"
  /// (mm) or "speed" (m/s); or any trace.csv column. Empty: the tilt, or a sphere's rotation.
  std::string chart;
  std::string body;                    ///< default: the scene's first dynamic body
  int jobs = 1;                        ///< runs at a time
  std::string godfinger;               ///< the executable the runs are started with
  bool quiet = false;
};

/// The --set lines that make every finger of `fingers` (names) the compare model `model`:
/// `fingers.F.contact_model=MODEL`, or for god_finger_3dof / god_finger_6dof
/// `fingers.F.contact_model=god_finger` and `fingers.F.pad_model=disc` / `=oriented`.
std::vector<std::string> compareModelOverrides(const std::vector<std::string>& fingers, const std::string& model);

/// Runs the comparison; 0 when every run finished (an [expect] failing is reported, not an
/// error), 1 when a run failed, 130/143 when interrupted. Throws InputError for bad options.
int runCompare(const CompareOptions& options);

/// One comparison frame rendered in-process (no child processes, no step times): each model's
/// run of `scene` with `overrides` up to `time` (s), its chart (the default quantity) over
/// [0, duration], for a width x height scene frame (compareLayout gives the picture's size). For the visual-regression goldens. Throws InputError, render::GlError.
render::Image renderCompareFrame(const std::string& scene, const std::vector<std::string>& models,
                                 const std::vector<std::string>& overrides, double time, double duration, int width,
                                 int height, const std::string& camera);

}  // namespace gf::app
