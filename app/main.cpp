// The `godfinger` command: its command line is app/commands/command_line.cpp.
#include "app/commands/command_line.hpp"
#include "render/render_thread.hpp"

int main(int argc, char** argv) {
  gf::render::keepFreedMemory();  // before any thread: every thread then shares one malloc arena
  return gf::app::runCommandLine(argc, argv);
}
