// An experiment performed by a person in the browser (`device = "web"`): one participant a
// session, `godfinger experiment FILE --participant N --serve [HOST:]PORT`. The page on that port
// goes through phases, each served by a server of its own on the one port: "ready" (the task's
// instruction, the trial and block, the last trial's result, a Start button), "trial" (the
// trial's realtime run: the frames with the goal drawn, the countdown; the pointer drives the
// task's fingers) and, after each block, "questionnaire" (Raw NASA-TLX's six scales and a realism
// rating). The page never shows the condition: no model, setting or level name reaches it.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "app/experiment/experiment.hpp"

namespace gf::app {

/// Raw NASA-TLX's six scales (Hart 2006: the unweighted mean of the six), each 0..100 in steps
/// of 5, as the table's columns name them.
inline constexpr std::array<const char*, 6> kTlxScales = {"mental_demand", "physical_demand", "temporal_demand",
                                                          "performance", "effort", "frustration"};

/// What a participant answered after a block.
struct BlockAnswers {
  int block = 0;
  std::array<int, 6> tlx{};  ///< kTlxScales, 0..100 (performance: 0 perfect, 100 failure)
  int realism = 0;           ///< 1 (not at all like touching a real object) .. 7 (just like it)
  /// The mean of the six scales (Raw TLX)
  double rawTlx() const;
};

/// The page's "answers mental_demand=V physical_demand=V ... realism=R" (any order, each once);
/// nullopt with `why` naming the first missing, repeated, unknown or out-of-range value.
std::optional<BlockAnswers> parseAnswers(const std::string& line, int block, std::string& why);

/// Runs participant options.participant's trials in the browser: resumes after the last trial
/// and questionnaire finished before (unless options.restart), writes the trial table, the
/// questionnaire table sub-NN/beh/sub-NN_task-LABEL_questionnaire.tsv (+ .json), the dataset's
/// files and the report. Returns 0, or 130 when interrupted (Ctrl-C) or stopped (--stop-after).
int runWebParticipant(const ExperimentDesc& e, const ExperimentOptions& options);

}  // namespace gf::app
