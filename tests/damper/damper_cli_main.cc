// Stand-in for hybridsim's main (server/ owns the real one): exposes the `damper` subcommands.
#include "server/commands/damper_commands.h"

int main(int argc, char** argv) {
  CLI::App app{"damper_cli: the `hybridsim damper ...` commands, standalone"};
  app.require_subcommand(1);
  add_damper_commands(app);
  CLI11_PARSE(app, argc, argv);
  return 0;
}
