// A study's report.md, written from its collected rows (study_run.cpp collects them). What it
// says follows the study's question: a scored cost study's errors and the best run per budget; a
// scored effect study's errors against its charted axis; an unscored one's values against the
// axis, beside the comparison values and the press they were formed from, without "error".
#pragma once

#include <string>
#include <vector>

#include "app/study/study.hpp"
#include "app/study/study_chart.hpp"

namespace gf::app {

/// The measures `run` is measured with: its series' own, or a reference run's first user's.
const std::vector<StudyMeasure>& measuresOf(const StudyPlan& plan, const StudyRun& run);

/// The report. `parallel_times`: the step times were taken with several runs at once.
std::string reportMd(const StudyPlan& plan, const std::vector<StudyRow>& rows, bool parallel_times);

}  // namespace gf::app
