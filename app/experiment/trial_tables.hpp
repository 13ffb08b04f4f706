// The parts of an experiment's run that simulated and web participants share (internal to
// app/experiment): a trial's folder and name, its run, the BIDS-like tables and the summary.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/experiment/experiment.hpp"
#include "app/experiment/outcome.hpp"

namespace gf::app {

/// The trace a trial keeps: 100 rows a second are enough to judge a hold of 0.1 s and keep a
/// trial's trace near 100 kB.
inline constexpr double kTraceRateHz = 100.0;

/// Everything one trial runs with.
struct TrialRun {
  StudyRun run;                      ///< scene and overrides (for the key and the command line)
  std::vector<std::string> fingers;  ///< the task scene's
  std::vector<std::string> hand_files;
  std::string dir, key;
};

/// "007": the trial's number, its run folder's and hand files' name.
std::string trialName(const Trial& t);
/// out/sub-NN/beh.
std::filesystem::path behDir(const std::string& out, const Trial& t);
/// A TSV cell: tabs and line ends made spaces (they would break the table); empty: "n/a".
std::string tsvCell(std::string s);

/// The participant's table sub-NN/beh/sub-NN_task-LABEL_beh.tsv (+ .json): one row a trial
/// with an outcome (those not run yet left out; with none, no table).
void writeParticipantTable(const ExperimentDesc& e, const std::string& out, int p, const std::vector<Trial>& trials,
                           const std::vector<TrialRun>& runs, const std::vector<std::optional<TrialOutcome>>& outcomes);
/// experiment.json, dataset_description.json and participants.tsv (+ .json): every simulated
/// participant with their hand's figures, or the people with a folder in `out`.
void writeDatasetFiles(const ExperimentDesc& e, const std::string& out);
/// Per factor level and task: successes and the median completion time, on standard output.
void printSummary(const ExperimentDesc& e, const std::vector<Trial>& trials, const std::vector<std::optional<TrialOutcome>>& outcomes);

}  // namespace gf::app
