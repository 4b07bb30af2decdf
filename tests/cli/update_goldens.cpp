// update_goldens: re-renders the golden references in tests/golden/ after an intended change to the
// look, the rig or a default scene, and says how far each moved. The golden tests only compare; this
// program is the one thing that writes the references, and it refuses to run in CI (CI=true): a
// reference is replaced by a person who has looked at what moved, never by a build that happened to
// differ. scripts/update-goldens builds and runs it; docs/golden-tests.md.
//
//   update_goldens [--only NAME[,NAME...]] [--into DIR]
//     --only  the renders to update, by name: fixed:4 (tests/golden/trot_side.json, frame 4),
//             shot:trot_side (a shot of tests/golden/scenes.json), movie:trot_layered; all by default
//     --into  write the new references under DIR, laid out as tests/golden/, instead of into it
//
// Prints one line a reference ("scenes/trot_side.0028.png: unchanged", "... changed: <numbers>",
// "... new"). Exit status 0; 1 when a render failed (the references rendered before it are updated);
// 2 when refused or misused.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "render/review/image_diff.h"
#include "tests/cli/golden_support.h"
#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

// Copies `image` over `reference` and says whether and how far it moved.
std::string replaceGolden(const fs::path& reference, const fs::path& image) {
  std::string what = "new";
  if (fs::exists(reference)) {
    try {
      const render::DiffResult d = render::compareImageFiles(reference, image, goldenThresholds());
      what = d.max_error == 0.0 ? "unchanged" : "changed: " + d.summary();
    } catch (const std::exception& e) {
      what = std::string("replaced, not comparable: ") + e.what();
    }
  }
  fs::create_directories(reference.parent_path());
  fs::copy_file(image, reference, fs::copy_options::overwrite_existing);
  return what;
}

// CI services set CI (GitHub Actions, GitLab CI, CircleCI, Travis: CI=true); anything but unset,
// empty, 0 or false counts.
bool inCi() {
  const char* ci = std::getenv("CI");
  if (!ci) return false;
  std::string v = ci;
  std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return !(v.empty() || v == "0" || v == "false");
}

int fail(const std::string& message, int code) {
  std::fprintf(stderr, "update-goldens: %s\n", message.c_str());
  return code;
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> words;
  for (std::size_t start = 0; start <= list.size();) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    if (comma > start) words.push_back(list.substr(start, comma - start));
    start = comma + 1;
  }
  return words;
}

int run(int argc, char** argv) {
  if (inCi())
    return fail(std::string("refused: CI=") + std::getenv("CI") +
                    ": golden references are updated by hand after an intended change, never in CI "
                    "(run scripts/update-goldens on your machine, look at what moved, commit it)",
                2);
  std::vector<std::string> only;
  fs::path into = kGoldenDir;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--only" || arg == "--into") && i + 1 < argc) {
      const std::string value = argv[++i];
      if (arg == "--only") only = split(value);
      else into = value;
    } else {
      return fail(arg + ": expected --only NAME[,NAME...] or --into DIR", 2);
    }
  }
  // Rendered in a folder of its own: the golden tests may be rendering theirs at the same time.
  std::vector<GoldenRender> renders = allGoldenRenders(fs::path(STIRRUP_BINARY_DIR) / "golden_update");
  for (const std::string& name : only)
    if (std::none_of(renders.begin(), renders.end(), [&](const GoldenRender& r) { return r.name == name; }))
      return fail("--only: no golden render \"" + name + "\" (expected fixed:FRAME, shot:SCENE_CAMERA or movie:NAME)", 2);
  if (!only.empty())
    renders.erase(std::remove_if(renders.begin(), renders.end(),
                                 [&](const GoldenRender& r) { return std::find(only.begin(), only.end(), r.name) == only.end(); }),
                  renders.end());
  for (const GoldenRender& r : renders) {
    fs::remove_all(r.out);
    const CommandResult result = runStirrup(r.args);
    if (result.exit_code != 0)
      return fail(r.name + ": the render failed (the references before it are updated): " + result.err, 1);
    for (const GoldenRender::File& f : r.files) {
      if (!fs::exists(f.image)) return fail(r.name + ": " + f.image.string() + " was not written", 1);
      std::printf("%s: %s\n", f.reference.string().c_str(), replaceGolden(into / f.reference, f.image).c_str());
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace
}  // namespace stirrup::test

int main(int argc, char** argv) {
  try {
    return stirrup::test::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "update-goldens: %s\n", e.what());
    return 1;
  }
}
