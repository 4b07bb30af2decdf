// stirrup rig eval HORSE.csv -o RIDER.csv: evaluates the rider rig on every row of a horse channel CSV.
// stirrup rig params: lists a profile's parameters, their values and the thesis passages they cite.
// stirrup rig balance SCENE: what the balance stage (rig/balance.h) decides on every frame of a scene.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/options.h"
#include "rig/bake.h"
#include "rig/error.h"
#include "rig/io/atomic_file.h"
#include "rig/io/channel_csv.h"
#include "rig/io/gltf_character.h"
#include "rig/pose.h"
#include "rig/rider_rig.h"
#include "scene/clip_factory.h"
#include "scene/frame_range.h"
#include "scene/profile_resolver.h"
#include "scene/ridden_pair.h"
#include "scene/rig_profile_json.h"
#include "scene/scene.h"
#include "scene/shot_evaluator.h"

namespace stirrup::cli {
namespace {

struct RigOptions {
  std::string scene;
  std::string horse_csv;
  std::string rider_csv;
  std::string profile = "thesis";
  std::vector<std::string> sets;
  bool allow_impossible = false;  // rig balance: a scene beyond a horse's limits loads, warning each frame
};

rig::RigProfile resolveProfile(const RigOptions& o) { return scene::resolveProfile(o.profile, parseSets(o.sets)); }

void runEval(const RigOptions& o) {
  const rig::RigProfile profile = resolveProfile(o);
  // Read and evaluate everything before writing, so bad input leaves no output file.
  const rig::HorseTrack track = rig::readHorseCsv(o.horse_csv);
  std::vector<rig::RiderChannels> rider;
  rider.reserve(track.horse.size());
  for (const rig::HorseChannels& h : track.horse) rider.push_back(rig::evaluateRider(h, profile));
  rig::writeRiderCsv(o.rider_csv, track.frames, rider);
}

void runParams(const RigOptions& o) {
  const rig::RigProfile profile = resolveProfile(o);
  std::printf("# profile %s: %s\n", profile.name.c_str(), profile.doc.c_str());
  for (const rig::RigParameter& param : rig::rigParameters()) {
    const std::string key(param.key), cites(param.cites);
    const auto text = [](double v) {
      char buf[32];
      const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
      return ec == std::errc() ? std::string(buf, end) : std::string("?");
    };
    std::printf("%s = %s  # %s (valid %s to %s)\n", key.c_str(), text(param.get(profile)).c_str(), cites.c_str(),
                text(param.min).c_str(), text(param.max).c_str());
  }
}

// One row a frame (a crowd: a frame and a pair, the pair's index first): the horse's back above level,
// the trunk's world lean as the channels pose it and as the stage leaves it (measured from the posed
// pelvis and neck joints), and the stage's terms; then sideways, the turn's tilt the stage answers, the
// horse's roll and her lean from the world's vertical, measured on the posed joints. Every pair is posed
// by the shot's evaluator (scene/shot_evaluator.h) with its own profile, the scene's overrides and
// then --set applied.
void runBalance(const RigOptions& o) {
  scene::SceneSpec scene = scene::loadScene(o.scene, {o.allow_impossible});
  // A crowd's pairs resolve their own profiles from the scene: --set joins its overrides, after them.
  const rig::RigProfile profile = scene::resolveProfileForEveryPair(scene, parseSets(o.sets));
  scene::ShotEvaluator characters(scene, profile, 0);
  const bool crowd = characters.isCrowd();
  std::ostringstream out;
  out << (crowd ? "pair," : "")
      << "frame,back_pitch_deg,thesis_lean_deg,channel_lean_deg,support_lean_deg,inertia_lean_deg,lean_deg,"
         "turn_deg,seat_lift_cm,limited,turn_tilt_deg,roll_deg,side_lean_deg\n";
  char row[320];
  scene::ShotFrame frame;
  for (int f : scene::parseFrameList(scene.frames, "frames")) {
    scene::FrameRequest request;
    request.frame = f;
    request.until = scene::EvalStage::Pose;
    characters.evaluate(request, frame);
    scene::warnImpossibleFrame(scene, f);
    for (int i = 0; i < characters.pairCount(); ++i) {
      const rig::Character& horse = characters.horse(i);
      const rig::Character& rider = characters.rider(i);
      const rig::MountedPose& pose = frame.pairs[std::size_t(i)].pose;
      const glm::mat4& saddle = pose.horse[horse.role("saddle")];
      const glm::vec3 heading = rig::saddleHeading(saddle);
      const glm::vec3 x(saddle[0]);
      const double back = std::atan2(double(x.y), double(glm::dot(x, heading))) * 180.0 / 3.14159265358979323846;
      const glm::vec3 trunk = glm::vec3(pose.rider[rider.role("neck")][3]) - glm::vec3(pose.rider[rider.role("pelvis")][3]);
      const double lean = rig::leanDegrees(trunk, heading);
      const rig::BalanceResult& r = pose.balance;
      if (crowd) out << i << ',';
      std::snprintf(row, sizeof row, "%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%d,%.3f,%.3f,%.3f\n", f, back, r.pose_lean_deg,
                    r.channel_lean_deg, r.support_lean_deg, r.inertia_lean_deg, lean, r.turn_deg, r.seat_lift_cm,
                    int(r.limited), r.turn_tilt_deg, rig::horseRollDegrees(horse, pose.horse),
                    rig::leanDegrees(trunk, rig::sideways(heading)));
      out << row;
    }
  }
  if (o.rider_csv.empty()) {
    std::fputs(out.str().c_str(), stdout);
    return;
  }
  const std::string text = out.str();
  rig::writeFileAtomically(o.rider_csv, std::vector<unsigned char>(text.begin(), text.end()));
}

void addProfileOptions(CLI::App* cmd, const std::shared_ptr<RigOptions>& opts) {
  cmd->add_option("--profile,-p", opts->profile,
                  "Rig profile: a name (thesis, english, novice, rigid) looked up in $STIRRUP_PROFILES, then in "
                  "scenes/profiles in stirrup's data folder, or a path to a .json file (docs/rider-rig.md)")
      ->capture_default_str();
  cmd->add_option("--set,-s", opts->sets,
                  "Override one profile parameter, KEY=NUMBER (repeatable), e.g. --set eq7.w2_scale=0.015; "
                  "keys: `stirrup rig params`, docs/rider-rig.md");
}

}  // namespace

void addRigCommand(CLI::App& app) {
  CLI::App* rig_cmd = app.add_subcommand("rig", "Evaluate the rider rig (Kuhnel 2003) on horse channels");
  rig_cmd->require_subcommand(1);

  auto opts = std::make_shared<RigOptions>();
  CLI::App* eval = rig_cmd->add_subcommand("eval", "Evaluate the rider rig on every row of a horse channel CSV");
  eval->footer(
      "HORSE.csv: a header row, then one row per frame, comma-separated.\n"
      "  The header holds `frame` and any subset of the horse channels of docs/channels.md, in\n"
      "  any order: lfHoof rfHoof lbHoof rbHoof .tx .ty .tz (cm), rearPivot .tx .ty .tz (cm) .rx .ry .rz\n"
      "  (degrees), backMid .rx .ry .rz (degrees). Absent channels are 0 (the rest pose). Values are\n"
      "  offsets from rest in the horse's travel frame; blank lines are skipped.\n"
      "RIDER.csv: `frame` then every rider channel (lowerBack.rz ... cloth.side): rotations in degrees,\n"
      "  translations in rider units (profile rider_unit_cm cm each), hair/cloth as drive values.\n"
      "  Written to RIDER.csv.tmp and renamed, so an error leaves no output file.\n"
      "Errors (exit 1, one line): a missing `frame` column, an unknown or repeated column, a row with\n"
      "  more or fewer fields than the header, an empty, non-numeric or non-finite value, e.g.\n"
      "  `stirrup: horse.csv: row 3, column lfHoof.ty: expected a number, got \"high\"` (row = line number).\n"
      "Example: stirrup rig eval trot_horse.csv -o trot_rider.csv --profile novice --set eq7.w2_scale=0.02");
  eval->add_option("horse", opts->horse_csv, "Horse channel CSV (input)")->required();
  eval->add_option("--out,-o", opts->rider_csv, "Rider channel CSV (output)")->required();
  addProfileOptions(eval, opts);
  eval->callback([opts] { runEval(*opts); });

  CLI::App* balance = rig_cmd->add_subcommand("balance", "Print what the balance stage decides on every frame of a scene");
  balance->footer(
      "CSV, one row a frame (docs/rider-rig.md, \"Balance\"): back_pitch_deg (the horse's back above level),\n"
      "  thesis_lean_deg (her trunk's world lean, pelvis to neck, as the channels pose it: balance 0),\n"
      "  the stage's terms channel_lean_deg, support_lean_deg, inertia_lean_deg, then lean_deg (measured on\n"
      "  the posed joints), turn_deg, seat_lift_cm and limited (1: a body limit held her). Leans are + toward\n"
      "  the horse's head. Sideways: turn_tilt_deg (in a turn, the tilt of the apparent vertical her roll\n"
      "  channels answer, balance.turn_share of atan(a/g)), roll_deg (the horse's hip line) and side_lean_deg\n"
      "  (her trunk from the world's vertical, pelvis to neck), + toward the horse's right. The scene's profile\n"
      "  applies, then --set.\n"
      "A crowd scene (docs/crowds.md): a first column `pair` (its index from 0), one row a frame and pair,\n"
      "  each pair with its own profile (then --set).\n"
      "Example: stirrup rig balance scenes/rear.json --set balance.max_fold_deg=60 -o rear_balance.csv");
  balance->add_option("scene", opts->scene, "Scene file")->required();
  balance->add_option("--out,-o", opts->rider_csv, "CSV file (default: standard output)");
  balance->add_option("--set,-s", opts->sets, "Override one profile parameter, KEY=NUMBER (repeatable)");
  balance->add_flag("--allow-impossible", opts->allow_impossible,
                    "Read a scene beyond a horse's limits (docs/horse-limits.md) anyway, warning on stderr for each frame");
  balance->callback([opts] { runBalance(*opts); });

  CLI::App* params = rig_cmd->add_subcommand("params", "List a rig profile's parameters, values and citations");
  addProfileOptions(params, opts);
  params->callback([opts] { runParams(*opts); });
}

}  // namespace stirrup::cli
