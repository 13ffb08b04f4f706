// The `godfinger` command: run scripted sessions, compute one contact area, list the bundled
// scenes, or drive a live session from standard input.
#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <thread>

#include "app/commands/check.hpp"
#include "app/compare/compare.hpp"
#include "app/session/interrupt.hpp"
#include "app/session/live.hpp"
#include "app/commands/mesh_info.hpp"
#include "app/runs/contacts.hpp"
#include "app/commands/plot.hpp"
#include "app/scene/scene_file.hpp"
#include "app/session/screenshots.hpp"
#include "app/session/session.hpp"
#include "app/study/study.hpp"
#include "app/runs/trace.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/schema.hpp"
#include "app/session/expectations.hpp"
#include "render/context.hpp"
#include "render/render_thread.hpp"
#include "sim/about.hpp"
#include "sim/contact_record.hpp"
#include "sim/mesh_import.hpp"
#include "sim/settings.hpp"

namespace {

using gf::app::InputError;

struct RunArgs {
  std::string scene;
  std::string out = "out";
  std::vector<std::string> overrides;
  double duration = 0.0;
  bool realtime = false;
  bool frames = false;
  std::string video, camera;
  std::string expectations = "check";
  bool no_fifo = false, no_yield = false;
  double spin_us = 0.0;
  bool quiet = false;
  std::vector<std::string> command_line;
};

const gf::sim::Setting<gf::sim::FingerDesc>& fingerSetting(std::string_view name) {
  return *gf::sim::findSetting(gf::sim::fingerSettings(), name);
}

struct PatchArgs {
  std::string mesh, out, point, normal, push;
  double scale = 1.0;
  double rounding = 0.0;  ///< collision margin rounding the mesh's edges (m)
  double max_distance = 0.001;  ///< farthest --point may be from the surface (m)
  gf::sim::FingerDesc finger;  ///< its god-finger settings, tau_a aside
  double tau_a_deg = gf::sim::givenValue(fingerSetting("tau_a"), gf::sim::FingerDesc{});
};

// A command-line check by the validator of setting `name` of `table` (the value in its unit).
template <class Desc>
CLI::Validator settingCheck(std::span<const gf::sim::Setting<Desc>> table, std::string_view name) {
  const gf::sim::Setting<Desc>* s = gf::sim::findSetting(table, name);
  return CLI::Validator(
      [s](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0') return "expected a number, got '" + text + "'";
        return gf::sim::checkGiven(*s, v).value_or("");
      },
      std::string(s->unit.empty() ? "" : "(" + std::string(s->unit) + ")"));
}

CLI::Validator fingerCheck(std::string_view name) { return settingCheck(gf::sim::fingerSettings(), name); }

void addRun(CLI::App& app, RunArgs& a) {
  CLI::App* run = app.add_subcommand("run", "Run a scene; write trace.csv, summary.json and contacts/");
  run->add_option("scene", a.scene, "Scene file, or the name of a bundled scene (godfinger list)")->required();
  run->add_option("--out", a.out, "Output folder (created if missing)");
  run->add_option("--set", a.overrides, "Override a scene field, e.g. --set fingers.left.n_sgo=0");
  run->add_option("--duration", a.duration, "Simulated seconds (default: the scene's)")
      ->check(settingCheck(gf::sim::sceneSettings(), "duration"));
  run->add_flag("--realtime", a.realtime, "Pace steps on the wall clock (absolute deadlines)");
  run->add_flag("--no-fifo", a.no_fifo, "Realtime: do not ask for SCHED_FIFO for the haptic loop (run as a user "
                                        "without root or CAP_SYS_NICE does)");
  run->add_flag("--no-yield", a.no_yield, "Realtime: keep the render thread and encoders at normal priority "
                                          "instead of SCHED_IDLE");
  run->add_option("--spin-us", a.spin_us, "Realtime: sleep until this long before each step's deadline, then "
                                          "spin (us; default 0: sleep)")
      ->check(CLI::Range(0.0, 1000.0));
  run->add_flag("--quiet", a.quiet, "No progress lines on stderr");
  run->add_flag("--frames", a.frames, "Write frames/000000.png ... at 60 frames per simulated second");
  run->add_option("--video", a.video, "Write an MP4 of the frames (H.264, via ffmpeg)");
  run->add_option("--camera", a.camera, "Camera of the scene to render (default: its first)");
  run->add_option("--expectations", a.expectations, "check: exit 3 when an [expect] of the scene fails (default); "
                                                    "report: only print them and write them into summary.json")
      ->check(CLI::IsMember({"check", "report"}));
}

void addPatch(CLI::App& app, PatchArgs& a) {
  CLI::App* p = app.add_subcommand("patch", "Compute one god-finger contact area on a mesh; write patch.json "
                                              "and its close-up patch.png");
  p->add_option("--mesh", a.mesh, "Mesh file (OBJ, PLY, STL, OFF, glTF, ...)")->required();
  p->add_option("--scale", a.scale, "Factor from mesh units to metres")
      ->check(settingCheck(gf::sim::bodySettings(), "scale"));
  p->add_option("--point", a.point, "Contact point X,Y,Z on the mesh (m)")->required();
  p->add_option("--normal", a.normal, "Outward surface normal X,Y,Z at the point (default: the normal of the face "
                                      "closest to the point; at an edge or vertex, of the face there the push presses "
                                      "into most)");
  p->add_option("--max-distance", a.max_distance, "Farthest the point may be from the mesh surface (m; default 0.001)")
      ->check(CLI::Range(0.0, 1.0));
  p->add_option("--push", a.push, "Coupling vector v = device - god-object X,Y,Z (m)")->required();
  p->add_option("--rounding", a.rounding, "Collision margin rounding the mesh's edges and corners (m): a point "
                                          "this close to an edge, with a normal between its faces', is an edge hit")
      ->check(CLI::Range(0.0, 0.01));
  p->add_option("--n-sgo", a.finger.patch.n_sgo, "Number of SGOs")->check(fingerCheck("n_sgo"));
  p->add_option("--r-max", a.finger.patch.r_max, "Largest contact radius r_max (m)")->check(fingerCheck("r_max"));
  p->add_option("--d0", a.finger.patch.d0, "Press depth scale D'_0 (m)")->check(fingerCheck("d0"));
  p->add_option("--alpha", a.finger.patch.alpha, "Stretch base alpha of Eq. 2")->check(fingerCheck("alpha"));
  p->add_option("--tau-a", a.tau_a_deg, "Angular threshold tau_a (degrees)")->check(fingerCheck("tau_a"));
  p->add_option("--friction", a.finger.patch.friction, "Friction coefficient theta")->check(fingerCheck("friction"));
  p->add_option("--out", a.out, "Output folder (created if missing)")->required();
}

gf::sim::Vec3 parseVec3(const std::string& option, const std::string& text) {
  gf::sim::Vec3 v;
  std::size_t pos = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t end = i < 2 ? text.find(',', pos) : text.size();
    if (end == std::string::npos) throw InputError("command line", 0, 0, option, "expected X,Y,Z, got '" + text + "'");
    const std::string cell = text.substr(pos, end - pos);
    char* stop = nullptr;
    v[i] = std::strtod(cell.c_str(), &stop);
    if (cell.empty() || *stop != '\0' || !std::isfinite(v[i])) {
      throw InputError("command line", 0, 0, option, "expected three finite numbers X,Y,Z, got '" + text + "'");
    }
    pos = end + 1;
  }
  return v;
}

int runCommand(const RunArgs& a) {
  gf::app::SessionDesc session = gf::app::loadSceneFile(gf::app::resolveScenePath(a.scene), a.overrides);
  session.overrides = a.overrides;
  if (a.duration > 0.0) session.scene.duration = a.duration;
  gf::app::sessionCamera(session, a.camera);  // an unknown camera fails before anything runs
  if (!a.video.empty() && std::filesystem::is_directory(a.video)) {
    throw InputError("command line", 0, 0, "--video", a.video + " is a folder; give a file such as out.mp4");
  }
  gf::app::SessionOptions options{a.out, a.realtime, !a.quiet, a.frames, a.video, a.camera};
  std::vector<gf::app::ExpectFailure> failed;
  options.expect_failures = &failed;
  options.stop_on_interrupt = true;
  options.fifo = !a.no_fifo;
  options.yield_render = !a.no_yield;
  options.spin_us = a.spin_us;
  options.command_line = a.command_line;
  const gf::sim::LoopStats stats = gf::app::runSession(session, options);
  std::printf("%s: %ld steps, step median %.1f us, p99 %.1f us; wrote %s/\n", session.scene.name.c_str(),
              stats.steps, stats.step_median_us, stats.step_p99_us, a.out.c_str());
  if (a.frames) std::printf("frames: %s/frames/\n", a.out.c_str());
  if (!a.video.empty()) std::printf("video: %s\n", a.video.c_str());
  // Ctrl-C or SIGTERM: the outputs hold the time reached; the shell's status for the signal.
  // A signal while the outputs were being finished ends with its status too (they are complete).
  if (stats.stopped || gf::app::interruptSignal() != 0) return gf::app::interruptedStatus();
  // 3: the run was fine, the scene's expectations were not.
  return failed.empty() || a.expectations == "report" ? 0 : 3;
}

// The close-up of a computed patch: the mesh as a static body, the patch as one finger's contact.
void writePatchCloseUp(const PatchArgs& a, const std::shared_ptr<const gf::sim::Mesh>& mesh,
                       const gf::sim::ContactRecord& record, const std::string& prefix) {
  gf::sim::SceneDesc scene;
  gf::sim::BodyDesc body;
  body.shape = gf::sim::ShapeKind::kConcaveMesh;
  body.mesh_path = a.mesh;
  body.mesh_scale = a.scale;
  body.mesh = mesh;  // drawn from the mesh already loaded
  body.mass = 0.0;
  scene.bodies.push_back(body);
  scene.fingers.push_back(a.finger);
  gf::sim::Snapshot snap;
  snap.bodies.resize(1);  // the mesh frame is the world frame
  gf::sim::toContactSnapshot(record, snap.bodies[0], snap.fingers.emplace_back().contacts.emplace_back());
  gf::render::renderCloseUps(scene, snap, prefix, 480);
}

// The contact normal when none is given: the hit face's, or at an edge or vertex the normal of
// the face around it that the push presses into most.
gf::sim::Vec3 pressedNormal(const gf::sim::Mesh& mesh, const gf::sim::SurfacePoint& hit, const gf::sim::Vec3& push) {
  if (hit.feature == gf::sim::Feature::kFace || !(push.norm() > 0.0)) return mesh.faceNormal(hit.face);
  const auto& tri = mesh.triangles()[static_cast<std::size_t>(hit.face)];
  const std::int32_t v = tri[static_cast<std::size_t>(hit.feature_index)];
  const std::int32_t w = hit.feature == gf::sim::Feature::kEdge ? tri[static_cast<std::size_t>((hit.feature_index + 1) % 3)] : v;
  gf::sim::Vec3 best = mesh.faceNormal(hit.face);
  double most = -best.dot(push);
  for (const std::int32_t* f = mesh.vertexFacesBegin(v); f != mesh.vertexFacesEnd(v); ++f) {
    const auto& t = mesh.triangles()[static_cast<std::size_t>(*f)];
    if (t[0] != w && t[1] != w && t[2] != w) continue;
    if (const double press = -mesh.faceNormal(*f).dot(push); press > most) most = press, best = mesh.faceNormal(*f);
  }
  return best;
}

int patchCommand(PatchArgs& a) {
  gf::sim::ContactRecord record;
  record.body = 0;
  const gf::sim::Vec3 point = parseVec3("--point", a.point);
  record.contact = {point, a.normal.empty() ? gf::sim::Vec3::Zero() : parseVec3("--normal", a.normal), 0.0, a.rounding};
  const gf::sim::Vec3 push = parseVec3("--push", a.push);
  if (!a.normal.empty() && record.contact.outward_normal_local.norm() < 1e-9) {
    throw InputError("command line", 0, 0, "--normal", "must not be zero");
  }
  if (a.finger.patch.n_sgo < gf::sim::kMinSgo) {
    throw InputError("command line", 0, 0, "--n-sgo", "a patch needs at least " + std::to_string(gf::sim::kMinSgo) + " SGOs");
  }
  gf::sim::setGiven(fingerSetting("tau_a"), a.finger, a.tau_a_deg);
  const gf::sim::PatchSettings& settings = a.finger.patch;
  std::shared_ptr<const gf::sim::Mesh> mesh;
  try {
    mesh = std::make_shared<const gf::sim::Mesh>(gf::sim::loadMesh(a.mesh, a.scale));
  } catch (const gf::sim::MeshLoadError& e) {
    throw InputError("command line", 0, 0, "--mesh", e.what());
  }
  // The point must lie on the surface (within --max-distance); without --normal, the closest
  // face's normal is the contact normal.
  const gf::sim::SurfacePoint closest = mesh->closestPoint(point, settings.feature_tolerance);
  if (closest.face < 0) throw InputError("command line", 0, 0, "--mesh", a.mesh + ": no faces");
  if (closest.query_distance > a.max_distance) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "is %.6g m from the mesh surface (closest surface point %.6g,%.6g,%.6g; --max-distance %.6g m)",
                  closest.query_distance, closest.point.x(), closest.point.y(), closest.point.z(), a.max_distance);
    throw InputError("command line", 0, 0, "--point", text);
  }
  if (a.normal.empty()) record.contact.outward_normal_local = pressedNormal(*mesh, closest, push);
  record.contact.outward_normal_local.normalize();
  gf::sim::computePatch(*mesh, record.contact, push, settings, record.patch);
  record.press_depth = record.patch.press_depth;
  if (record.patch.valid) record.contact.point_local = record.patch.hit.point;  // c_p on the mesh
  const gf::sim::Patch& patch = record.patch;
  nlohmann::json j = gf::app::patchJson(patch, settings);
  j["mesh"] = a.mesh;
  j["scale"] = a.scale;
  j["normal_from"] = a.normal.empty() ? "closest face (at an edge or vertex: the one pressed most)" : "--normal";
  const std::string why = gf::app::patchExplanation(patch, settings);
  j["explanation"] = why;
  std::error_code ec;
  std::filesystem::create_directories(a.out, ec);
  if (ec) throw std::runtime_error(a.out + ": cannot create folder: " + ec.message());
  const std::string path = (std::filesystem::path(a.out) / "patch.json").string();
  gf::app::writeFileAtomically(path, j.dump(1) + "\n");
  const std::string picture = (std::filesystem::path(a.out) / "patch").string();
  writePatchCloseUp(a, mesh, record, picture);
  std::printf("radius %.6g m, %zu of %d SGOs%s%s; wrote %s and %s.png\n", patch.radius, patch.sgos.size(),
              settings.n_sgo, why.empty() ? "" : ": ", why.c_str(), path.c_str(), picture.c_str());
  return 0;
}

int screenshotsCommand(const std::string& out) {
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) throw std::runtime_error(out + ": cannot create folder: " + ec.message());
  for (const gf::app::Shot& shot : gf::app::referenceShots()) {
    const std::string path = (std::filesystem::path(out) / (shot.name + ".png")).string();
    gf::render::writePng(path, gf::app::renderShot(shot), 9);
    std::printf("%s\n", path.c_str());
  }
  return 0;
}

struct StudyArgs {
  std::string study, out, emit_jobs, collect;
  std::vector<std::string> overrides;
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  bool quick = false;
};

void addStudy(CLI::App& app, StudyArgs& a) {
  CLI::App* s = app.add_subcommand("study", "Run an accuracy study: every configuration as a `godfinger run`; write "
                                             "results.csv, work-precision.png and report.md");
  s->add_option("study", a.study, "Study file, or the name of a bundled study (assets/studies)")->required();
  s->add_option("--out", a.out, "Output folder (default: study-NAME; with --collect, the collected folder)");
  s->add_option("--jobs", a.jobs, "Runs at a time (default: the number of cores); --jobs 1 for published step times")
      ->check(CLI::Range(1, 256));
  s->add_option("--set", a.overrides, "Override a scene field in every run, e.g. --set duration=2");
  s->add_flag("--quick", a.quick, "The study's small grid (for tests)");
  s->add_option("--emit-jobs", a.emit_jobs, "Write one shell command line per run into this file (for GNU parallel "
                                            "or a Slurm array) instead of running");
  s->add_option("--collect", a.collect, "Collect the run folders a job runner wrote under this folder");
  s->get_option("--emit-jobs")->excludes("--collect");
}

int studyCommand(const StudyArgs& a) {
  const gf::app::StudyDesc study = gf::app::loadStudyFile(a.study);
  bool quick = a.quick;
  std::vector<std::string> overrides = a.overrides;
  if (!a.collect.empty()) {
    if (!std::filesystem::is_directory(a.collect)) {
      throw InputError("command line", 0, 0, "--collect", a.collect + ": no such folder");
    }
    // The runs' folder names come from the grid: collect the grid they were made with.
    if (const std::optional<gf::app::StudyGrid> grid = gf::app::readStudyGrid(a.collect)) {
      if ((a.quick && !grid->quick) || (!a.overrides.empty() && a.overrides != grid->extra)) {
        throw InputError("command line", 0, 0, "--collect",
                         a.collect + " holds runs made " + (grid->quick ? "with" : "without") + " --quick and " +
                             std::to_string(grid->extra.size()) + " --set (see its grid.json); give the same or none");
      }
      quick = grid->quick;
      overrides = grid->extra;
    }
  }
  const gf::app::StudyPlan plan = gf::app::expandStudy(study, quick, overrides);
  // The --quick grid's own overrides are checked too, whichever grid runs.
  if (!quick) gf::app::expandStudy(study, true, overrides);
  gf::app::StudyOptions options;
  options.out = a.out.empty() ? (a.collect.empty() ? "study-" + study.name : a.collect) : a.out;
  options.jobs = a.jobs;
  options.godfinger = std::filesystem::canonical("/proc/self/exe").string();
  if (!a.emit_jobs.empty()) {
    gf::app::emitStudyJobs(plan, options, a.emit_jobs);
    return 0;
  }
  if (!a.collect.empty()) return gf::app::collectStudy(plan, a.collect, options.out, false);
  return gf::app::runStudy(plan, options);
}

// `godfinger --version`: this build and what it runs on.
std::string versionText() {
  std::string text = "godfinger " + gf::app::versionString() + " (commit " + gf::app::commitString() + ")\n";
  text += gf::sim::bulletVersion() + ", " + gf::sim::assimpVersion() + ", " + gf::sim::eigenVersion() + "\n";
  try {
    const gf::render::GlContext context;  // a 1x1 OSMesa context, just to ask it
    text += "OpenGL " + context.description() + " (OSMesa, offscreen)";
  } catch (const std::exception& e) {
    text += std::string("OpenGL: unavailable (") + e.what() + ")";
  }
  return text;
}

int listCommand() {
  for (const std::string& path : gf::app::bundledScenePaths()) {
    const std::string name = std::filesystem::path(path).stem().string();
    try {
      const gf::app::SessionDesc s = gf::app::loadSceneFile(path);
      std::printf("%-24s %s\n", name.c_str(), s.summary.c_str());
    } catch (const std::exception& e) {
      std::printf("%-24s (does not load: %s)\n", name.c_str(), e.what());
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"godfinger: god-finger contact areas for haptic interaction on Bullet", "godfinger"};
  app.require_subcommand(1);
  app.set_version_flag("--version", versionText, "Print the version, the git commit and the libraries' versions");
  RunArgs run_args;
  addRun(app, run_args);
  PatchArgs patch_args;
  addPatch(app, patch_args);
  StudyArgs study_args;
  addStudy(app, study_args);
  gf::app::CheckOptions check;
  check.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  CLI::App* check_cmd = app.add_subcommand("check", "Run scenes offline and check their [expect] tables; one line "
                                                    "each, exit 1 if any fails");
  check_cmd->add_option("paths", check.paths, "Scene files, folders of them, or bundled scene names")->required();
  check_cmd->add_option("--out", check.out, "Folder for the runs (default: check)");
  check_cmd->add_option("--set", check.overrides, "Override a field of every scene, e.g. --set "
                                                  "world.contact_solver=aggregate");
  check_cmd->add_option("--jobs", check.jobs, "Scenes at a time (default: the number of cores)")->check(CLI::Range(1, 256));
  gf::app::CompareOptions compare;
  compare.jobs = check.jobs;
  std::string compare_models;
  CLI::App* compare_cmd = app.add_subcommand(
      "compare", "Run a scene once per contact model (offline, in parallel) and draw one video of the runs side "
                 "by side over a chart of a trace quantity; compare.json holds their measures");
  compare_cmd->add_option("scene", compare.scene, "Scene file or bundled scene name")->required();
  compare_cmd->add_option("--models", compare_models, "Contact models, comma-separated (1 to 4 of god_object, "
                                                      "soft_finger, god_finger)")
      ->default_val("god_object,soft_finger,god_finger");
  compare_cmd->add_option("--set", compare.overrides, "Override a scene field in every run");
  compare_cmd->add_option("--duration", compare.duration, "Simulated seconds (default: the scene's)")
      ->check(CLI::Range(1e-3, 3600.0));
  compare_cmd->add_option("--out", compare.out, "Folder for the runs, compare.json and frames (default: compare-SCENE)");
  compare_cmd->add_option("--video", compare.video, "Write the comparison as an MP4 (H.264, via ffmpeg)");
  compare_cmd->add_flag("--frames", compare.frames, "Write the comparison's frames/000000.png ... (always without --video)");
  compare_cmd->add_flag("--keep-run-frames", compare.keep_run_frames, "Keep each run's own frames (MODEL/frames)");
  compare_cmd->add_option("--camera", compare.camera, "Camera of the scene (default: its first)");
  compare_cmd->add_option("--chart", compare.chart, "Quantity charted: of --body, rotation (angle turned, deg), tilt "
                                                   "(angle from the start, deg), height (mm) or speed (m/s); or any "
                                                   "trace.csv column (default: rotation)");
  compare_cmd->add_option("--body", compare.body, "Body of the chart (default: the scene's first dynamic body)");
  compare_cmd->add_option("--jobs", compare.jobs, "Runs at a time (default: the number of cores; 1 for step times "
                                                  "to publish)")
      ->check(CLI::Range(1, 256));
  compare_cmd->add_flag("--quiet", compare.quiet, "Only errors");
  app.add_subcommand("list", "List the bundled scenes");
  gf::app::LiveOptions live;
  CLI::App* live_cmd = app.add_subcommand("live", "Interactive session: one command a line on standard input");
  live_cmd->add_option("scene", live.scene_path, "Scene file or bundled scene name")->required();
  live_cmd->add_option("--set", live.overrides, "Override a scene field");
  live_cmd->add_option("--out", live.out_dir, "Folder for snapshots (contacts/)");
  gf::app::MeshInfoOptions mesh_info;
  bool mesh_info_json = false;
  CLI::App* mesh_cmd = app.add_subcommand("mesh-info", "What a mesh file holds: parts, size, unit and up axis, whether it "
                                                       "is closed and outward, volume, centre of mass and inertia");
  mesh_cmd->add_option("file", mesh_info.path, "Mesh file (OBJ, PLY, STL, OFF, glTF, Collada, ...)")->required();
  mesh_cmd->add_option("--scale", mesh_info.scale, "File units to metres, as a body's scale (default 1)")
      ->check(settingCheck(gf::sim::bodySettings(), "scale"));
  mesh_cmd->add_option("--mass", mesh_info.mass, "Mass (kg) for the inertia (default: from --density)")->check(CLI::Range(1e-9, 1e9));
  mesh_cmd->add_option("--density", mesh_info.density, "Density (kg/m^3) when no mass is given (default 1000)")
      ->check(CLI::Range(1e-6, 1e6));
  mesh_cmd->add_flag("--json", mesh_info_json, "Print JSON instead of text");
  gf::app::PlotOptions plot;
  CLI::App* plot_cmd = app.add_subcommand("plot", "Draw columns of a CSV (trace.csv, forces.csv) against time as a PNG");
  plot_cmd->add_option("csv", plot.csv, "The CSV file (a header row, then numbers)")->required();
  plot_cmd->add_option("--y", plot.y, "A column to draw (repeat for more curves)")->required();
  plot_cmd->add_option("--x", plot.x, "The column along the x axis (default: t)");
  plot_cmd->add_option("--out", plot.out, "PNG file (default: plot.png beside the CSV)");
  plot_cmd->add_option("--title", plot.title, "Chart title (default: the file and the columns)");
  plot_cmd->add_option("--width", plot.width, "Pixels (default 1200)")->check(CLI::Range(200, 4000));
  plot_cmd->add_option("--height", plot.height, "Pixels (default 600)")->check(CLI::Range(150, 4000));
  app.add_subcommand("schema", "Print the JSON Schema of scene files (for editors that check TOML against a schema)");
  std::string shots_out = "screenshots";
  app.add_subcommand("screenshots", "Render the reference pictures (visual-regression goldens) into --out")
      ->add_option("--out", shots_out, "Folder (default: screenshots, the goldens when run from the repository)");
  if (argc == 1) {  // bare `godfinger`: the usage and the command list
    std::fputs(app.help().c_str(), stdout);
    return 1;
  }
  // A reader that went away (ffmpeg, a closed pipe) is a write error we report, not a signal
  // that kills the run before it writes what it reached.
  std::signal(SIGPIPE, SIG_IGN);
  std::signal(SIGXFSZ, SIG_IGN);  // a file past the size limit: a write error too
  run_args.command_line.assign(argv, argv + argc);
  CLI11_PARSE(app, argc, argv);
  try {
    if (app.got_subcommand("list")) return listCommand();
    if (app.got_subcommand("schema")) {
      std::fputs((gf::app::sceneSchema().dump(2) + "\n").c_str(), stdout);
      return 0;
    }
    if (app.got_subcommand("mesh-info")) {
      try {
        const nlohmann::json info = gf::app::meshInfoJson(mesh_info);
        std::fputs(mesh_info_json ? (info.dump(2) + "\n").c_str() : gf::app::meshInfoText(info).c_str(), stdout);
      } catch (const gf::sim::MeshLoadError& e) {
        throw InputError("command line", 0, 0, "file", e.what());
      }
      return 0;
    }
    if (app.got_subcommand("plot")) {
      std::printf("wrote %s\n", gf::app::writePlot(plot).c_str());
      return 0;
    }
    if (app.got_subcommand("screenshots")) return screenshotsCommand(shots_out);
    if (app.got_subcommand("patch")) return patchCommand(patch_args);
    if (app.got_subcommand("study")) return studyCommand(study_args);
    if (app.got_subcommand("check")) {
      check.godfinger = std::filesystem::canonical("/proc/self/exe").string();
      return gf::app::runCheck(check);
    }
    if (app.got_subcommand("compare")) {
      compare.godfinger = std::filesystem::canonical("/proc/self/exe").string();
      for (std::size_t a = 0; a <= compare_models.size();) {
        const std::size_t b = std::min(compare_models.find(',', a), compare_models.size());
        if (b > a) compare.models.push_back(compare_models.substr(a, b - a));
        a = b + 1;
      }
      return gf::app::runCompare(compare);
    }
    if (app.got_subcommand("live")) {
      live.scene_path = gf::app::resolveScenePath(live.scene_path);
      live.stop_on_interrupt = true;
      return gf::app::runLive(live, std::cin, std::cout);
    }
    return runCommand(run_args);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "godfinger: error: %s\n", e.what());
    return 1;
  }
}
