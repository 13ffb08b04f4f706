#include "app/commands/commands.hpp"

#include <filesystem>

#include "app/runs/summary.hpp"
#include "render/context.hpp"
#include "sim/about.hpp"

namespace gf::app {
namespace {

// The order of `godfinger --help`.
constexpr CommandEntry kCommands[] = {
    {"run", makeRunCommand},         {"patch", makePatchCommand},   {"study", makeStudyCommand},
    {"check", makeCheckCommand},     {"compare", makeCompareCommand}, {"list", makeListCommand},
    {"live", makeLiveCommand},       {"mesh-info", makeMeshInfoCommand}, {"plot", makePlotCommand},
    {"schema", makeSchemaCommand},   {"screenshots", makeScreenshotsCommand},
};

}  // namespace

std::span<const CommandEntry> commandTable() { return kCommands; }

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
