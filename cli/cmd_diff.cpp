// stirrup diff A B: compares two images, or two image sequences frame by frame, like OpenImageIO's
// idiff, and exits 0 / 1 / 2 for pass / warn / fail (3 when the images cannot be compared).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include "cli/commands.h"
#include "render/review/image_diff.h"
#include "rig/error.h"
#include "scene/frame_sequence.h"

namespace stirrup::cli {
namespace {

namespace fs = std::filesystem;

struct DiffOptions {
  std::string a, b;
  double fail = 1e-6, failpercent = 0.0, warn = 1e-6, warnpercent = 0.0;
  double hardfail = std::numeric_limits<double>::infinity();
  std::string diff_image;
  double scale = 16.0;
};

bool isSequence(const std::string& s) { return scene::FrameSequence::isPattern(s); }

// Frames of a sequence pattern NAME.####.png found on disk, by frame number.
std::map<int, fs::path> findFrames(const std::string& pattern) {
  std::map<int, fs::path> frames = scene::FrameSequence::parse(pattern)->scan();
  if (frames.empty()) throw rig::InputError(pattern + ": no frames match the pattern");
  return frames;
}

std::string verdictName(render::DiffVerdict v) {
  switch (v) {
    case render::DiffVerdict::Pass: return "PASS";
    case render::DiffVerdict::Warn: return "WARNING";
    case render::DiffVerdict::Fail: return "FAILURE";
  }
  return "?";
}

void compareAll(const DiffOptions& o) {
  render::DiffThresholds t;
  t.fail = o.fail;
  t.fail_fraction = o.failpercent / 100.0;
  t.warn = o.warn;
  t.warn_fraction = o.warnpercent / 100.0;
  t.hardfail = o.hardfail;

  struct FramePair {
    int frame;
    fs::path a, b;
  };
  std::vector<FramePair> pairs;
  if (isSequence(o.a) != isSequence(o.b))
    throw rig::InputError("diff: expected two images or two sequences (NAME.####.png), got one of each");
  if (isSequence(o.a)) {
    const auto fa = findFrames(o.a), fb = findFrames(o.b);
    for (const auto& [frame, file] : fa) {
      auto it = fb.find(frame);
      if (it == fb.end()) throw rig::InputError(o.b + ": frame " + std::to_string(frame) + " is missing");
      pairs.push_back({frame, file, it->second});
    }
    for (const auto& [frame, file] : fb)
      if (!fa.count(frame)) throw rig::InputError(o.a + ": frame " + std::to_string(frame) + " is missing");
  } else {
    pairs.push_back({0, o.a, o.b});
  }

  render::DiffVerdict worst = render::DiffVerdict::Pass;
  for (const auto& [frame, a, b] : pairs) {
    fs::path diff_image;
    if (!o.diff_image.empty()) {
      diff_image = o.diff_image;
      if (isSequence(o.a) && isSequence(o.diff_image))  // OUT.####.png: the frame number in the #s
        diff_image = scene::FrameSequence::parse(o.diff_image)->path(frame);
      else if (pairs.size() > 1)  // one diff image per frame: OUT.ext -> OUT.<frame file name>
        diff_image = fs::path(o.diff_image).replace_extension("").string() + "." + b.filename().string();
      std::error_code ec;  // a failure here shows as the write's own one-line error
      if (diff_image.has_parent_path()) fs::create_directories(diff_image.parent_path(), ec);
    }
    const render::DiffResult r = render::compareImageFiles(a, b, t, diff_image, o.scale);
    std::printf("%s vs %s: %s: %s\n", a.string().c_str(), b.string().c_str(), verdictName(r.verdict).c_str(),
                r.summary().c_str());
    worst = std::max(worst, r.verdict);
  }
  if (pairs.size() > 1) std::printf("%zu frames: %s\n", pairs.size(), verdictName(worst).c_str());
  throw ExitStatus{static_cast<int>(worst)};
}

void runDiff(const DiffOptions& o) {
  try {
    compareAll(o);
  } catch (const rig::InputError& e) {  // images that cannot be compared: idiff's exit status 3
    std::fprintf(stderr, "stirrup: %s\n", e.what());
    throw ExitStatus{3};
  }
}

}  // namespace

void addDiffCommand(CLI::App& app) {
  auto o = std::make_shared<DiffOptions>();
  CLI::App* cmd = app.add_subcommand("diff", "Compare two images or image sequences like idiff");
  cmd->footer(
      "The error of a pixel is its largest absolute channel difference (0..1). FAILURE when more than\n"
      "--failpercent % of the pixels exceed --fail, or any pixel exceeds --hardfail; WARNING likewise with\n"
      "--warn / --warnpercent. Prints mean, RMS and max error, PSNR and the worst pixel.\n"
      "Sequences: give two patterns like out/a/trot_side.####.png out/b/trot_side.####.png.\n"
      "Exit status: 0 pass, 1 warning, 2 failure, 3 images that cannot be compared (size, channels).");
  cmd->add_option("a", o->a, "First image (the reference) or sequence pattern")->required();
  cmd->add_option("b", o->b, "Second image or sequence pattern")->required();
  cmd->add_option("--fail", o->fail, "Per-pixel failure threshold (default 1e-6)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--failpercent", o->failpercent, "Percent of pixels allowed over --fail (default 0)")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--warn", o->warn, "Per-pixel warning threshold (default 1e-6)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--warnpercent", o->warnpercent, "Percent of pixels allowed over --warn (default 0)")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--hardfail", o->hardfail, "No pixel may exceed this (default: none)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--diff-image,-o", o->diff_image, "Write |A - B| scaled by --scale; for sequences a pattern OUT.####.png (one file per frame)");
  cmd->add_option("--scale", o->scale, "Diff image scale (default 16)")->check(CLI::PositiveNumber);
  cmd->callback([o] { runDiff(*o); });
}

}  // namespace stirrup::cli
