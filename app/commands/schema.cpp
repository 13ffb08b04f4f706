// `godfinger schema`: the JSON Schema of scene files, for editors.
#include <cstdio>

#include "app/commands/commands.hpp"
#include "app/scene/schema.hpp"

namespace gf::app {
namespace {

class SchemaCommand final : public Command {
 public:
  CLI::App* add(CLI::App& app) override {
    return app.add_subcommand("schema", "Print the JSON Schema of scene files (for editors that check TOML against "
                                        "a schema)");
  }

  int run() override {
    std::fputs((sceneSchema().dump(2) + "\n").c_str(), stdout);
    return 0;
  }
};

}  // namespace

std::unique_ptr<Command> makeSchemaCommand(const std::vector<std::string>&) { return std::make_unique<SchemaCommand>(); }

}  // namespace gf::app
