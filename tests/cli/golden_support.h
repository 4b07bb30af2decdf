// Shared by the golden-image tests: the thresholds, the comparison with a reference, and the HTML
// report written next to the new image when a comparison fails.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "render/review/image_diff.h"

namespace stirrup::test {

inline const std::filesystem::path kGoldenDir = std::filesystem::path(STIRRUP_SOURCE_DIR) / "tests/golden";

// The golden frames of tests/golden/trot_side.json.
// Frame 4: the diagonal pairs spread wide and the rider lifted; frame 9: the pairs passing, the
// rider sunk back into the saddle.
inline constexpr int kGoldenFrames[] = {4, 9};

// Rendering is byte-deterministic (the measured difference is 0 at every thread count), so the
// tolerance only has to absorb another CPU's floating-point paths: a handful of isolated pixels.
// A pixel fails when a channel is off by more than 4/255 (Blender's per-pixel threshold); the
// comparison fails when more than 0.01% of the pixels (5 of 320x180) fail. Blender's 0.5% (288
// pixels) let a 10% change of the Equation 1, 4 or 10 weights through: they move the rider's torso
// and head by 20-40 pixels of a 320x180 frame (README, "Golden images", for the measured margins).
inline render::DiffThresholds goldenThresholds() {
  render::DiffThresholds t;
  t.fail = 4.0 / 255.0;
  t.fail_fraction = 0.0001;
  t.warn = 1.0 / 255.0;
  t.warn_fraction = 0.0;
  return t;
}

// "trot_side.0004.png"
std::string goldenName(int frame);

// "NAME.0063.png"
std::string frameFileName(const std::string& base, int frame);

// The golden set of the shipped scenes (tests/golden/scenes.json): each shot renders
// scenes/SCENE.json through CAMERA at the set's resolution and preset, and each of its frames is
// compared with tests/golden/scenes/SCENE_CAMERA.####.png.
struct GoldenShot {
  std::string scene, camera;
  std::vector<int> frames;
  std::string why;
  std::string name() const { return scene + "_" + camera; }
};
inline void PrintTo(const GoldenShot& s, std::ostream* os) { *os << s.name(); }
// A movie of the review set (stirrup movies --only MOVIE --frames-limit N --keep-frames), whose
// output files (kept frames with burn-ins, the slate, sheets, plots) are compared with
// tests/golden/movies/FILENAME.
struct GoldenMovie {
  std::string movie;
  int frames_limit = 0;
  std::string date;
  std::vector<std::string> files;  // relative to the movies' output folder
  std::string why;
};
inline void PrintTo(const GoldenMovie& m, std::ostream* os) { *os << m.movie; }
struct GoldenSet {
  std::string resolution, preset;
  std::vector<GoldenShot> shots;
  std::vector<GoldenMovie> movies;
};
inline const std::filesystem::path kMovieGoldenDir = kGoldenDir / "movies";
inline const std::filesystem::path kSceneGoldenDir = kGoldenDir / "scenes";
GoldenSet loadGoldenSet();  // throws std::runtime_error naming the file and field on bad input

struct GoldenComparison {
  render::DiffResult diff;
  std::filesystem::path image, reference, diff_image;
  std::filesystem::path report;  // empty unless the comparison failed
  bool failed() const { return diff.verdict == render::DiffVerdict::Fail; }
  std::string message() const;   // the numbers and where the files and the report are
};

// Compares `image` with `reference` under goldenThresholds(), writing the diff image (x16) next to
// `image`. When the comparison fails, also copies the reference next to `image` and writes
// IMAGE_STEM.report.html there: the reference, the new image and the diff side by side (relative
// links) and the numbers.
GoldenComparison compareWithGolden(const std::filesystem::path& reference, const std::filesystem::path& image);

// One golden render: the stirrup command that makes it, the folder it renders into, and which rendered
// file is compared with which reference. The golden tests (golden_test.cpp) run these and only
// compare: nothing in the test suite writes a reference. The separate command that updates them after
// an intended change (update_goldens.cpp, run by scripts/update-goldens) runs the same list, so the
// frames live in one place.
struct GoldenRender {
  std::string name;  // "fixed:4", "shot:trot_side", "movie:trot_layered" (update_goldens --only)
  std::string args;  // stirrup's arguments, quoted
  std::filesystem::path out;  // where it renders: a folder under `base` (the tests' or the updater's own)
  struct File {
    std::filesystem::path image;      // rendered, in `out`
    std::filesystem::path reference;  // relative to kGoldenDir
  };
  std::vector<File> files;
  std::string why;
};
// `base` is the folder the renders go under: the tests' (kGoldenOutDir) or the updater's own, so the
// two never render into the same folder when CTest runs them side by side.
inline const std::filesystem::path kGoldenOutDir = std::filesystem::path(STIRRUP_BINARY_DIR) / "golden_out";
GoldenRender fixedTrotRender(int frame, const std::filesystem::path& base = kGoldenOutDir);  // trot_side.json
GoldenRender shotRender(const GoldenSet& set, const GoldenShot& shot, const std::filesystem::path& base = kGoldenOutDir);
GoldenRender movieRender(const GoldenSet& set, const GoldenMovie& movie, const std::filesystem::path& base = kGoldenOutDir);
// Every golden render: the fixed trot frames, every shot and every movie of the set.
std::vector<GoldenRender> allGoldenRenders(const std::filesystem::path& base = kGoldenOutDir);

}  // namespace stirrup::test
