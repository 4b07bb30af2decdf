// A crowd of horse-and-rider pairs (issue 19): each pair rides its own path at its own speed and
// stride phase, with its own rig profile, seed and proportions, so that no two riders move alike.
//
// A crowd is given either pair by pair (PairSpec, a scene's "riders" list) or as a CrowdSpec (a
// scene's "crowd" block) that generateCrowd turns into PairSpecs: N pairs in a formation of ranks
// behind a lead path. Generation is a pure function of the spec: each pair draws its values from its
// own std::mt19937_64 (whose output the C++ standard fixes), seeded from the crowd's seed and the
// pair's index, and turns raw 64-bit draws into numbers itself (the standard distributions are not the
// same on every standard library), so the same spec gives the same crowd everywhere, and pair i is the
// same in a crowd of 10 and of 100 (of the same files).
//
// Each generated pair's path is the lead path offset sideways along its normal by the pair's file in
// the formation and its jitter, and started behind the lead by its rank and jitter (the lead is
// continued straight beyond its ends for this); its speed keys are the lead's scaled by its speed
// factor. Its start phase is a time offset into its own clip, with the path begun farther back by
// the distance covered in that time, so the phase moves its stride, not its place in the formation.
//
// validatePairs (called by generateCrowd, and by scenes on an explicit list) rejects proportions out
// of range, unknown profiles, and any two pairs whose footprints (rig/motion/pair_footprint.h) meet at
// any frame: one line naming the source, the two pairs and the frame.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "rig/character.h"
#include "rig/characters/horse_character.h"
#include "rig/characters/seating.h"
#include "rig/characters/rider_character.h"
#include "rig/motion/pair_footprint.h"
#include "rig/motion/path_clip.h"
#include "rig/motion/terrain.h"

namespace stirrup::rig {

// At most this many pairs: our choice, twice the largest crowd issue 19 benchmarks (100 pairs), whose
// renderer work (instancing, levels of detail) is what bounds a crowd, and is still to come.
inline constexpr int kMaxCrowdPairs = 200;
// A generated crowd's lead rides its path in at most this long (s): our choice, a shot and not a film.
// A crowd is checked at every frame when its scene loads, about a millisecond a pair and second of
// clip, so this and kMaxCrowdPairs keep a scene's load under half a minute. An explicit list's rides
// are held to it too.
inline constexpr double kMaxCrowdSeconds = 120.0;
// A generated pair's path holds at most this many points: a very long lead is sampled more coarsely
// (its length over this), so a pair's path table stays small (rig/motion/ground_path.h).
inline constexpr int kMaxPairPathPoints = 500;

struct ProportionRange {
  double lo = 0, hi = 0;
  bool contains(double v) const { return v >= lo && v <= hi; }  // false for NaN
};
// The proportions a pair may have. Heights: issue 19 ("horses of 145-175 cm at the withers, riders of
// 150-190 cm"). Build (rig/characters/proportions.h: it multiplies the rider's girths): our choice, a
// slim to a stout rider (the footprint test builds and rides both ends).
inline constexpr ProportionRange kWithersHeightRangeCm{145.0, 175.0};
inline constexpr ProportionRange kRiderHeightRangeCm{150.0, 190.0};
inline constexpr ProportionRange kRiderBuildRange{0.85, 1.25};

// The rig profiles a pair may ride with (scenes/profiles/).
const std::vector<std::string>& crowdProfiles();

// A pair's own characters (issue 60: a troop of the user's horse), resolved by the scene before the
// pairs are checked (scene/crowd_characters.h): each pair's horse and rider seated as a single pair's
// are, the box they take at rest, and, where the pair plays its horse's own animation, that animation
// placed at the pair's slot.
struct PairCharacters {
  std::shared_ptr<const Character> horse, rider;  // at rest, the rider seated on this horse
  SeatReport seat;
  PairExtent extent;                               // pairExtent(horse, rider)
  std::shared_ptr<const Clip> own_clip;            // the horse's own animation, placed; null: a gait along the path
};

struct PairSpec {
  PathClipParams path;          // its own path, speed keys, clip variation and seed
  double clip_offset_s = 0;     // its clip is sampled at the shot's time plus this (its start phase)
  std::string profile = "thesis";
  double withers_height_cm = 160, rider_height_cm = 170, rider_build = 1;
  // Colours by name (rig/characters/palette.h); the defaults are the default characters' own.
  std::string coat = "bay";                          // the horse's coat and points
  std::string jacket = "red", hair = "brown", skin = "light";  // the rider's
  // The user's characters (issue 60): "default" (generated at the proportions and colours above) or a
  // glTF file (the scene's folder resolved), with a mapping file or none (the file's role table, else
  // the automatic mapping), as a scene's "characters" names them.
  std::string horse_file = "default", horse_mapping, rider_file = "default", rider_mapping;
  // With a horse file: its own animation by name (empty: its first), played from the pair's slot
  // instead of a gait along the path.
  std::optional<std::string> animation;
  // Where the pair stands at the shot's start and the way it faces: its slot in the formation (a
  // generated crowd), or the start of its path (a list). An own animation is placed there.
  glm::dvec2 slot_cm{0.0};
  double slot_heading_deg = 0.0;
  // Resolved by the scene (scene/crowd_characters.h) when a file is named; null: generated characters.
  std::shared_ptr<const PairCharacters> characters;
  bool ownCharacters() const { return horse_file != "default" || rider_file != "default"; }

  HorseParams horse() const;    // scaledHorse (rig/characters/proportions.h), at these proportions and coat
  RiderParams rider() const;    // scaledRider, in these colours
};

struct Formation {
  int files = 1;                 // pairs side by side in a rank (columns)
  double file_spacing_cm = 250;  // between neighbouring files' paths, across the lead's heading
  double rank_spacing_cm = 600;  // between neighbouring ranks, along it
  double jitter_cm = 0;          // each pair moved by up to this, along and across, from its slot
};

struct CrowdSpec {
  int pairs = 1;
  std::vector<glm::dvec2> lead_points;           // the front rank's middle rides this (cm, world x and z)
  std::vector<SpeedProfile::Key> lead_speed;     // over time (s, cm/s)
  Formation formation;
  double speed_variation = 0;    // each pair's speeds × (1 + u), u uniform in [-this, +this]; at most kMaxSpeedVariation
  double start_offset_max_s = 0; // each pair's clip_offset_s uniform in [0, this]; at most kMaxStartOffsetS
  std::vector<std::pair<std::string, double>> profile_mix = {{"thesis", 1.0}};  // name, weight
  ProportionRange withers_height_cm = kWithersHeightRangeCm;
  ProportionRange rider_height_cm = kRiderHeightRangeCm;
  ProportionRange rider_build = kRiderBuildRange;
  double gait_variation = 0.1;   // each pair's clip variation (PathClipParams::variation)
  // Each generated pair's coat, jacket, hair and skin are drawn uniformly from the palette's names
  // (rig/characters/palette.h).
  std::uint64_t seed = 1;
  // The user's characters for some pairs (issue 60): each entry names its pairs (pair indices, as a
  // frame list: "0-3", "0-29x2") and the horse and rider files they ride (PairSpec::horse_file ...) and
  // whether they play the horse's own animation. A pair is named by one entry at most.
  struct Characters {
    std::vector<int> pairs;  // empty: every pair
    std::string horse_file = "default", horse_mapping, rider_file = "default", rider_mapping;
    std::optional<std::string> animation;
  };
  std::vector<Characters> characters;
};

// Limits of the variations (our choices): 10% covers a troop's spread of cruising speeds (a 900 cm/s
// gallop ± 90); a start phase of up to 2 s covers a whole stride at every gait (the walk's is the
// slowest, about 1.05 s: rig/motion/procedural_gait.cpp) with room for the pairs to be out of step.
inline constexpr double kMaxSpeedVariation = 0.1;
inline constexpr double kMaxStartOffsetS = 2.0;
// A generated pair's path is sampled from the offset lead this often (cm) and joined by the ground
// path's curve (rig/motion/ground_path.h): at 100 cm the curve is within a millimetre of the offset
// (tests/rig/motion/crowd_test.cpp). Longer leads are sampled more coarsely (kMaxPairPathPoints).
inline constexpr double kPairPathStepCm = 100.0;
// The inside of the formation's tightest turn keeps at least this fraction of the lead's radius, so
// an inside file's path never folds on itself (an offset curve has a cusp where the offset reaches
// the radius).
inline constexpr double kMinInsideRadiusFraction = 0.5;
// Clearance the spacing rule (minimumSpacing) keeps between two pairs' footprints: our choice.
inline constexpr double kFormationClearanceCm = 20.0;

struct Spacing {
  double file_cm = 0, rank_cm = 0;
};
// The spacing a formation needs so that no two of its pairs meet, for the largest pair the spec's
// ranges allow: files apart by the footprint's width rolled into the lead's hardest turn, plus the jitter
// of both pairs; ranks by the footprint's length, the jitter, the distance the fastest and slowest
// pairs draw apart over the lead path, the shear of the jittered files through its turns, and the turn
// between two ranks.
// generateCrowd rejects a formation closer than this; its frame-by-frame check is the guarantee.
Spacing minimumSpacing(const CrowdSpec& spec, const std::string& source);

// Each pair's clip as validatePairs made it, in pair order: a scene keeps them, so that a shot does not
// make them again (a path clip scans its footfalls: some milliseconds a second of ride).
using PairClips = std::vector<std::shared_ptr<const Clip>>;
// Resolves the pairs' own characters before they are checked (the scene's: scene/crowd_characters.h).
using PairResolver = std::function<void(std::vector<PairSpec>&)>;

// The pairs of a crowd spec, checked (validatePairs). Errors are one-line InputErrors
// "SOURCE: crowd.FIELD: expected ..." (source e.g. "scenes/cavalry.json"). The shot runs for the
// lead's clip: crowdFrames(spec) frames at fps. `clips`, if given, receives validatePairs' clips.
// `resolve`, if given, is run on the generated pairs before they are checked (their own characters).
std::vector<PairSpec> generateCrowd(const CrowdSpec& spec, std::shared_ptr<const Terrain> terrain, double fps,
                                    const std::string& source, PairClips* clips = nullptr, const PairResolver& resolve = {});

// Frames a crowd's shot needs at fps: the lead path's clip, from frame 1 at t = 0 to its end.
int crowdFrames(const CrowdSpec& spec, std::shared_ptr<const Terrain> terrain, double fps, const std::string& source);

// Checks pairs given directly (FIELD e.g. "riders") or generated ("crowd"): count, proportions,
// profiles, their paths (PathClip's own checks), and that no two footprints meet at any of `frames`
// frames (frames <= 0: until the last pair's clip ends). Throws InputError "SOURCE: FIELD[i].KEY: expected ..." or "SOURCE: FIELD: pairs 3 and 7
// overlap at frame 41 (1.667 s): ...". The pairs are checked and their clips made in parallel; the error
// is the first bad pair's, whatever the threads.
PairClips validatePairs(const std::vector<PairSpec>& pairs, std::shared_ptr<const Terrain> terrain, double fps, int frames,
                   const std::string& source, const std::string& field);

// The pair's path clip over the terrain (null: flat), its hooves turned about its own horse's rest places
// (its own characters' horse where it has one).
std::unique_ptr<PathClip> makePairClip(const PairSpec& pair, std::shared_ptr<const Terrain> terrain,
                                       const std::string& source);
// What the pair plays: its horse's own animation where it has one (PairCharacters::own_clip), else its
// path clip.
std::shared_ptr<const Clip> pairClip(const PairSpec& pair, std::shared_ptr<const Terrain> terrain, const std::string& source);
// The box the pair takes: its own characters' where it has them, else its generated horse's and rider's.
PairExtent pairSpecExtent(const PairSpec& pair);

}  // namespace stirrup::rig
