// A study's measures, taken from one run folder (trace.csv, summary.json, contacts/) and the
// run's scene, and their references.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "app/runs/run_reader.hpp"
#include "app/scene/session_desc.hpp"
#include "app/study/study.hpp"

namespace gf::app {

/// What one run wrote, with the scene it ran (loaded again with the run's overrides).
struct RunOutputs {
  std::string dir;
  SessionDesc session;
  nlohmann::json summary;
  CsvTable trace;  ///< trace.csv

  /// The trace column `name`; throws InputError naming the file when it is missing.
  const std::vector<double>& column(const std::string& name) const;
};

/// Reads `dir`'s trace.csv and summary.json (app/runs/run_reader.hpp); throws
/// std::runtime_error naming the file when one is missing or malformed.
RunOutputs readRunOutputs(const std::string& dir, const SessionDesc& session);

struct MeasureResult {
  double measure = NAN, reference = NAN, error = NAN;
  std::string note;  ///< why the measure is NaN when the run gives it none (a roll ratio of a body at rest)
  /// What an analytic reference of the press was formed from (NaN for other references): the
  /// press force F (N), the pad radius r (m: the Eq. 1 radius of the press, or a soft pad's own)
  /// and the friction coefficient mu (NaN for F r, which has none).
  double press_force_n = NAN, press_radius_m = NAN, friction = NAN;
};

/// Measure `m` of `run` against its reference: the analytic formula of the run's own measured
/// quantities, or the same measure of `reference_run` (required for ReferenceKind::kRun).
/// Throws std::runtime_error when the outputs cannot give it.
MeasureResult evaluateMeasure(const StudyMeasure& m, const RunOutputs& run, const RunOutputs* reference_run);

/// The error of `measure` against `reference` as `kind` forms it.
double measureError(ErrorKind kind, double measure, double reference);

}  // namespace gf::app
