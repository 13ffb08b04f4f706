#include "app/compare/compare.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <exception>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <unistd.h>

#include "app/compare/chart_quantity.hpp"
#include "app/runs/files.hpp"
#include "app/runs/jobs.hpp"
#include "app/runs/run_folder.hpp"
#include "app/runs/run_reader.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "app/process/console.hpp"
#include "app/process/interrupt.hpp"
#include "app/session/session.hpp"
#include "render/gl/context.hpp"
#include "render/frames/frame_sinks.hpp"
#include "render/render_thread.hpp"
#include "sim/loop/haptic_loop.hpp"
#include "sim/scene/settings.hpp"
#include "sim/world/world.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

// The pad model a compare model name stands for (a god-finger with it), or null.
const char* padModelOf(const std::string& model) {
  if (model == "god_finger_3dof") return "disc";
  if (model == "god_finger_6dof") return "oriented";
  return nullptr;
}

const sim::Setting<sim::FingerDesc>& contactModelSetting() {
  return *sim::findSetting(sim::fingerSettings(), "contact_model");
}

// The --set lines giving every finger of the scene `model`.
std::vector<std::string> modelOverrides(const SessionDesc& session, const std::string& model) {
  std::vector<std::string> names;
  for (const sim::FingerDesc& f : session.scene.fingers) names.push_back(f.name);
  return compareModelOverrides(names, model);
}

// The models, checked: 1..4 known contact models or pad models, none twice.
void checkModels(const std::vector<std::string>& models) {
  if (models.empty() || models.size() > 4) {
    throw commandLineError("--models", "give 1 to 4 contact models, e.g. god_object,god_finger");
  }
  for (std::size_t i = 0; i < models.size(); ++i) {
    const bool pad = padModelOf(models[i]) != nullptr;
    if (!pad && sim::choiceIndex(contactModelSetting(), models[i]) < 0) {
      throw commandLineError("--models",
                       "unknown contact model '" + models[i] + "' (one of " + sim::choiceList(contactModelSetting()) +
                           ", god_finger_3dof, god_finger_6dof)");
    }
    if (std::find(models.begin(), models.begin() + static_cast<long>(i), models[i]) != models.begin() + static_cast<long>(i)) {
      throw commandLineError("--models", "'" + models[i] + "' is given twice");
    }
  }
}

// Each model's session: the scene with the overrides, then the model on every finger.
std::vector<SessionDesc> modelSessions(const std::string& scene_path, const std::vector<std::string>& models,
                                       const std::vector<std::string>& overrides, const SessionDesc& base) {
  std::vector<SessionDesc> out;
  for (const std::string& m : models) {
    std::vector<std::string> set = overrides;
    for (const std::string& o : modelOverrides(base, m)) set.push_back(o);
    out.push_back(loadSceneFile(scene_path, set));
  }
  return out;
}

int framesIn(const fs::path& folder) {
  int n = 0;
  while (fs::exists(folder / frameFileName(n))) ++n;
  return n;
}


// The scene's base session, refusing what a comparison cannot run: a live device.
SessionDesc baseSession(const std::string& scene_path, const std::vector<std::string>& overrides) {
  SessionDesc base = loadSceneFile(scene_path, overrides);
  if (!base.udp_devices.empty()) {
    throw InputError(scene_path, 0, 0, "device.udp", "a live UDP device drives this scene: compare needs recorded device tracks");
  }
  return base;
}

// The overlay draws its own panels into each run's frames, and its scripted clicks change the
// settings being compared: the runs go without it, and a scene whose script changes them is
// refused. Returns the overrides every run gets.
std::vector<std::string> runOverrides(const SessionDesc& base, const std::string& scene_path,
                                      const std::vector<std::string>& given) {
  std::vector<std::string> overrides = given;
  if (!base.view.overlay) return overrides;
  if (!base.view.actions.empty()) {
    throw InputError(scene_path, 0, 0, "render.actions",
                     "scripted overlay input changes the finger settings during the run, so the runs would not "
                     "compare the models: compare a scene without it");
  }
  std::string effects;
  for (const sim::EffectSwitch& e : sim::effectSwitches()) {
    if (base.scene.effects.*e.on) effects.append(effects.empty() ? "\"" : ", \"").append(e.name).append("\"");
  }
  for (const auto& [name, on] : {std::pair{"patch_highlight", base.view.patch_highlight},
                                 std::pair{"patch_insets", base.view.patch_insets}, std::pair{"shadows", base.view.shadows}}) {
    if (on) effects.append(effects.empty() ? "\"" : ", \"").append(name).append("\"");
  }
  overrides.push_back("effects=[" + effects + "]");
  return overrides;
}

// Finishes both sinks, each on its own (a PNG folder that fails does not cost the video), then
// throws the first failure.
void finishSinks(render::PngSequenceWriter* png, render::VideoWriter* video) {
  std::exception_ptr failed;
  try {
    if (png) png->finish();
  } catch (...) {
    failed = std::current_exception();
  }
  try {
    if (video) video->finish();
  } catch (...) {
    if (!failed) failed = std::current_exception();
  }
  if (failed) std::rethrow_exception(failed);
}

// One comparison, stage by stage (runCompare).
class CompareRun {
 public:
  explicit CompareRun(const CompareOptions& o) : o_(o) {}
  void prepare();
  bool runModels();  // false: a run failed or the comparison was interrupted (status_ says)
  void measure();
  void compose();
  void finish();
  int status() const { return status_; }

 private:
  std::vector<std::string> runLines() const;
  void reportRun(std::size_t i, int code);
  nlohmann::json modelJson(std::size_t i, const render::ChartSeries& series) const;
  void progress(int k, int count) const;

  const CompareOptions& o_;
  std::string scene_path_;
  std::optional<SessionDesc> base_;
  std::optional<Quantity> quantity_;
  std::vector<std::string> overrides_;
  std::vector<SessionDesc> sessions_;
  double duration_ = 0.0;
  int width_ = 0, height_ = 0, jobs_ = 1;
  bool frames_ = false;
  render::CompareLayout layout_;
  fs::path out_, video_path_;
  std::optional<RunFolder> folder_;
  std::vector<int> codes_;
  std::vector<nlohmann::json> summaries_;
  render::ChartSpec chart_;
  std::vector<render::ComparePanel> panels_;
  nlohmann::json models_ = nlohmann::json::array();
  int written_ = 0, stopped_by_ = 0, status_ = 0;
};

// Everything that can be checked is, before any run or folder: the models, the scene, the chart,
// the camera, the frame size, the video path; then the folder is this comparison's.
void CompareRun::prepare() {
  checkModels(o_.models);
  scene_path_ = resolveScenePath(o_.scene);
  base_ = baseSession(scene_path_, o_.overrides);
  quantity_ = chartQuantity(*base_, o_.chart, o_.body);
  sessionCamera(*base_, o_.camera);  // an unknown camera fails here, before any run
  overrides_ = runOverrides(*base_, scene_path_, o_.overrides);
  sessions_ = modelSessions(scene_path_, o_.models, overrides_, *base_);
  duration_ = o_.duration > 0.0 ? o_.duration : base_->scene.duration;
  width_ = base_->view.width;
  height_ = base_->view.height;
  if (width_ < 480 || height_ < 270) {
    throw InputError(scene_path_, 0, 0, width_ < 480 ? "render.width" : "render.height",
                     "a comparison needs a frame of at least 480 x 270 pixels (this one is " + std::to_string(width_) +
                         " x " + std::to_string(height_) + ")");
  }
  layout_ = render::compareLayout(width_, height_, static_cast<int>(o_.models.size()));
  out_ = fs::absolute(o_.out.empty() ? defaultOutFolder("compare-" + base_->scene.name) : o_.out);
  video_path_ = o_.video.empty() ? fs::path() : fs::absolute(o_.video);
  frames_ = o_.frames || o_.video.empty();
  if (!o_.video.empty()) requireVideoPath(video_path_.string());
  folder_.emplace(out_);
  requireWritableFolder(out_, "the comparison");
  if (frames_) {
    requireWritableFolder(out_ / kFramesFolder, "the comparison's frames");
    clearFrames(out_ / kFramesFolder);  // a frame sequence left by an earlier comparison
  }
  jobs_ = std::min(o_.jobs, static_cast<int>(o_.models.size()));
}

// Each model's `godfinger run` line: the overrides, the model on every finger, panel-sized frames
// whose labels keep out of the top-left corner, where the panel's label goes.
std::vector<std::string> CompareRun::runLines() const {
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < o_.models.size(); ++i) {
    std::vector<std::string> args;
    for (const std::string& s : overrides_) args.insert(args.end(), {"--set", s});
    for (const std::string& s : modelOverrides(*base_, o_.models[i])) args.insert(args.end(), {"--set", s});
    for (const std::string& s : {"render.width=" + std::to_string(layout_.panel_width),
                                 "render.height=" + std::to_string(layout_.panel_height), std::string("record.trace=true"),
                                 std::string("render.reserve_top_left=true"),  // the panel's label
                                 std::string("record.force_chart=false")}) {
      args.insert(args.end(), {"--set", s});
    }
    args.insert(args.end(), {"--frames", "--quiet", "--duration", exactSeconds(duration_)});
    if (!o_.camera.empty()) args.insert(args.end(), {"--camera", o_.camera});
    lines.push_back(godfingerRunLine(o_.godfinger, scene_path_, (out_ / o_.models[i]).string(), args));
  }
  return lines;
}

void CompareRun::reportRun(std::size_t i, int code) {
  codes_[i] = code;
  summaries_[i] = readSummary(out_ / o_.models[i]);
  const bool ok = (code == 0 || code == 3) && summaries_[i].is_object();
  if (ok && !o_.quiet) {
    const nlohmann::json step = summaries_[i].value("step_time_us", nlohmann::json::object());
    std::printf("%-12s done: step %.1f us (median)%s\n", o_.models[i].c_str(), step.value("median", 0.0),
                code == 3 ? "; an [expect] of the scene failed" : "");
  } else if (!ok && jobsSignal() != 0) {
    std::printf("%-12s interrupted\n", o_.models[i].c_str());
  } else if (!ok) {
    std::printf("%-12s ERROR exit %d: %s\n", o_.models[i].c_str(), code, lastLogLine(out_ / o_.models[i]).c_str());
  }
  flushOutput();
}

bool CompareRun::runModels() {
  if (!o_.quiet) {
    std::printf("compare %s: %zu model%s, %g s each, %d run%s at a time, into %s/\n", base_->scene.name.c_str(),
                o_.models.size(), o_.models.size() == 1 ? "" : "s", duration_, jobs_, jobs_ == 1 ? "" : "s",
                out_.string().c_str());
    flushOutput();
  }
  codes_.assign(o_.models.size(), -1);
  summaries_.assign(o_.models.size(), nullptr);
  if (runJobs(runLines(), jobs_, [&](std::size_t i, int code) { reportRun(i, code); })) {
    status_ = 128 + jobsSignal();
    return false;
  }
  for (std::size_t i = 0; i < codes_.size(); ++i) {
    if ((codes_[i] != 0 && codes_[i] != 3) || !summaries_[i].is_object()) {
      std::fprintf(stderr, "godfinger: error: the %s run failed; see %s\n", o_.models[i].c_str(),
                   (out_ / o_.models[i] / kRunLogFile).c_str());
      status_ = 1;
      return false;
    }
  }
  return true;
}

nlohmann::json CompareRun::modelJson(std::size_t i, const render::ChartSeries& series) const {
  const nlohmann::json& summary = summaries_[i];
  nlohmann::json failed = nlohmann::json::array();
  const nlohmann::json expectations = summary.value("expectations", nlohmann::json::object());
  for (const nlohmann::json& c : expectations.value("checks", nlohmann::json::array())) {
    if (!c.value("passed", true)) failed.push_back(c.value("name", ""));
  }
  return {{"model", o_.models[i]},
          {"folder", (out_ / o_.models[i]).string()},
          {"settings", modelDetail(sessions_[i])},
          {"exit_code", codes_[i]},
          {"expectations_failed", failed},
          {"step_time_us", summary.value("step_time_us", nlohmann::json::object())},
          {"patch_time_us", summary.value("patch_time_us", nlohmann::json(nullptr))},
          {"counters", summary.value("counters", nlohmann::json(nullptr))},
          {"chart", seriesMeasures(series)}};
}

// The runs' measures and curves: measured on every row, thinned for drawing.
void CompareRun::measure() {
  chart_ = chartFor(*quantity_);
  for (std::size_t i = 0; i < o_.models.size(); ++i) {
    render::ChartSeries series = traceSeries(*quantity_, sessions_[i].scene, out_ / o_.models[i] / kTraceFile);
    models_.push_back(modelJson(i, series));
    thin(series.x, series.y);
    series.label = modelTitle(o_.models[i]);
    series.colour = modelColour(o_.models[i], i);
    styleModelSeries(series, o_.models[i], i, o_.models.size());
    const nlohmann::json step = summaries_[i].value("step_time_us", nlohmann::json::object());
    char timing[96];
    std::snprintf(timing, sizeof timing, "haptic step %.1f us (median)", step.value("median", 0.0));
    panels_.push_back({modelTitle(o_.models[i]), modelDetail(sessions_[i]), timing, series.colour});
    chart_.series.push_back(std::move(series));
  }
}

// A line that rewrites itself on a terminal, a line every 10 % otherwise.
void CompareRun::progress(int k, int count) const {
  if (o_.quiet) return;
  if (isatty(STDERR_FILENO) != 0) {
    if (k % 30 == 29 || k + 1 == count) std::fprintf(stderr, "\rcompositing frame %d of %d%s", k + 1, count, k + 1 == count ? "\n" : "");
  } else if ((10 * (k + 1)) / count != (10 * k) / count) {
    std::fprintf(stderr, "compositing frame %d of %d\n", k + 1, count);
  }
}

// The comparison's frames: one per frame of the shortest run.
void CompareRun::compose() {
  int count = -1;
  for (const std::string& m : o_.models) {
    const int n = framesIn(out_ / m / kFramesFolder);
    count = count < 0 ? n : std::min(count, n);
  }
  const double fps = render::FrameOutputSettings{}.fps;  // what each run's frames are written at
  InterruptScope scope;
  render::GlContext context;
  render::CompareCompositor compositor(width_, height_, panels_, chart_);
  std::unique_ptr<render::PngSequenceWriter> png;
  if (frames_) png = std::make_unique<render::PngSequenceWriter>((out_ / kFramesFolder).string());
  std::unique_ptr<render::VideoWriter> video;
  if (!o_.video.empty()) {
    video = std::make_unique<render::VideoWriter>(video_path_.string(), layout_.width, layout_.height, fps);
  }
  std::vector<render::Image> images(o_.models.size());
  std::vector<const render::Image*> pointers;
  for (const render::Image& image : images) pointers.push_back(&image);
  for (int k = 0; k < count; ++k) {
    if ((stopped_by_ = interruptSignal()) != 0) break;
    for (std::size_t i = 0; i < o_.models.size(); ++i) {
      images[i] = render::readPng((out_ / o_.models[i] / kFramesFolder / frameFileName(k)).string());
    }
    render::Image frame = png ? png->spare() : render::Image{};
    compositor.compose(pointers, k / fps, frame);
    if (video) video->push(frame);
    if (png) png->push(std::move(frame));
    ++written_;
    progress(k, count);
  }
  finishSinks(png.get(), video.get());
}

// The runs' own frames go (unless kept or interrupted), then compare.json.
void CompareRun::finish() {
  if (!o_.keep_run_frames && stopped_by_ == 0) {
    std::error_code ec;
    for (const std::string& m : o_.models) fs::remove_all(out_ / m / kFramesFolder, ec);
  }
  const nlohmann::json compare = {
      {"scene", base_->scene.name},
      {"source", scene_path_},
      {"overrides", o_.overrides},
      {"duration_s", duration_},
      {"chart", {{"quantity", quantityName(*quantity_)}, {"label", quantity_->label}, {"body", quantity_->body_name}}},
      {"jobs", jobs_},
      {"step_time_note", jobs_ > 1 ? "runs shared the machine (--jobs > 1): step times are not for publication"
                                   : "one run at a time"},
      {"frames", written_},
      {"video", video_path_.string()},
      {"interrupted", stopped_by_ != 0},
      {"models", models_}};
  writeFileAtomically((out_ / "compare.json").string(), compare.dump(2) + "\n");
  if (!o_.quiet) {
    std::printf("wrote %s/compare.json, %d frame%s%s%s\n", out_.string().c_str(), written_, written_ == 1 ? "" : "s",
                frames_ ? " in frames/" : "", o_.video.empty() ? "" : (", " + video_path_.string()).c_str());
  }
  status_ = stopped_by_ != 0 ? 128 + stopped_by_ : 0;
}

}  // namespace

int runCompare(const CompareOptions& o) {
  CompareRun run(o);
  run.prepare();
  if (!run.runModels()) return run.status();
  run.measure();
  run.compose();
  run.finish();
  return run.status();
}

std::vector<std::string> compareModelOverrides(const std::vector<std::string>& fingers, const std::string& model) {
  std::vector<std::string> out;
  const char* pad = padModelOf(model);
  for (const std::string& f : fingers) {
    out.push_back("fingers." + f + ".contact_model=" + (pad ? std::string("god_finger") : model));
    if (pad) out.push_back("fingers." + f + ".pad_model=" + pad);
  }
  return out;
}

render::Image renderCompareFrame(const std::string& scene, const std::vector<std::string>& models,
                                 const std::vector<std::string>& overrides, double time, double duration, int width,
                                 int height, const std::string& camera) {
  checkModels(models);
  const std::string scene_path = resolveScenePath(scene);
  const SessionDesc base = loadSceneFile(scene_path, overrides);
  const Quantity quantity = chartQuantity(base, "", "");
  std::vector<SessionDesc> sessions = modelSessions(scene_path, models, overrides, base);
  const render::CompareLayout layout = render::compareLayout(width, height, static_cast<int>(models.size()));
  render::ChartSpec chart = chartFor(quantity);
  std::vector<render::ComparePanel> panels;
  std::vector<render::Image> images;
  for (std::size_t i = 0; i < models.size(); ++i) {
    SessionDesc& s = sessions[i];
    s.view.width = layout.panel_width;
    s.view.height = layout.panel_height;
    sim::World world(s.scene);
    QuantityTrack track(quantity, world.bodyPose(quantity.body).orientation);
    render::ChartSeries series;
    series.x.push_back(0.0);
    series.y.push_back(track.atStart());
    sim::Snapshot at;
    const long snap_step = sim::stepCount(time, s.scene.world.haptic_rate_hz);
    long step = 0;
    if (snap_step == 0) world.snapshot(at);
    sim::runHapticLoop(world, sim::deviceTracks(s.scene), {s.scene.world.haptic_rate_hz, duration}, [&](const sim::World& w) {
      series.x.push_back(w.time());
      const int b = quantity.body;
      series.y.push_back(track.next(w.time(), w.bodyPose(b), w.bodyLinearVelocity(b), w.bodyAngularVelocity(b)));
      if (++step == snap_step) w.snapshot(at);
    });
    thin(series.x, series.y);
    series.label = modelTitle(models[i]);
    series.colour = modelColour(models[i], i);
    styleModelSeries(series, models[i], i, models.size());
    panels.push_back({series.label, modelDetail(s), "", series.colour});
    chart.series.push_back(std::move(series));
    SessionOptions options;
    options.camera = camera;
    render::FrameOutputSettings settings = frameSettings(s, options);
    settings.top_left_taken = true;  // the panel's label
    images.push_back(render::renderStill(s.scene, at, settings));
  }
  render::GlContext context;
  render::CompareCompositor compositor(width, height, panels, chart);
  std::vector<const render::Image*> pointers;
  for (const render::Image& image : images) pointers.push_back(&image);
  render::Image out;
  compositor.compose(pointers, time, out);
  return out;
}

}  // namespace gf::app
