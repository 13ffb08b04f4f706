// The Python module `godfinger`: run() and study() go through the command's own code (a
// session's run folder, a study's `godfinger run` processes) into a temporary folder, read back
// into numpy arrays and dicts; World is world.cpp's. Bad input raises godfinger.InputError (a
// ValueError) with the command line's message.
#include "app/python/module.hpp"

#include <dlfcn.h>
#include <pybind11/stl.h>

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <optional>

#include "app/python/convert.hpp"
#include "app/runs/run_folder.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/input_error.hpp"
#include "app/scene/scene_file.hpp"
#include "app/session/session.hpp"
#include "app/study/study.hpp"
#include "sim/scene/settings.hpp"

namespace fs = std::filesystem;

namespace gf::app::python {
namespace {

using namespace pybind11::literals;

// What a run left, read back.
struct RunResult {
  py::dict trace;
  py::object summary = py::none();
  py::dict contacts;
  std::vector<std::string> failed_expectations;
  std::optional<std::string> out;
  long steps = 0;
};

// The folder this module was loaded from.
fs::path moduleFolder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&bindWorld), &info) == 0 || !info.dli_fname) return {};
  return fs::absolute(info.dli_fname).parent_path();
}

// The godfinger executable beside the module: a build tree's <build>/godfinger, or an installed
// prefix's bin/godfinger; else the one on PATH.
std::string godfingerExecutable() {
  const fs::path here = moduleFolder();
  for (const fs::path& exe : {here / ".." / "godfinger", here / GF_PY_TO_BIN / "godfinger"}) {
    if (!here.empty() && fs::exists(exe)) return fs::canonical(exe).string();
  }
  return "godfinger";
}

// Finds the bundled data beside the module (a build tree's share/godfinger, or the installed
// prefix's) for the scene reader and the runs a study starts, unless $GODFINGER_DATA says.
void findDataBesideModule() {
  const fs::path here = moduleFolder();
  if (here.empty() || std::getenv("GODFINGER_DATA")) return;
  for (const fs::path& data : {here / ".." / "share" / "godfinger", here / GF_PY_TO_DATA}) {
    if (fs::is_directory(data / "scenes")) {
      setenv("GODFINGER_DATA", fs::canonical(data).c_str(), 0);
      return;
    }
  }
}

// A folder of its own under the system's temporary folder, removed when done (unless kept).
class Scratch {
 public:
  explicit Scratch(const std::optional<std::string>& keep) {
    if (keep) {
      path_ = *keep;
      return;
    }
    std::string pattern = (fs::temp_directory_path() / "godfinger-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error(pattern + ": cannot create a temporary folder");
    path_ = pattern;
    owned_ = true;
  }
  ~Scratch() {
    std::error_code ignored;
    if (owned_) fs::remove_all(path_, ignored);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  const std::string& path() const { return path_; }
  void keep() { owned_ = false; }

 private:
  std::string path_;
  bool owned_ = false;
};

// trace.csv, summary.json and contacts/*.json of a finished run folder.
void readRunFolder(const fs::path& dir, RunResult& r) {
  if (fs::exists(dir / kTraceFile)) r.trace = columnsDict(readTrace(dir));
  if (const nlohmann::json summary = readSummary(dir); !summary.is_null()) r.summary = jsonObject(summary);
  for (const fs::path& f : contactFiles(dir)) r.contacts[py::str(f.stem().string())] = jsonObject(readJsonFile(f));
}

// An optional path argument: None, or a str, bytes or os.PathLike.
std::optional<std::string> optionalPath(const py::object& value, const std::string& what) {
  if (value.is_none()) return std::nullopt;
  return pathText(value, what);
}

RunResult run(const py::object& scene_arg, std::optional<double> duration, const py::dict& set,
              const py::object& out_arg, bool close_ups) {
  const std::string scene = pathText(scene_arg, "run: scene");
  const std::optional<std::string> out = optionalPath(out_arg, "run: out");
  const std::vector<std::string> overrides = overridesFromDict(set);
  SessionDesc session = loadSceneFile(resolveScenePath(scene), overrides);
  session.overrides = overrides;
  if (duration) {
    const sim::Setting<sim::SceneDesc>& d = *sim::findSetting(sim::sceneSettings(), "duration");
    if (const std::optional<std::string> why = sim::checkGiven(d, *duration)) {
      throw InputError("godfinger.run", 0, 0, "duration", *why);
    }
    session.scene.duration = *duration;
  }
  Scratch folder(out);
  SessionOptions options;
  options.out_dir = folder.path();
  options.progress = false;
  options.close_ups = close_ups;
  std::vector<ExpectFailure> failed;
  options.expect_failures = &failed;
  options.command_line = {"python3", "godfinger.run", scene};
  for (const std::string& o : overrides) options.command_line.push_back("--set=" + o);
  RunResult r;
  {
    py::gil_scoped_release unlocked;  // other Python threads go on while the run does
    r.steps = runSession(session, options).steps;
  }
  readRunFolder(folder.path(), r);
  for (const ExpectFailure& f : failed) r.failed_expectations.push_back(f.text());
  r.out = out;
  return r;
}

py::dict study(const py::object& name_arg, int jobs, bool quick, const py::dict& set, const py::object& out_arg,
               bool progress, bool restart) {
  const std::string name_or_file = pathText(name_arg, "study: name_or_file");
  const std::optional<std::string> out = optionalPath(out_arg, "study: out");
  if (jobs < 1 || jobs > 256) throw InputError("godfinger.study", 0, 0, "jobs", "must be in 1..256, got " + std::to_string(jobs));
  const StudyDesc desc = loadStudyFile(name_or_file);
  const std::vector<std::string> overrides = overridesFromDict(set);
  const StudyPlan plan = expandStudy(desc, quick, overrides);
  if (!quick) expandStudy(desc, true, overrides);  // the --quick grid's overrides are checked too, as the command does
  Scratch folder(out);
  StudyOptions options;
  options.out = folder.path();
  options.jobs = jobs;
  options.progress = progress;
  options.restart = restart;
  options.godfinger = godfingerExecutable();
  int code = 0;
  {
    py::gil_scoped_release unlocked;
    const RunFolder lock(options.out);
    code = runStudy(plan, options);
  }
  if (code != 0) {
    folder.keep();
    throw std::runtime_error("study " + desc.name + ": not every run succeeded and was measured (exit " +
                             std::to_string(code) + "); see " + options.out + "/report.md and runs/*/run.log");
  }
  return columnsDict(readCsvText((fs::path(options.out) / kResultsFile).string()));
}

}  // namespace

}  // namespace gf::app::python

PYBIND11_MODULE(godfinger, m) {
  namespace py = pybind11;
  using namespace gf::app::python;
  using namespace pybind11::literals;
  m.doc() = "godfinger: the god-finger contact method on Bullet (runs, live worlds, studies)";
  py::register_exception<gf::app::InputError>(m, "InputError", PyExc_ValueError);
  // Its message may hold a path's bytes that are not UTF-8 (a bytes path): decoded with
  // replacement characters rather than lost.
  py::register_exception_translator([](std::exception_ptr raised) {
    try {
      if (raised) std::rethrow_exception(raised);
    } catch (const gf::app::InputError& e) {
      const std::string what = e.what();
      const auto text = py::reinterpret_steal<py::object>(
          PyUnicode_DecodeUTF8(what.data(), static_cast<py::ssize_t>(what.size()), "replace"));
      PyErr_SetObject(py::module_::import("godfinger").attr("InputError").ptr(), text.ptr());
    }
  });
  findDataBesideModule();
  py::class_<RunResult>(m, "Run", "What a run wrote: trace, summary, contacts")
      .def_readonly("trace", &RunResult::trace, "trace.csv as {column: numpy array}")
      .def_readonly("summary", &RunResult::summary, "summary.json as a dict")
      .def_readonly("contacts", &RunResult::contacts, "contacts/*.json as {name: dict}")
      .def_readonly("failed_expectations", &RunResult::failed_expectations, "The scene's [expect] that failed")
      .def_readonly("steps", &RunResult::steps, "Haptic steps run")
      .def_readonly("out", &RunResult::out, "The run folder when one was given (else None: a temporary one, removed)");
  m.def("run", &run, "scene"_a, py::kw_only(), "duration"_a = py::none(), "set"_a = py::dict(), "out"_a = py::none(),
        "close_ups"_a = false, "Runs a scene as `godfinger run` does; returns its trace, summary and contacts");
  m.def("study", &study, "name_or_file"_a, py::kw_only(), "jobs"_a = 1, "quick"_a = false, "set"_a = py::dict(),
        "out"_a = py::none(), "progress"_a = false, "restart"_a = false,
        "Runs an accuracy study as `godfinger study` does (into `out`, the runs already finished there kept "
        "unless restart=True); returns results.csv as {column: numpy array}");
  bindWorld(m);
}
