// Study files: reading, and expanding a study into its runs.
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "app/runs/jobs.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "app/scene/toml_reader.hpp"
#include "app/measures/contact_whole.hpp"
#include "app/study/study.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

constexpr const char* kMeasureKinds[] = {"friction_torque", "friction_force", "roll_ratio", "swing",
                                         "force_sd", "geodesic_radius", "trajectory", "tip_moment"};
constexpr const char* kReferenceKinds[] = {"run", "two_thirds_mu_f_r", "mu_f_r", "hertz_mu_f_r", "thin_layer_mu_f_r", "mu_f",
                                           "rolling_prediction", "patch_radius", "f_r"};
constexpr const char* kErrorKinds[] = {"relative", "absolute", "deviation"};
constexpr const char* kCostKinds[] = {"step", "patch"};
constexpr const char* kQuestions[] = {"cost", "effect"};

// The analytic references each measure can be compared with (the reference run always can).
bool referenceFits(MeasureKind m, ReferenceKind r) {
  switch (r) {
    case ReferenceKind::kRun: return true;
    case ReferenceKind::kTwoThirdsMuFR:
    case ReferenceKind::kMuFR:
    case ReferenceKind::kHertzMuFR:
    case ReferenceKind::kThinLayerMuFR: return m == MeasureKind::kFrictionTorque;
    case ReferenceKind::kMuF: return m == MeasureKind::kFrictionForce;
    case ReferenceKind::kRollingPrediction: return m == MeasureKind::kRollRatio;
    case ReferenceKind::kPatchRadius: return m == MeasureKind::kGeodesicRadius;
    case ReferenceKind::kFR: return m == MeasureKind::kTipMoment;
    case ReferenceKind::kValue: return m != MeasureKind::kTrajectory;  // its reference is the path's
  }
  return false;
}

StudySource sourceAt(const toml::node& n, const std::string& field) {
  return {static_cast<int>(n.source().begin.line), static_cast<int>(n.source().begin.column), field};
}

// A TOML value as `--set` reads it; numbers in their shortest exact form (0.3, not
// 0.29999999999999999), floats kept floats.
std::string tomlText(const toml::node& n) {
  if (const toml::array* a = n.as_array()) {
    std::string out = "[";
    for (std::size_t i = 0; i < a->size(); ++i) out.append(i ? ", " : "").append(tomlText(*a->get(i)));
    return out + "]";
  }
  if (n.is_floating_point()) {
    char b[32];
    const auto [end, ec] = std::to_chars(b, b + sizeof b, n.as_floating_point()->get());
    std::string out(b, ec == std::errc() ? end : b);
    if (out.find_first_of(".eni") == std::string::npos) out += ".0";
    return out;
  }
  std::ostringstream s;
  n.visit([&](const auto& v) { s << v; });
  return s.str();
}

std::vector<StudyOverride> readSet(Reader& r, const std::string& key) {
  std::vector<StudyOverride> out;
  const std::vector<std::pair<std::string, const toml::node*>> items = r.strings(key);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string field = r.field(key) + "." + std::to_string(i);
    const std::size_t eq = items[i].first.find('=');
    if (eq == std::string::npos || eq == 0) r.fail(items[i].second, key, "expected \"FIELD=VALUE\", got '" + items[i].first + "'");
    out.push_back({items[i].first, sourceAt(*items[i].second, field), {}});
  }
  return out;
}

std::vector<StudyOverride> axisValues(Reader& r, const std::string& key) {
  std::vector<StudyOverride> out;
  const toml::node* n = r.find(key);
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a) r.fail(n, key, std::string("expected an array of values, got ") + typeName(*n));
  if (a->empty()) r.fail(n, key, "empty: list at least one value");
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& v = *a->get(i);
    if (v.is_table()) r.fail(&v, key, "expected a value for --set, got a table");
    out.push_back({tomlText(v), sourceAt(v, r.field(key) + "." + std::to_string(i)), {}});
  }
  return out;
}

std::vector<StudyAxis> readAxes(Reader& parent, const std::string& key) {
  std::vector<StudyAxis> out;
  for (const auto& [name, t] : parent.arrayTables(key, "")) {
    Reader r(*t, parent.field(name), parent.file());
    StudyAxis axis;
    const toml::node* field = r.find("field");
    if (!field) r.fail(nullptr, "field", "missing: the scene field to vary (as for --set), or a list of them");
    if (field->is_string()) {
      axis.fields.push_back(field->as_string()->get());
    } else if (field->is_array()) {
      for (const auto& [text, node] : r.strings("field")) axis.fields.push_back(text);
    }
    if (axis.fields.empty()) r.fail(field, "field", "expected a field name or a non-empty array of them");
    axis.name = r.string("name", axis.fields.front());
    if (axis.name.empty()) r.fail(r.nodeOf("name"), "name", "must not be empty");
    for (const std::string& f : axis.fields) {
      if (f.empty() || f.find('=') != std::string::npos) r.fail(field, "field", "'" + f + "' is not a field path");
    }
    if (!r.has("values")) r.fail(nullptr, "values", "missing: the list of values");
    axis.values = axisValues(r, "values");
    axis.quick = axisValues(r, "quick");
    for (std::vector<StudyOverride>* list : {&axis.values, &axis.quick}) {
      for (StudyOverride& v : *list) v.field_source = sourceAt(*field, r.field("field"));
    }
    if (axis.quick.empty()) axis.quick = {axis.values.front()};
    axis.chart = r.boolean("chart", false);
    for (const StudyOverride& v : axis.values) {
      char* end = nullptr;
      const double x = std::strtod(v.text.c_str(), &end);
      if (axis.chart && (end == v.text.c_str() || *end != '\0' || !std::isfinite(x))) {
        r.fail(r.nodeOf("chart"), "chart", "a charted axis needs numbers as values, got " + v.text);
      }
    }
    r.finish();
    out.push_back(std::move(axis));
  }
  return out;
}

StudyMeasure readMeasure(Reader& r) {
  StudyMeasure m;
  m.source = sourceAt(r.table(), r.field(""));
  m.kind = static_cast<MeasureKind>(r.choice("kind", kMeasureKinds, -1));
  m.name = r.string("name", kMeasureKinds[static_cast<int>(m.kind)]);
  m.body = r.string("body", "");
  if (m.body.empty()) r.fail(nullptr, "body", "missing: the scene body the measure is taken on");
  m.finger = r.string("finger", "");
  m.axis = r.vec3("axis", m.axis);
  if (m.axis.norm() < 1e-9) r.fail(r.nodeOf("axis"), "axis", "must not be zero");
  m.axis.normalize();
  if (const toml::node* w = r.find("window")) {
    const toml::array* a = w->as_array();
    if (!a || a->size() != 2 || !a->get(0)->is_number() || !a->get(1)->is_number()) {
      r.fail(w, "window", "expected [from, to] in seconds");
    }
    m.from = a->get(0)->value<double>().value_or(0.0);
    m.to = a->get(1)->value<double>().value_or(0.0);
    if (!(m.from >= 0.0) || !(m.to > m.from)) r.fail(w, "window", "expected 0 <= from < to");
  }
  m.at = r.number("at", 0.0, 0.0, 1e6);
  // A number is a reference of its own (a free ball's roll ratio: 1); else a named one.
  const toml::node* reference = r.find("reference");
  if (reference && reference->is_number()) {
    m.reference = ReferenceKind::kValue;
    m.reference_value = r.number("reference", 0.0, -1e300, 1e300);
  } else {
    m.reference = static_cast<ReferenceKind>(r.choice("reference", kReferenceKinds, 0));
  }
  if (!referenceFits(m.kind, m.reference)) {
    const std::string name = m.reference == ReferenceKind::kValue
                                 ? std::string("a number")
                                 : "'" + std::string(kReferenceKinds[static_cast<int>(m.reference)]) + "'";
    r.fail(reference, "reference", name + " is not a reference of " + kMeasureKinds[static_cast<int>(m.kind)]);
  }
  const ErrorKind default_error = m.kind == MeasureKind::kTrajectory ? ErrorKind::kDeviation
                                  : m.kind == MeasureKind::kSwing || m.kind == MeasureKind::kForceSd ||
                                          m.kind == MeasureKind::kRollRatio
                                      ? ErrorKind::kAbsolute
                                      : ErrorKind::kRelative;
  m.error = static_cast<ErrorKind>(r.choice("error", kErrorKinds, static_cast<int>(default_error)));
  if ((m.kind == MeasureKind::kTrajectory) != (m.error == ErrorKind::kDeviation)) {
    r.fail(r.nodeOf("error"), "error", "a trajectory's error is its deviation; other measures are relative or absolute");
  }
  if (m.kind == MeasureKind::kGeodesicRadius && !r.has("at")) {
    r.fail(nullptr, "at", "missing: the time of the contacts snapshot the radius is read from");
  }
  r.finish();
  return m;
}

std::vector<StudyMeasure> readMeasures(Reader& parent, const std::string& key) {
  std::vector<StudyMeasure> out;
  if (!parent.has(key)) return out;
  for (const auto& [name, t] : parent.arrayTables(key, "", true)) {
    Reader r(*t, parent.field(name), parent.file());
    out.push_back(readMeasure(r));
  }
  return out;
}

// [reference_run]: true when present.
bool readReferenceRun(Reader& parent, std::vector<StudyOverride>& set, std::vector<StudyOverride>& quick_set) {
  const toml::node* n = parent.find("reference_run");
  if (!n) return false;
  if (!n->is_table()) parent.fail(n, "reference_run", std::string("expected a table, got ") + typeName(*n));
  Reader r(*n->as_table(), parent.field("reference_run"), parent.file());
  set = readSet(r, "set");
  quick_set = readSet(r, "quick_set");
  r.finish();
  return true;
}

std::string slug(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_';
    if (keep) out += c;
    else if (!out.empty() && out.back() != '-') out += '-';
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out;
}

// A value as written in results, without the quotes of a TOML string.
std::string valueText(const std::string& toml_value) {
  std::string v = toml_value;
  const bool quoted = v.size() >= 2 && (v.front() == '"' || v.front() == '\'') && v.back() == v.front();
  if (quoted) v = v.substr(1, v.size() - 2);
  return v;
}

void checkMeasures(const StudyDesc& study, const StudySeries& series, const SessionDesc& s) {
  for (const StudyMeasure& m : series.measures) {
    const auto fail = [&](const std::string& field, const std::string& why) {
      throw InputError(study.source, m.source.line, m.source.column, m.source.field + field, why);
    };
    const sim::BodyDesc* body = nullptr;
    for (const sim::BodyDesc& b : s.scene.bodies) {
      if (b.name == m.body) body = &b;
    }
    if (!body) fail("body", "no body '" + m.body + "' in " + s.source);
    if (m.kind != MeasureKind::kGeodesicRadius && body->mass <= 0.0) fail("body", "'" + m.body + "' is static: it does not move");
    if (m.kind == MeasureKind::kGeodesicRadius && body->shape != sim::ShapeKind::kSphere) fail("body", "must be a sphere");
    if (m.kind == MeasureKind::kRollRatio && body->shape != sim::ShapeKind::kSphere) fail("body", "must be a sphere");
    const bool friction = m.kind == MeasureKind::kFrictionTorque || m.kind == MeasureKind::kFrictionForce;
    if (friction && !hasFlatFaces(body->shape)) {
      fail("body", "must be a box or a cylinder: the measure checks that the finger's contact stays whole on "
                   "the flat face it presses");
    }
    bool finger = m.finger.empty() && !s.scene.fingers.empty();
    for (const sim::FingerDesc& f : s.scene.fingers) finger = finger || f.name == m.finger;
    if (!finger) fail("finger", "no finger '" + m.finger + "' in " + s.source);
    if (m.kind == MeasureKind::kGeodesicRadius) {
      bool recorded = false;
      for (double t : s.record.contact_times) recorded = recorded || std::abs(t - m.at) < 5e-4;
      if (!recorded) fail("at", "the scene records no contacts at " + std::to_string(m.at) + " s ([record] contacts)");
    }
    if (m.reference == ReferenceKind::kRun && !series.has_reference_run) {
      fail("reference", "'run' needs a [reference_run] in the study or the series");
    }
  }
}

// Most runs a study's grid may expand into: each is a process of seconds to minutes, and each is
// loaded and checked before anything runs (the bundled studies have at most 56).
constexpr double kMaxStudyRuns = 1000;

// The grid's size before it is built: per series the product of its axes' lengths, plus its
// reference run. A few axes of many values would otherwise exhaust the memory while the runs
// are listed.
void checkGridSize(const StudyDesc& study, bool quick) {
  double total = 0.0;
  for (const StudySeries& series : study.series) {
    if (quick && !series.quick) continue;
    double runs = 1.0;
    for (const StudyAxis& a : series.axes) runs *= static_cast<double>((quick ? a.quick : a.values).size());
    total += runs + (series.has_reference_run ? 1.0 : 0.0);
    if (total <= kMaxStudyRuns) continue;
    const StudySource at = series.axes.empty() ? StudySource{} : series.axes.back().values.front().field_source;
    std::ostringstream why;
    why << std::setprecision(15) << "the " << (quick ? "--quick " : "") << "grid has " << total << " runs with series '"
        << series.name << "', more than " << kMaxStudyRuns << " (use fewer values or split the study)";
    throw InputError(study.source, at.line, at.column, at.field, why.str());
  }
}

// `scored` and `question` fit together and the study: a cost question ranks runs by their error,
// so it is scored; an effect is shown against a charted axis; an unscored study has no measure
// that is itself an error (a trajectory is a distance from its reference run).
void checkQuestion(Reader& r, const StudyDesc& study) {
  const toml::node* question = r.nodeOf("question");
  if (study.question == StudyQuestion::kCost && !study.scored) {
    r.fail(question ? question : r.nodeOf("scored"), question ? "question" : "scored",
           "a cost question ranks runs by their error against the references: it needs scored = true "
           "(or question = \"effect\")");
  }
  if (study.question == StudyQuestion::kEffect && study.chart_axes.empty()) {
    r.fail(question, "question", "\"effect\" is shown against an axis: give an [[axes]] chart = true");
  }
  for (const StudySeries& s : study.series) {
    for (const StudyMeasure& m : s.measures) {
      if (study.scored || m.kind != MeasureKind::kTrajectory) continue;
      r.fail(r.nodeOf("scored"), "scored",
             "false, but measure '" + m.name + "' is a trajectory: its value is a distance from the reference run, an error");
    }
  }
}

}  // namespace

std::string resolveSceneIn(const std::string& base_dir, const std::string& scene) {
  const fs::path p = fs::path(base_dir) / scene;
  if (fs::is_regular_file(p)) return fs::absolute(p).lexically_normal().string();
  if (scene.find('/') != std::string::npos) throw InputError(p.string(), 0, 0, "", "no such scene file");
  return fs::absolute(resolveScenePath(scene)).string();
}

SessionDesc loadSceneWithOverrides(const std::string& source, const std::string& scene,
                                   const std::vector<StudyOverride>& overrides) {
  std::vector<std::string> texts;
  for (const StudyOverride& o : overrides) texts.push_back(o.text);
  try {
    return loadSceneFile(scene, texts);
  } catch (const InputError& e) {
    for (auto o = overrides.rbegin(); o != overrides.rend(); ++o) {
      const std::string key = o->text.substr(0, o->text.find('='));
      // The override's own field, a field below it, or a sibling in the table it writes into (a
      // finger named by mistake lacks its device).
      const std::string parent = key.substr(0, key.rfind('.') + 1);
      const bool same = e.field() == key || e.field().rfind(key + ".", 0) == 0 || key.rfind(e.field() + ".", 0) == 0 ||
                        (!parent.empty() && e.field().rfind(parent, 0) == 0) || e.file().rfind("--set " + o->text, 0) == 0;
      if (!same) continue;
      if (o->source.line == 0) throw commandLineError("--set " + o->text, e.field() + ": " + e.reason());
      // A field the scene does not have is the axis' fault, a bad value the value's.
      const bool unknown = e.reason().rfind("unknown field", 0) == 0 || e.reason().find("is not a table") != std::string::npos;
      const StudySource& at = unknown && o->field_source.line > 0 ? o->field_source : o->source;
      throw InputError(source, at.line, at.column, at.field,
                       "'" + o->text + "': " + (e.field().empty() ? "" : e.field() + ": ") + e.reason());
    }
    throw;
  }
}

std::string bundledStudyDir() {
  if (const char* env = std::getenv("GODFINGER_STUDIES"); env && *env) return env;
  return (fs::path(bundledSceneDir()).parent_path() / "studies").string();
}

StudyDesc loadStudyFile(const std::string& name_or_path) {
  const std::string path = resolveBundledFile(name_or_path, bundledStudyDir(), "study", "assets/studies");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, 0, "", "cannot open the study file");
  std::stringstream text;
  text << in.rdbuf();
  return parseStudyText(text.str(), path, fs::path(path).parent_path().string());
}

StudyDesc parseStudyText(const std::string& text, const std::string& source_name, const std::string& base_dir) {
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    throw InputError(source_name, static_cast<int>(e.source().begin.line), static_cast<int>(e.source().begin.column), "",
                     std::string(e.description()));
  }
  Reader r(root, "", source_name);
  StudyDesc study;
  study.source = source_name;
  study.name = r.string("name", fs::path(source_name).stem().string());
  study.summary = r.string("summary", "");
  study.cost = static_cast<CostKind>(r.choice("cost", kCostKinds, 0));
  study.scored = r.boolean("scored", true);
  study.question = static_cast<StudyQuestion>(r.choice("question", kQuestions, 0));
  const auto sceneOf = [&](Reader& at, const std::string& fallback) {
    const std::string scene = at.string("scene", "");
    if (scene.empty()) return fallback;
    try {
      return resolveSceneIn(base_dir, scene);
    } catch (const InputError& e) {
      at.fail(at.nodeOf("scene"), "scene", e.reason());
    }
  };
  const std::string scene = sceneOf(r, "");
  const std::vector<StudyOverride> set = readSet(r, "set");
  const std::vector<StudyAxis> axes = readAxes(r, "axes");
  for (const StudyAxis& a : axes) {
    if (a.chart) study.chart_axes.push_back(a.name);
  }
  const std::vector<StudyMeasure> measures = readMeasures(r, "measures");
  std::vector<StudyOverride> reference_set, reference_quick;
  const bool reference = readReferenceRun(r, reference_set, reference_quick);
  study.quick_set = readSet(r, "quick_set");
  for (const auto& [key, t] : r.arrayTables("series", ": the lines of the chart", true)) {
    Reader sr(*t, key, source_name);
    StudySeries s;
    s.name = sr.string("name", "");
    if (s.name.empty()) sr.fail(nullptr, "name", "missing: the series' name (its line in the chart)");
    for (const StudySeries& other : study.series) {
      if (other.name == s.name) sr.fail(sr.nodeOf("name"), "name", "'" + s.name + "' is already a series");
    }
    s.scene = sceneOf(sr, scene);
    if (s.scene.empty()) sr.fail(nullptr, "scene", "missing: no scene in the study nor in the series");
    s.set = set;
    for (StudyOverride& o : readSet(sr, "set")) s.set.push_back(std::move(o));
    s.axes = readAxes(sr, "axes");
    for (const StudyAxis& a : s.axes) {
      if (a.chart) sr.fail(sr.nodeOf("axes"), "axes", "chart: only an axis of the whole study ([[axes]]) is charted");
    }
    s.axes.insert(s.axes.end(), axes.begin(), axes.end());
    s.measures = readMeasures(sr, "measures");
    if (s.measures.empty()) s.measures = measures;
    if (s.measures.empty()) sr.fail(nullptr, "measures", "missing: no [[measures]] in the study nor in the series");
    std::vector<StudyOverride> own_reference, own_quick;
    if (readReferenceRun(sr, own_reference, own_quick)) {
      s.has_reference_run = true;
      s.reference_set = set;
      s.reference_set.insert(s.reference_set.end(), own_reference.begin(), own_reference.end());
      s.reference_quick_set = own_quick;
    } else if (reference) {
      s.has_reference_run = true;
      s.reference_set = set;
      s.reference_set.insert(s.reference_set.end(), reference_set.begin(), reference_set.end());
      s.reference_quick_set = reference_quick;
    }
    s.quick = sr.boolean("quick", true);
    sr.finish();
    study.series.push_back(std::move(s));
  }
  checkQuestion(r, study);
  r.finish();
  return study;
}

StudyPlan expandStudy(const StudyDesc& study, bool quick, const std::vector<std::string>& extra) {
  checkGridSize(study, quick);
  StudyPlan plan;
  plan.study = study;
  plan.quick = quick;
  plan.extra = extra;
  std::vector<StudyOverride> command;
  for (const std::string& e : extra) command.push_back({e, {}, {}});
  std::vector<StudyRun> references, runs;
  std::map<std::string, int> reference_index;  // scene + overrides -> index in references
  for (std::size_t si = 0; si < study.series.size(); ++si) {
    const StudySeries& series = study.series[si];
    if (quick && !series.quick) continue;
    int reference = -1;
    if (series.has_reference_run) {
      StudyRun ref;
      ref.measured_as = static_cast<int>(si);
      ref.scene = series.scene;
      ref.overrides = series.reference_set;
      ref.overrides.insert(ref.overrides.end(), command.begin(), command.end());
      if (quick) {
        ref.overrides.insert(ref.overrides.end(), study.quick_set.begin(), study.quick_set.end());
        ref.overrides.insert(ref.overrides.end(), series.reference_quick_set.begin(), series.reference_quick_set.end());
      }
      std::string key = ref.scene;
      for (const StudyOverride& o : ref.overrides) key += "\n" + o.text;
      const auto [it, added] = reference_index.emplace(key, static_cast<int>(references.size()));
      if (added) references.push_back(ref);
      reference = it->second;
    }
    // The cross product of the axes, the first axis varying fastest.
    std::vector<std::size_t> at(series.axes.size(), 0);
    while (true) {
      StudyRun run;
      run.series = run.measured_as = static_cast<int>(si);
      run.scene = series.scene;
      run.reference = reference;
      run.overrides = series.set;
      run.overrides.insert(run.overrides.end(), command.begin(), command.end());
      for (std::size_t k = 0; k < series.axes.size(); ++k) {
        const StudyOverride& v = (quick ? series.axes[k].quick : series.axes[k].values)[at[k]];
        for (const std::string& f : series.axes[k].fields) run.overrides.push_back({f + "=" + v.text, v.source, v.field_source});
        run.axis_values.emplace_back(series.axes[k].name, valueText(v.text));
      }
      if (quick) run.overrides.insert(run.overrides.end(), study.quick_set.begin(), study.quick_set.end());
      runs.push_back(std::move(run));
      std::size_t k = 0;
      for (; k < at.size(); ++k) {
        const std::size_t size = (quick ? series.axes[k].quick : series.axes[k].values).size();
        if (++at[k] < size) break;
        at[k] = 0;
      }
      if (k == at.size()) break;
    }
  }
  plan.runs = references;  // first, so a run's reference index is its index in plan.runs
  for (StudyRun& r : runs) plan.runs.push_back(std::move(r));
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    StudyRun& r = plan.runs[i];
    std::string name = r.series < 0 ? "reference" : study.series[static_cast<std::size_t>(r.series)].name;
    for (const auto& [field, value] : r.axis_values) name.append(1, '-').append(field.substr(field.rfind('.') + 1)).append(value);
    char prefix[32];
    std::snprintf(prefix, sizeof prefix, "%03zu-", i);
    r.id = std::string(prefix).append(slug(name));
    // Every configuration is loaded and checked before anything runs.
    const SessionDesc scene = loadSceneWithOverrides(study.source, r.scene, r.overrides);
    if (r.series >= 0) checkMeasures(study, study.series[static_cast<std::size_t>(r.series)], scene);
  }
  return plan;
}

std::vector<std::string> runArguments(const StudyRun& run) {
  // A study measures: the scene's [expect] is recorded, not a failure.
  std::vector<std::string> arguments = {"--expectations", "report"};
  for (const StudyOverride& o : run.overrides) arguments.insert(arguments.end(), {"--set", o.text});
  return arguments;
}

std::string runCommandLine(const std::string& godfinger, const std::string& out_dir, const StudyRun& run) {
  return godfingerRunLine(godfinger, run.scene, (fs::path(out_dir) / "runs" / run.id).string(), runArguments(run));
}

}  // namespace gf::app
