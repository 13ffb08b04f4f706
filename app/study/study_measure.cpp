#include "app/study/study_measure.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include "app/runs/run_folder.hpp"
#include "app/runs/run_reader.hpp"
#include "app/measures/contact_whole.hpp"
#include "app/measures/roll_ratio.hpp"
#include "sim/scene/effective_settings.hpp"
#include "sim/patch/god_finger.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;
using sim::Vec3;

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

// Least-squares slope of y over x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
  const double d = n * sxx - sx * sx;
  return d > 0.0 ? (n * sxy - sx * sy) / d : NAN;
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? NAN : s / static_cast<double>(v.size());
}

// The rows of the run inside the measure's window, and the run's named things.
class View {
 public:
  View(const StudyMeasure& m, const RunOutputs& run) : m_(m), run_(run), t_(run.column("t")) {
    for (std::size_t i = 0; i < t_.size(); ++i) {
      if (t_[i] >= m.from - 1e-9 && t_[i] <= m.to + 1e-9) rows_.push_back(i);
    }
    if (rows_.size() < 2) fail("fewer than two trace rows in the window");
    const sim::SceneDesc& scene = run.session.scene;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      if (scene.bodies[b].name == m.body) body_ = &scene.bodies[b];
    }
    for (const sim::FingerDesc& f : scene.fingers) {
      if (!finger_ && (m.finger.empty() || f.name == m.finger)) finger_ = &f;
    }
    if (!body_) fail("no body '" + m.body + "'");
    if (!finger_) fail("no finger '" + m.finger + "'");
  }
  [[noreturn]] void fail(const std::string& why) const { throw std::runtime_error(run_.dir + ": " + m_.name + ": " + why); }

  const std::vector<std::size_t>& rows() const { return rows_; }
  double t(std::size_t row) const { return t_[row]; }
  const sim::BodyDesc& body() const { return *body_; }
  const sim::FingerDesc& finger() const { return *finger_; }
  // Body column `suffix` ("vx") at every window row.
  std::vector<double> bodyColumn(const std::string& suffix) const { return windowed(m_.body + "." + suffix); }
  Vec3 bodyVector(std::size_t row, const char* a, const char* b, const char* c) const {
    return Vec3(run_.column(m_.body + a)[row], run_.column(m_.body + b)[row], run_.column(m_.body + c)[row]);
  }
  Eigen::Quaterniond orientation(std::size_t row) const {
    const auto& c = [&](const char* s) { return run_.column(m_.body + s)[row]; };
    return Eigen::Quaterniond(c(".qw"), c(".qx"), c(".qy"), c(".qz")).normalized();
  }
  std::vector<double> windowed(const std::string& column) const {
    const std::vector<double>& c = run_.column(column);
    std::vector<double> out;
    for (std::size_t r : rows_) out.push_back(c[r]);
    return out;
  }
  std::vector<double> times() const { return windowed("t"); }
  // The finger's normal force along the axis (N), mean over the window.
  double normalForce() const {
    const std::string f = finger_->name;
    double sum = 0.0;
    for (std::size_t r : rows_) {
      sum += Vec3(run_.column(f + ".fx")[r], run_.column(f + ".fy")[r], run_.column(f + ".fz")[r]).dot(m_.axis);
    }
    return std::abs(sum / static_cast<double>(rows_.size()));
  }
  // Fails unless the finger pressed along the axis at every row of the window (a friction
  // limit measured after the body slid out from under the finger means nothing).
  void checkPressed() const {
    const std::string f = finger_->name;
    const double mean_press = normalForce();
    for (std::size_t r : rows_) {
      const double press =
          std::abs(Vec3(run_.column(f + ".fx")[r], run_.column(f + ".fy")[r], run_.column(f + ".fz")[r]).dot(m_.axis));
      if (!(press > 0.2 * mean_press) || mean_press <= 0.0) {
        char b[96];
        std::snprintf(b, sizeof b, "the finger did not press along the axis at t = %.4f s (lost contact?)", t_[r]);
        fail(b);
      }
    }
  }
  // Fails at the first row of the window where the finger's contact is no longer whole on the
  // face it presses (app/measures/contact_whole.hpp): a friction limit measured while the contact
  // hangs over the edge is partly the edge's. The window must end before it.
  void checkWhole() const {
    const std::string f = finger_->name;
    const sim::SceneDesc& scene = run_.session.scene;
    const sim::PatchSettings patch =
        sim::effectiveSettings(finger_->patch, scene.effects, scene.world.contact_solver).patch;
    const auto at = [&](const std::string& column, std::size_t r) { return run_.column(column)[r]; };
    for (std::size_t r : rows_) {
      PressState s;
      s.body = {bodyVector(r, ".px", ".py", ".pz"), orientation(r)};
      s.proxy = Vec3(at(f + ".px", r), at(f + ".py", r), at(f + ".pz", r));
      s.device = Vec3(at(f + ".dx", r), at(f + ".dy", r), at(f + ".dz", r));
      s.patch_radius = at(f + ".r", r);
      const std::optional<double> over = contactOverhang(*body_, patch, m_.axis, s);
      char b[96];
      if (!over) {
        std::snprintf(b, sizeof b, " along the axis at t = %.4f s", t_[r]);
        fail("the finger presses no flat face of the " + m_.body + b);
      }
      if (*over <= 0.0) continue;
      std::snprintf(b, sizeof b, " at t = %.4f s, inside the window [%g, %g]; end the window before it", t_[r],
                    m_.from, m_.to);
      fail("the finger's contact leaves the " + m_.body + "'s face" + b);
    }
  }
  // The finger's mean patch radius over the window rows where it had one (m); 0 when it had
  // none (a god-object or soft finger has no area).
  double patchRadius() const {
    std::vector<double> r;
    for (double x : windowed(finger_->name + ".r")) {
      if (x > 0.0) r.push_back(x);
    }
    return r.empty() ? 0.0 : mean(r);
  }
  // The pad radius Eq. 1 gives for the measured press: depth F / k of the coupling spring (m).
  // Every rigid model presses the same, so this is the pad the analytic torsion limits are of. A
  // soft pad's is its own: the mean radius of its pressed skin's area over the window.
  double pressRadius() const {
    if (softPad()) return patchRadius();
    const sim::PatchSettings& p = finger_->patch;
    return sim::contactRadius(normalForce() / finger_->coupling.stiffness, p.r_max, p.d0);
  }
  double friction() const { return finger_->patch.friction; }
  bool softPad() const { return finger_->patch.model == sim::ContactModel::kFemPad; }
  // F r for a measure about an axis across the press: F the mean magnitude of the finger's
  // coupling force over the window's first kPressRows rows, before the load tips the body (N),
  // r the Eq. 1 radius of its press depth F / k (m).
  double pressMoment() const {
    const auto [press, radius] = pressAcross();
    return press * radius;
  }
  // F and r of pressMoment() (N, m).
  std::pair<double, double> pressAcross() const {
    constexpr std::size_t kPressRows = 50;
    const std::string f = finger_->name;
    const std::size_t n = std::min(rows_.size(), kPressRows);
    double sum = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t r = rows_[k];
      sum += Vec3(run_.column(f + ".fx")[r], run_.column(f + ".fy")[r], run_.column(f + ".fz")[r]).norm();
    }
    const double press = sum / static_cast<double>(n);
    const sim::PatchSettings& p = finger_->patch;
    if (softPad()) return {press, patchRadius()};
    return {press, sim::contactRadius(press / finger_->coupling.stiffness, p.r_max, p.d0)};
  }
  // The loads on the body at time t: force (N) and torque (N m).
  std::pair<Vec3, Vec3> loads(double t) const {
    Vec3 f = Vec3::Zero(), tau = Vec3::Zero();
    for (const sim::LoadDesc& l : run_.session.scene.loads) {
      if (l.body_name != m_.body) continue;
      const double k = sim::loadFactor(l, t);
      f += k * l.force;
      tau += k * l.torque;
    }
    return {f, tau};
  }
  // The body's moment of inertia about the axis at a row (kg m^2), from summary.json.
  double inertiaAbout(std::size_t row) const {
    for (const nlohmann::json& b : run_.summary.at("bodies")) {
      if (b.at("name") != m_.body) continue;
      const Eigen::Matrix3d rot = orientation(row).toRotationMatrix();
      double i = 0.0;
      for (int k = 0; k < 3; ++k) i += b.at("inertia_kg_m2")[k].get<double>() * std::pow(m_.axis.dot(rot.col(k)), 2);
      return i;
    }
    fail("summary.json lists no inertia of '" + m_.body + "'");
  }

 private:
  const StudyMeasure& m_;
  const RunOutputs& run_;
  const std::vector<double>& t_;
  std::vector<std::size_t> rows_;
  const sim::BodyDesc* body_ = nullptr;
  const sim::FingerDesc* finger_ = nullptr;
};

// Applied torque about the axis minus I times the fitted angular acceleration: the friction
// torque while the body spins (N m).
double frictionTorque(const StudyMeasure& m, const View& v) {
  v.checkWhole();
  v.checkPressed();
  std::vector<double> t = v.times(), w, applied, inertia;
  for (std::size_t r : v.rows()) {
    w.push_back(v.bodyVector(r, ".wx", ".wy", ".wz").dot(m.axis));
    applied.push_back(v.loads(v.t(r)).second.dot(m.axis));
    inertia.push_back(v.inertiaAbout(r));
  }
  return mean(applied) - mean(inertia) * slope(t, w);
}

// Applied force minus m times the fitted acceleration, across the axis: the friction force (N).
double frictionForce(const StudyMeasure& m, const View& v) {
  v.checkWhole();
  v.checkPressed();
  const std::vector<double> t = v.times();
  Vec3 applied = Vec3::Zero();
  for (std::size_t r : v.rows()) applied += v.loads(v.t(r)).first / static_cast<double>(v.rows().size());
  const Vec3 a(slope(t, v.bodyColumn("vx")), slope(t, v.bodyColumn("vy")), slope(t, v.bodyColumn("vz")));
  const Vec3 f = applied - v.body().mass * a;
  return (f - f.dot(m.axis) * m.axis).norm();
}

// A measure's value, and why it has none when it is NaN.
struct Value {
  double x = NAN;
  std::string note;
};

// Rotation angle times the radius over the distance travelled across the axis
// (app/measures/roll_ratio.hpp, as [expect] max_roll_ratio takes it); none for a body at rest.
Value rollRatio(const StudyMeasure& m, const View& v) {
  RollRatio roll(v.body().radius, m.axis);
  for (std::size_t r : v.rows()) roll.add(v.bodyVector(r, ".px", ".py", ".pz"), v.orientation(r));
  if (roll.travelled()) return {roll.value(), {}};
  char b[160];
  std::snprintf(b, sizeof b, "the %s went %.3g mm in the window [%g, %g], less than %g %% of its radius (it rests)",
                m.body.c_str(), roll.distance() * 1e3, m.from, m.to, RollRatio::kMinTravel * 100.0);
  return {NAN, std::string("no roll ratio: ") + b};
}

// The moment the contact held about the axis when the body tipped: at the first row where the
// body has turned about the axis by kTipAngleDeg since the window's start, the applied torque
// about it minus I times the angular acceleration fitted over the kTipFitRows rows up to it.
Value tipMoment(const StudyMeasure& m, const View& v) {
  constexpr std::size_t kTipFitRows = 20;
  const Eigen::Quaterniond q0 = v.orientation(v.rows().front());
  std::vector<double> t, w;
  for (std::size_t r : v.rows()) {
    t.push_back(v.t(r));
    w.push_back(v.bodyVector(r, ".wx", ".wy", ".wz").dot(m.axis));
    const Eigen::AngleAxisd aa(v.orientation(r) * q0.inverse());
    if (std::abs(aa.angle() * aa.axis().dot(m.axis)) * kRadToDeg < kTipAngleDeg) continue;
    const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(std::min(t.size(), kTipFitRows));
    const std::vector<double> tt(t.end() - n, t.end()), ww(w.end() - n, w.end());
    return {v.loads(v.t(r)).second.dot(m.axis) - v.inertiaAbout(r) * slope(tt, ww), {}};
  }
  char b[160];
  std::snprintf(b, sizeof b, "no tip moment: the %s did not turn by %g deg about the axis in the window [%g, %g]",
                m.body.c_str(), kTipAngleDeg, m.from, m.to);
  return {NAN, b};
}

// Largest rotation about the axis since the window's first row (deg).
double swing(const StudyMeasure& m, const View& v) {
  const Eigen::Quaterniond q0 = v.orientation(v.rows().front());
  double out = 0.0;
  for (std::size_t r : v.rows()) {
    const Eigen::AngleAxisd aa(v.orientation(r) * q0.inverse());
    out = std::max(out, std::abs(aa.angle() * aa.axis().dot(m.axis)) * kRadToDeg);
  }
  return out;
}

// Standard deviation of m (dv/dt - g) along the axis over the window (N).
double forceSd(const StudyMeasure& m, const View& v, const RunOutputs& run) {
  const sim::SceneDesc& scene = run.session.scene;
  const double g = scene.effects.gravity ? scene.world.gravity.dot(m.axis) : 0.0;
  const std::vector<double>& t = run.column("t");
  const std::vector<double> &vx = run.column(m.body + ".vx"), &vy = run.column(m.body + ".vy"),
                            &vz = run.column(m.body + ".vz");
  std::vector<double> f;
  for (std::size_t r : v.rows()) {
    if (r == 0) continue;
    const double dv = Vec3(vx[r] - vx[r - 1], vy[r] - vy[r - 1], vz[r] - vz[r - 1]).dot(m.axis);
    f.push_back(v.body().mass * (dv / (t[r] - t[r - 1]) - g));
  }
  const double mu = mean(f);
  double s2 = 0.0;
  for (double x : f) s2 += (x - mu) * (x - mu);
  return std::sqrt(s2 / static_cast<double>(f.size()));
}

// The contacts snapshot at the measure's time: the finger's first contact.
nlohmann::json contactAt(const StudyMeasure& m, const RunOutputs& run, const View& v) {
  const std::string path = (fs::path(run.dir) / kContactsFolder / (contactStem(m.at) + ".json")).string();
  const nlohmann::json j = readContacts(run.dir, m.at);
  for (const nlohmann::json& f : j.at("fingers")) {
    if (f.at("name") != v.finger().name) continue;
    if (f.at("contacts").empty()) v.fail(path + ": the finger has no contact");
    return f.at("contacts")[0];
  }
  v.fail(path + ": no finger '" + v.finger().name + "'");
}

Vec3 vec(const nlohmann::json& a) { return Vec3(a[0].get<double>(), a[1].get<double>(), a[2].get<double>()); }

// Mean great-circle distance from the contact point to the ring's SGOs on the sphere (m).
double geodesicRadius(const StudyMeasure& m, const RunOutputs& run, const View& v) {
  const nlohmann::json c = contactAt(m, run, v);
  const Vec3 centre = v.body().position, p = vec(c.at("point")) - centre;
  const std::size_t n = std::min<std::size_t>(c.at("sgos").size(), static_cast<std::size_t>(v.finger().patch.n_sgo));
  if (n == 0) v.fail("the contact has no SGO");
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 s = vec(c.at("sgos")[i]) - centre;
    sum += v.body().radius * std::atan2(p.cross(s).norm(), p.dot(s));
  }
  return sum / static_cast<double>(n);
}

// RMS distance between the body's path and the reference run's at this run's times (m), and
// the RMS distance of the reference path from its start (m).
std::pair<double, double> trajectory(const StudyMeasure& m, const RunOutputs& run, const RunOutputs& ref) {
  const std::vector<double>& t = run.column("t");
  const std::vector<double>& tr = ref.column("t");
  const auto at = [&](const RunOutputs& o, std::size_t r) {
    return Vec3(o.column(m.body + ".px")[r], o.column(m.body + ".py")[r], o.column(m.body + ".pz")[r]);
  };
  const Vec3 start = at(ref, 0);
  double dev = 0.0, disp = 0.0;
  long n = 0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < m.from - 1e-9 || t[i] > m.to + 1e-9 || t[i] < tr.front() || t[i] > tr.back()) continue;
    while (j + 1 < tr.size() && tr[j + 1] < t[i]) ++j;
    const std::size_t k = std::min(j + 1, tr.size() - 1);
    const double w = tr[k] > tr[j] ? std::clamp((t[i] - tr[j]) / (tr[k] - tr[j]), 0.0, 1.0) : 0.0;
    const Vec3 p_ref = (1 - w) * at(ref, j) + w * at(ref, k);
    dev += (at(run, i) - p_ref).squaredNorm();
    disp += (p_ref - start).squaredNorm();
    ++n;
  }
  if (n == 0) throw std::runtime_error(run.dir + ": " + m.name + ": no time in common with the reference run");
  return {std::sqrt(dev / n), std::sqrt(disp / n)};
}

Value measureOnly(const StudyMeasure& m, const RunOutputs& run, const View& v) {
  switch (m.kind) {
    case MeasureKind::kFrictionTorque: return {frictionTorque(m, v), {}};
    case MeasureKind::kFrictionForce: return {frictionForce(m, v), {}};
    case MeasureKind::kRollRatio: return rollRatio(m, v);
    case MeasureKind::kSwing: return {swing(m, v), {}};
    case MeasureKind::kForceSd: return {forceSd(m, v, run), {}};
    case MeasureKind::kGeodesicRadius: return {geodesicRadius(m, run, v), {}};
    case MeasureKind::kTipMoment: return tipMoment(m, v);
    case MeasureKind::kTrajectory: break;
  }
  v.fail("a trajectory is measured against its reference run");
}

}  // namespace

const std::vector<double>& RunOutputs::column(const std::string& name) const { return trace.column(name); }

RunOutputs readRunOutputs(const std::string& dir, const SessionDesc& session) {
  return {dir, session, requireSummary(dir), readTrace(dir)};
}

double measureError(ErrorKind kind, double measure, double reference) {
  switch (kind) {
    case ErrorKind::kRelative: return measure / reference - 1.0;
    case ErrorKind::kAbsolute: return measure - reference;
    case ErrorKind::kDeviation: return measure / reference;
  }
  return NAN;
}

namespace {

// The press an analytic reference was formed from, in `r`.
void statePress(ReferenceKind k, const View& v, MeasureResult& r) {
  switch (k) {
    case ReferenceKind::kTwoThirdsMuFR:
    case ReferenceKind::kMuFR:
    case ReferenceKind::kHertzMuFR:
    case ReferenceKind::kThinLayerMuFR:
      r.press_force_n = v.normalForce();
      r.press_radius_m = v.pressRadius();
      r.friction = v.friction();
      return;
    case ReferenceKind::kMuF:
      r.press_force_n = v.normalForce();
      r.friction = v.friction();
      return;
    case ReferenceKind::kFR: std::tie(r.press_force_n, r.press_radius_m) = v.pressAcross(); return;
    default: return;
  }
}

}  // namespace

MeasureResult evaluateMeasure(const StudyMeasure& m, const RunOutputs& run, const RunOutputs* reference_run) {
  MeasureResult r;
  const View v(m, run);
  if (m.kind == MeasureKind::kTrajectory) {
    if (!reference_run) v.fail("no reference run");
    std::tie(r.measure, r.reference) = trajectory(m, run, *reference_run);
  } else {
    const Value x = measureOnly(m, run, v);
    r.measure = x.x;
    r.note = x.note;
    switch (m.reference) {
      case ReferenceKind::kRun:
        if (!reference_run) v.fail("no reference run");
        r.reference = measureOnly(m, *reference_run, View(m, *reference_run)).x;
        break;
      case ReferenceKind::kValue: r.reference = m.reference_value; break;
      case ReferenceKind::kTwoThirdsMuFR: r.reference = 2.0 / 3.0 * v.friction() * v.normalForce() * v.pressRadius(); break;
      case ReferenceKind::kMuFR: r.reference = v.friction() * v.normalForce() * v.pressRadius(); break;
      case ReferenceKind::kHertzMuFR:
        r.reference = 3.0 * std::numbers::pi / 16.0 * v.friction() * v.normalForce() * v.pressRadius();
        break;
      case ReferenceKind::kThinLayerMuFR: r.reference = 8.0 / 15.0 * v.friction() * v.normalForce() * v.pressRadius(); break;
      case ReferenceKind::kMuF: r.reference = v.friction() * v.normalForce(); break;
      case ReferenceKind::kRollingPrediction:
        r.reference = v.friction() + v.patchRadius() / v.body().radius >= 1.0 ? 0.0 : 1.0;
        break;
      case ReferenceKind::kFR: r.reference = v.pressMoment(); break;
      case ReferenceKind::kPatchRadius: r.reference = contactAt(m, run, v).at("radius_m").get<double>(); break;
    }
    statePress(m.reference, v, r);
  }
  r.error = measureError(m.error, r.measure, r.reference);
  return r;
}

}  // namespace gf::app
