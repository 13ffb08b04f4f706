#include "app/compare/compare.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include "app/session/interrupt.hpp"
#include "app/runs/jobs.hpp"
#include "app/runs/run_reader.hpp"
#include "app/session/console.hpp"
#include "app/scene/scene_file.hpp"
#include "app/session/session.hpp"
#include "app/runs/trace.hpp"
#include "app/scene/data_folder.hpp"
#include "app/runs/run_folder.hpp"
#include "app/runs/run_reader.hpp"
#include "render/context.hpp"
#include "render/frame_sinks.hpp"
#include "render/render_thread.hpp"
#include "sim/haptic_loop.hpp"
#include "sim/settings.hpp"
#include "sim/world.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxChartPoints = 4000;  // per model: the chart is at most 1920 pixels wide

const sim::Setting<sim::FingerDesc>& contactModelSetting() {
  return *sim::findSetting(sim::fingerSettings(), "contact_model");
}

// The --set lines giving every finger of the scene `model`.
std::vector<std::string> modelOverrides(const SessionDesc& session, const std::string& model) {
  std::vector<std::string> out;
  for (const sim::FingerDesc& f : session.scene.fingers) out.push_back("fingers." + f.name + ".contact_model=" + model);
  return out;
}

// Each model's colour in the chart and its panel's swatch (linear RGB); others by position.
Eigen::Vector3f modelColour(const std::string& model, std::size_t index) {
  if (model == "god_object") return {0.80f, 0.15f, 0.10f};
  if (model == "soft_finger") return {0.05f, 0.55f, 0.25f};
  if (model == "god_finger") return {0.05f, 0.30f, 0.90f};
  return index % 2 ? Eigen::Vector3f(0.6f, 0.3f, 0.7f) : Eigen::Vector3f(0.3f, 0.3f, 0.3f);
}

std::string modelTitle(const std::string& model) {
  if (model == "god_object") return "god-object";
  if (model == "soft_finger") return "soft finger";
  if (model == "god_finger") return "god-finger";
  return model;
}

// The settings that make the model what it is, for its panel (the first finger's; the bundled
// scenes give every finger the same).
std::string modelDetail(const SessionDesc& session) {
  if (session.scene.fingers.empty()) return "";
  const sim::PatchSettings& p = session.scene.fingers.front().patch;
  char b[200];
  switch (sim::effectiveModel(p)) {
    case sim::ContactModel::kGodObject: std::snprintf(b, sizeof b, "one point, mu %.3g", p.friction); break;
    case sim::ContactModel::kSoftFinger:
      std::snprintf(b, sizeof b, "one point, torsion %.3g mm x normal force, mu %.3g", 1000.0 * p.torsional_friction,
                    p.friction);
      break;
    case sim::ContactModel::kGodFinger:
      std::snprintf(b, sizeof b, "%d SGOs%s, r_max %.3g mm, alpha %.3g, tau_a %.3g deg, mu %.3g", p.n_sgo,
                    p.fill == sim::PatchFill::kFilled ? " (filled)" : "", 1000.0 * p.r_max, p.alpha,
                    p.tau_a * 180.0 / std::numbers::pi, p.friction);
      break;
  }
  return b;
}

// The chart's quantity.
struct Quantity {
  enum Kind { kRotation, kTilt, kHeight, kSpeed, kColumn } kind = kRotation;
  int body = -1;
  std::string body_name, column;
  std::string label;  // the y axis's label
};

Quantity chartQuantity(const SessionDesc& session, const std::string& chart, const std::string& body) {
  Quantity q;
  const std::vector<sim::BodyDesc>& bodies = session.scene.bodies;
  const bool of_body = chart == "rotation" || chart == "tilt" || chart == "height" || chart == "speed";
  if (!of_body) {
    // A trace.csv column: checked against the columns the runs will write.
    const std::vector<std::string> columns = traceColumns(session.scene);
    if (std::find(columns.begin(), columns.end(), chart) == columns.end()) {
      std::string known;
      for (const std::string& c : columns) known.append(known.empty() ? "" : ", ").append(c);
      throw InputError("command line", 0, 0, "--chart",
                       "'" + chart + "' is neither rotation, tilt, height, speed nor a trace.csv column of this scene (" +
                           known + ")");
    }
    if (!body.empty()) throw InputError("command line", 0, 0, "--body", "a trace column names its body itself: drop --body");
    q.kind = Quantity::kColumn;
    q.column = chart;
    q.label = chart;
    return q;
  }
  std::string dynamic;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].mass <= 0.0) continue;
    dynamic.append(dynamic.empty() ? "" : ", ").append(bodies[b].name);
    if (body.empty() ? q.body < 0 : bodies[b].name == body) q.body = static_cast<int>(b);
  }
  if (q.body < 0 && body.empty()) {
    throw InputError("command line", 0, 0, "--chart",
                     chart + " is of a dynamic body and the scene has none: chart a trace.csv column (e.g. a finger's .fy)");
  }
  if (q.body < 0) {
    throw InputError("command line", 0, 0, "--body", "no dynamic body '" + body + "' (the scene's: " + dynamic + ")");
  }
  q.body_name = bodies[static_cast<std::size_t>(q.body)].name;
  q.kind = chart == "rotation" ? Quantity::kRotation
           : chart == "tilt"   ? Quantity::kTilt
           : chart == "height" ? Quantity::kHeight
                               : Quantity::kSpeed;
  q.label = chart == "rotation" ? q.body_name + ": angle turned since the start (deg)"
            : chart == "tilt"   ? q.body_name + ": angle from its starting orientation (deg)"
            : chart == "height" ? q.body_name + ": height (mm)"
                                : q.body_name + ": speed (m/s)";
  return q;
}

// The quantity along one run, fed each state in time order after the start: the angle turned
// (the integral of |angular velocity| over time, so a rolling ball's keeps growing), the angle
// from the starting orientation (at most 180 degrees), the centre's height or speed.
class QuantityTrack {
 public:
  /// `start`: the body's orientation at t = 0.
  QuantityTrack(const Quantity& q, const sim::Quat& start) : q_(q), start_(start) {}
  double next(double t, const sim::Pose& pose, const sim::Vec3& velocity, const sim::Vec3& angular_velocity) {
    turned_ += angular_velocity.norm() * (t - last_t_) * 180.0 / std::numbers::pi;
    last_t_ = t;
    switch (q_.kind) {
      case Quantity::kRotation: return turned_;
      case Quantity::kTilt: {
        const sim::Quat d = start_.conjugate() * pose.orientation;
        return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w())) * 180.0 / std::numbers::pi;
      }
      case Quantity::kHeight: return 1000.0 * pose.position.y();
      case Quantity::kSpeed: return velocity.norm();
      case Quantity::kColumn: break;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }
  /// The value at t = 0 when the description gives it: nothing turned, at rest; NaN otherwise.
  double atStart() const {
    return q_.kind == Quantity::kRotation || q_.kind == Quantity::kTilt || q_.kind == Quantity::kSpeed
               ? 0.0
               : std::numeric_limits<double>::quiet_NaN();
  }

 private:
  const Quantity& q_;
  sim::Quat start_;
  double last_t_ = 0.0, turned_ = 0.0;
};

// A series thinned for the chart to at most kMaxChartPoints points: each bucket of samples keeps
// its lowest and highest (in time order), so peaks survive; the last sample is always kept.
void thin(std::vector<double>& x, std::vector<double>& y) {
  const std::size_t n = std::min(x.size(), y.size());
  const std::size_t k = (2 * n + kMaxChartPoints - 1) / kMaxChartPoints;
  if (k <= 2) return;
  std::size_t out = 0;
  for (std::size_t a = 0; a < n; a += k) {
    const std::size_t e = std::min(n, a + k);
    std::size_t lo = a, hi = a;
    for (std::size_t i = a; i < e; ++i) {
      if (y[i] < y[lo]) lo = i;
      if (y[i] > y[hi]) hi = i;
    }
    const std::size_t first = std::min(lo, hi), second = std::max(lo, hi);
    x[out] = x[first], y[out] = y[first], ++out;
    if (second != first) x[out] = x[second], y[out] = y[second], ++out;
  }
  if (x[out - 1] != x[n - 1]) x[out] = x[n - 1], y[out] = y[n - 1], ++out;
  x.resize(out);
  y.resize(out);
}

// The quantity of one run from its trace.csv (every row, t = 0 first where it is known).
render::ChartSeries traceSeries(const Quantity& q, const sim::SceneDesc& scene, const fs::path& trace) {
  render::ChartSeries s;
  if (q.kind == Quantity::kColumn) {
    std::vector<std::vector<double>> c = readCsvColumns(trace.string(), {"t", q.column});
    s.x = std::move(c[0]);
    s.y = std::move(c[1]);
    return s;
  }
  std::vector<std::string> names = {"t"};
  for (const char* k : {".px", ".py", ".pz", ".qx", ".qy", ".qz", ".qw", ".vx", ".vy", ".vz", ".wx", ".wy", ".wz"}) {
    names.push_back(q.body_name + k);
  }
  const std::vector<std::vector<double>> c = readCsvColumns(trace.string(), names);
  QuantityTrack track(q, scene.bodies[static_cast<std::size_t>(q.body)].orientation);
  if (std::isfinite(track.atStart())) {
    s.x.push_back(0.0);
    s.y.push_back(track.atStart());
  }
  for (std::size_t i = 0; i < c[0].size(); ++i) {
    const sim::Pose pose{sim::Vec3(c[1][i], c[2][i], c[3][i]), sim::Quat(c[7][i], c[4][i], c[5][i], c[6][i])};
    s.x.push_back(c[0][i]);
    s.y.push_back(track.next(c[0][i], pose, sim::Vec3(c[8][i], c[9][i], c[10][i]), sim::Vec3(c[11][i], c[12][i], c[13][i])));
  }
  return s;
}

render::ChartSpec chartFor(const Quantity& q) {
  render::ChartSpec chart;
  chart.x_label = "time (s)";
  chart.y_label = q.label;
  return chart;
}

// Headline numbers of a series: last, largest magnitude, mean magnitude.
nlohmann::json seriesMeasures(const render::ChartSeries& s) {
  double largest = 0.0, sum = 0.0, last = std::numeric_limits<double>::quiet_NaN();
  long n = 0;
  for (double v : s.y) {
    if (!std::isfinite(v)) continue;
    largest = std::max(largest, std::abs(v));
    sum += std::abs(v);
    last = v;
    ++n;
  }
  return {{"final", std::isfinite(last) ? nlohmann::json(last) : nlohmann::json(nullptr)},
          {"max_abs", largest},
          {"mean_abs", n > 0 ? sum / static_cast<double>(n) : 0.0}};
}

// The models, checked: 1..4 known contact models, none twice.
void checkModels(const std::vector<std::string>& models) {
  if (models.empty() || models.size() > 4) {
    throw InputError("command line", 0, 0, "--models", "give 1 to 4 contact models, e.g. god_object,god_finger");
  }
  for (std::size_t i = 0; i < models.size(); ++i) {
    if (sim::choiceIndex(contactModelSetting(), models[i]) < 0) {
      throw InputError("command line", 0, 0, "--models",
                       "unknown contact model '" + models[i] + "' (one of " + sim::choiceList(contactModelSetting()) + ")");
    }
    if (std::find(models.begin(), models.begin() + static_cast<long>(i), models[i]) != models.begin() + static_cast<long>(i)) {
      throw InputError("command line", 0, 0, "--models", "'" + models[i] + "' is given twice");
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
  char name[32];
  for (;; ++n) {
    std::snprintf(name, sizeof name, "%06d.png", n);
    if (!fs::exists(folder / name)) return n;
  }
}

}  // namespace

int runCompare(const CompareOptions& o) {
  checkModels(o.models);
  const std::string scene_path = resolveScenePath(o.scene);
  const SessionDesc base = loadSceneFile(scene_path, o.overrides);
  if (!base.udp_devices.empty()) {
    throw InputError(scene_path, 0, 0, "device.udp", "a live UDP device drives this scene: compare needs recorded device tracks");
  }
  const Quantity quantity = chartQuantity(base, o.chart, o.body);
  sessionCamera(base, o.camera);  // an unknown camera fails here, before any run
  // The overlay draws its own panels into each run's frames, and its scripted clicks change the
  // settings being compared: the runs go without it, and a scene whose script changes them is
  // refused.
  std::vector<std::string> overrides = o.overrides;
  if (base.view.overlay) {
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
  }
  const std::vector<SessionDesc> sessions = modelSessions(scene_path, o.models, overrides, base);
  const double duration = o.duration > 0.0 ? o.duration : base.scene.duration;
  const int width = base.view.width, height = base.view.height;
  if (width < 480 || height < 270) {
    throw InputError(scene_path, 0, 0, width < 480 ? "render.width" : "render.height",
                     "a comparison needs a frame of at least 480 x 270 pixels (this one is " + std::to_string(width) + " x " +
                         std::to_string(height) + ")");
  }
  const double fps = render::FrameOutputSettings{}.fps;  // what each run's frames are written at
  const render::CompareLayout layout = render::compareLayout(width, height, static_cast<int>(o.models.size()));
  const fs::path out = fs::absolute(o.out.empty() ? "compare-" + base.scene.name : o.out);
  const fs::path video_path = o.video.empty() ? fs::path() : fs::absolute(o.video);
  const bool frames = o.frames || o.video.empty();
  if (!o.video.empty()) requireVideoPath(video_path.string());
  requireWritableFolder(out, "the comparison");
  if (frames) {
    requireWritableFolder(out / "frames", "the comparison's frames");
    clearFrames(out / "frames");  // a frame sequence left by an earlier comparison
  }
  const int jobs = std::min(o.jobs, static_cast<int>(o.models.size()));

  std::vector<std::string> lines;
  for (std::size_t i = 0; i < o.models.size(); ++i) {
    std::vector<std::string> args;
    for (const std::string& s : overrides) args.insert(args.end(), {"--set", s});
    for (const std::string& s : modelOverrides(base, o.models[i])) args.insert(args.end(), {"--set", s});
    for (const std::string& s : {"render.width=" + std::to_string(layout.panel_width),
                                 "render.height=" + std::to_string(layout.panel_height), std::string("record.trace=true"),
                                 std::string("record.force_chart=false")}) {
      args.insert(args.end(), {"--set", s});
    }
    char d[32];
    std::snprintf(d, sizeof d, "%.17g", duration);
    args.insert(args.end(), {"--frames", "--quiet", "--duration", d});
    if (!o.camera.empty()) args.insert(args.end(), {"--camera", o.camera});
    lines.push_back(godfingerRunLine(o.godfinger, scene_path, (out / o.models[i]).string(), args));
  }
  if (!o.quiet) {
    std::printf("compare %s: %zu model%s, %g s each, %d run%s at a time, into %s/\n", base.scene.name.c_str(),
                o.models.size(), o.models.size() == 1 ? "" : "s", duration, jobs, jobs == 1 ? "" : "s",
                out.string().c_str());
    flushOutput();
  }
  std::vector<int> codes(o.models.size(), -1);
  std::vector<nlohmann::json> summaries(o.models.size());
  const bool interrupted = runJobs(lines, jobs, [&](std::size_t i, int code) {
    codes[i] = code;
    summaries[i] = readSummary(out / o.models[i]);
    const bool ok = (code == 0 || code == 3) && summaries[i].is_object();
    if (ok && !o.quiet) {
      const nlohmann::json step = summaries[i].value("step_time_us", nlohmann::json::object());
      std::printf("%-12s done: step %.1f us (median)%s\n", o.models[i].c_str(), step.value("median", 0.0),
                  code == 3 ? "; an [expect] of the scene failed" : "");
    } else if (!ok && jobsSignal() != 0) {
      std::printf("%-12s interrupted\n", o.models[i].c_str());
    } else if (!ok) {
      std::printf("%-12s ERROR exit %d: %s\n", o.models[i].c_str(), code, lastLogLine(out / o.models[i]).c_str());
    }
    flushOutput();
  });
  if (interrupted) return 128 + jobsSignal();
  for (std::size_t i = 0; i < codes.size(); ++i) {
    if ((codes[i] != 0 && codes[i] != 3) || !summaries[i].is_object()) {
      std::fprintf(stderr, "godfinger: error: the %s run failed; see %s\n", o.models[i].c_str(),
                   (out / o.models[i] / "run.log").c_str());
      return 1;
    }
  }

  // The runs' measures and curves: measured on every row, thinned for drawing.
  render::ChartSpec chart = chartFor(quantity);
  std::vector<render::ComparePanel> panels;
  nlohmann::json models = nlohmann::json::array();
  for (std::size_t i = 0; i < o.models.size(); ++i) {
    const fs::path dir = out / o.models[i];
    const nlohmann::json& summary = summaries[i];
    render::ChartSeries series = traceSeries(quantity, sessions[i].scene, dir / "trace.csv");
    const nlohmann::json measures = seriesMeasures(series);
    thin(series.x, series.y);
    series.label = modelTitle(o.models[i]);
    series.colour = modelColour(o.models[i], i);
    const nlohmann::json step = summary.value("step_time_us", nlohmann::json::object());
    char timing[96];
    std::snprintf(timing, sizeof timing, "haptic step %.1f us (median)", step.value("median", 0.0));
    panels.push_back({modelTitle(o.models[i]), modelDetail(sessions[i]), timing, series.colour});
    nlohmann::json failed = nlohmann::json::array();
    const nlohmann::json expectations = summary.value("expectations", nlohmann::json::object());
    for (const nlohmann::json& c : expectations.value("checks", nlohmann::json::array())) {
      if (!c.value("passed", true)) failed.push_back(c.value("name", ""));
    }
    models.push_back({{"model", o.models[i]},
                      {"folder", dir.string()},
                      {"settings", modelDetail(sessions[i])},
                      {"exit_code", codes[i]},
                      {"expectations_failed", failed},
                      {"step_time_us", step},
                      {"patch_time_us", summary.value("patch_time_us", nlohmann::json(nullptr))},
                      {"counters", summary.value("counters", nlohmann::json(nullptr))},
                      {"chart", measures}});
    chart.series.push_back(std::move(series));
  }

  // The comparison's frames: one per frame of the shortest run.
  int count = -1;
  for (const std::string& m : o.models) {
    const int n = framesIn(out / m / "frames");
    count = count < 0 ? n : std::min(count, n);
  }
  int written = 0;
  int stopped_by = 0;
  {
    InterruptScope scope;
    render::GlContext context;
    render::CompareCompositor compositor(width, height, panels, chart);
    std::unique_ptr<render::PngSequenceWriter> png;
    if (frames) png = std::make_unique<render::PngSequenceWriter>((out / "frames").string());
    std::unique_ptr<render::VideoWriter> video;
    if (!o.video.empty()) video = std::make_unique<render::VideoWriter>(video_path.string(), width, height, fps);
    std::vector<render::Image> images(o.models.size());
    std::vector<const render::Image*> pointers;
    for (const render::Image& image : images) pointers.push_back(&image);
    const bool terminal = isatty(STDERR_FILENO) != 0;
    for (int k = 0; k < count; ++k) {
      if ((stopped_by = interruptSignal()) != 0) break;
      char name[32];
      std::snprintf(name, sizeof name, "%06d.png", k);
      for (std::size_t i = 0; i < o.models.size(); ++i) images[i] = render::readPng((out / o.models[i] / "frames" / name).string());
      render::Image frame = png ? png->spare() : render::Image{};
      compositor.compose(pointers, k / fps, frame);
      if (video) video->push(frame);
      if (png) png->push(std::move(frame));
      ++written;
      // A line that rewrites itself on a terminal, a line every 10 % otherwise.
      if (!o.quiet && terminal && (k % 30 == 29 || k + 1 == count)) {
        std::fprintf(stderr, "\rcompositing frame %d of %d", k + 1, count);
        if (k + 1 == count) std::fputc('\n', stderr);
      } else if (!o.quiet && !terminal && (10 * (k + 1)) / count != (10 * k) / count) {
        std::fprintf(stderr, "compositing frame %d of %d\n", k + 1, count);
      }
    }
    if (png) png->finish();
    if (video) video->finish();
  }
  if (!o.keep_run_frames && stopped_by == 0) {
    std::error_code ec;
    for (const std::string& m : o.models) fs::remove_all(out / m / "frames", ec);
  }
  const nlohmann::json compare = {
      {"scene", base.scene.name},
      {"source", scene_path},
      {"overrides", o.overrides},
      {"duration_s", duration},
      {"chart", {{"quantity", o.chart}, {"label", quantity.label}, {"body", quantity.body_name}}},
      {"jobs", jobs},
      {"step_time_note", jobs > 1 ? "runs shared the machine (--jobs > 1): step times are not for publication"
                                    : "one run at a time"},
      {"frames", written},
      {"video", video_path.string()},
      {"interrupted", stopped_by != 0},
      {"models", models}};
  {
    const fs::path path = out / "compare.json";
    std::ofstream f(path.string() + ".tmp");
    f << compare.dump(2) << "\n";
    f.close();
    if (!f) throw std::runtime_error((path.string() + ".tmp") + ": cannot write");
    fs::rename(path.string() + ".tmp", path);
  }
  if (!o.quiet) {
    std::printf("wrote %s/compare.json, %d frame%s%s%s\n", out.string().c_str(), written, written == 1 ? "" : "s",
                frames ? " in frames/" : "", o.video.empty() ? "" : (", " + video_path.string()).c_str());
  }
  return stopped_by != 0 ? 128 + stopped_by : 0;
}

render::Image renderCompareFrame(const std::string& scene, const std::vector<std::string>& models,
                                 const std::vector<std::string>& overrides, double time, double duration, int width,
                                 int height, const std::string& camera) {
  checkModels(models);
  const std::string scene_path = resolveScenePath(scene);
  const SessionDesc base = loadSceneFile(scene_path, overrides);
  const Quantity quantity = chartQuantity(base, "rotation", "");
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
    panels.push_back({series.label, modelDetail(s), "", series.colour});
    chart.series.push_back(std::move(series));
    SessionOptions options;
    options.camera = camera;
    images.push_back(render::renderStill(s.scene, at, frameSettings(s, options)));
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
