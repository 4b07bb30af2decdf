// Each subcommand of `stirrup` lives in its own file and registers itself on the app here.
// A callback reports bad input by throwing rig::InputError (one line, printed by main, exit 1).
#pragma once

#include <CLI/CLI.hpp>

namespace stirrup::cli {

// Thrown by a command that has already reported its outcome and wants `stirrup` to exit with `code`
// (for example `diff`: 0 pass, 1 warn, 2 fail, 3 images that cannot be compared).
struct ExitStatus {
  int code = 0;
};

void addBakeCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addDiffCommand(CLI::App& app);
void addFarmCommand(CLI::App& app);
void addLayerCommand(CLI::App& app);
void addLiveCommand(CLI::App& app);
void addMoviesCommand(CLI::App& app);
void addCharacterCommand(CLI::App& app);
void addCheckCommand(CLI::App& app);
void addClipCommand(CLI::App& app);
void addRenderCommand(CLI::App& app);
void addRigCommand(CLI::App& app);
void addSpineCommand(CLI::App& app);

}  // namespace stirrup::cli
