#include "app/commands/commands.hpp"

#include <algorithm>
#include <filesystem>
#include <thread>

#include "app/runs/summary.hpp"
#include "render/gl/context.hpp"
#include "sim/about.hpp"

namespace gf::app {
namespace {

// run, patch, study, experiment, check, compare, list, live, mesh-info, plot, schema, screenshots: the
// order of `godfinger --help`.
constexpr CommandFactory kCommands[] = {makeRunCommand,      makePatchCommand,    makeStudyCommand,
                                        makeExperimentCommand, makeCheckCommand,    makeCompareCommand,  makeListCommand,
                                        makeLiveCommand,     makeMeshInfoCommand, makePlotCommand,
                                        makeSchemaCommand,   makeScreenshotsCommand, makeBenchCommand};

}  // namespace

std::span<const CommandFactory> commandTable() { return kCommands; }

int defaultJobs() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

std::string versionText() {
  std::string text = "godfinger " + versionString() + " (commit " + commitString() + ")\n";
  text += sim::bulletVersion() + ", " + sim::assimpVersion() + ", " + sim::eigenVersion() + "\n";
  try {
    const render::GlContext context;  // a 1x1 OSMesa context, just to ask it
    text += "OpenGL " + context.description() + " (OSMesa, offscreen)";
  } catch (const std::exception& e) {
    text += std::string("OpenGL: unavailable (") + e.what() + ")";
  }
  return text;
}

std::string selfExecutable() { return std::filesystem::canonical("/proc/self/exe").string(); }

}  // namespace gf::app
