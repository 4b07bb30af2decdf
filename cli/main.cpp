// stirrup: animate a horse, and stirrup moves the rider.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "render/tracer/sample_lanes.h"
#include "rig/error.h"

int main(int argc, char** argv) {
  CLI::App app{"stirrup " STIRRUP_VERSION
               ": bakes a rider's motion from a horse's controls and renders review movies"};
  app.require_subcommand(1);
  app.set_version_flag("--version", STIRRUP_VERSION);
  stirrup::cli::addBakeCommand(app);
  stirrup::cli::addBenchCommand(app);
  stirrup::cli::addCharacterCommand(app);
  stirrup::cli::addCheckCommand(app);
  stirrup::cli::addClipCommand(app);
  stirrup::cli::addDiffCommand(app);
  stirrup::cli::addFarmCommand(app);
  stirrup::cli::addLayerCommand(app);
  stirrup::cli::addLiveCommand(app);
  stirrup::cli::addMoviesCommand(app);
  stirrup::cli::addRenderCommand(app);
  stirrup::cli::addRigCommand(app);
  stirrup::cli::addSpineCommand(app);
  try {
    // STIRRUP_SIMD pins the integrator's SIMD kernels to one instruction set (SSE4, AVX2, AVX3 =
    // AVX-512), as STIRRUP_EMBREE_CONFIG pins Embree's: every target gives the same bytes.
    if (const char* simd = std::getenv("STIRRUP_SIMD"); simd && *simd) {
      try {
        stirrup::render::pinSimdTarget(simd);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string("STIRRUP_SIMD: ") + e.what());
      }
    }
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const stirrup::cli::ExitStatus& s) {
    return s.code;
  } catch (const stirrup::rig::InputError& e) {
    std::fprintf(stderr, "stirrup: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stirrup: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
