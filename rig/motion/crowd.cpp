#include "rig/motion/crowd.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <tuple>

#include "rig/characters/palette.h"
#include "rig/characters/proportions.h"
#include "rig/error.h"
#include "rig/motion/ground_path.h"
#include "rig/parallel_first_error.h"
#include "rig/units.h"

namespace stirrup::rig {
namespace {


// Decorrelates the crowd's seed and a pair's index into the seed of the pair's own generator
// (splitmix64: Steele, Lea and Flood 2014, "Fast splittable pseudorandom number generators", OOPSLA).
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Numbers from raw 64-bit draws, the same on every standard library.
struct Draws {
  std::mt19937_64 engine;
  double unit() { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }  // [0, 1), 53 bits
  double between(const ProportionRange& r) { return r.lo + (r.hi - r.lo) * unit(); }
  double symmetric() { return 2.0 * unit() - 1.0; }  // [-1, 1)
};

std::string allowedRangeText(const ProportionRange& r) { return numberText(r.lo) + " to " + numberText(r.hi); }

// The lead path as the pairs see it: continued straight along its end tangents beyond either end.
struct LeadPath {
  GroundPath path;
  GroundPath::Sample at(double s) const {
    GroundPath::Sample a = path.at(std::clamp(s, 0.0, path.length()));
    if (s < 0.0 || s > path.length()) {
      a.position += a.tangent * (s - std::clamp(s, 0.0, path.length()));
      a.curvature = 0.0;
    }
    return a;
  }
};

// What the spacing rule needs of the lead path, sampled every kMeasureStepCm.
constexpr double kMeasureStepCm = 10.0;
struct LeadMeasure {
  double length = 0, max_curvature = 0;
  double max_turn_rad = 0;   // the largest heading change from the start, either way
  double total_turn_rad = 0; // the heading's changes, all counted as positive
};
LeadMeasure measure(const GroundPath& p) {
  LeadMeasure m;
  m.length = p.length();
  double prev = p.at(0.0).heading_deg, turned = 0.0;
  for (double s = 0.0;; s = std::min(s + kMeasureStepCm, m.length)) {
    const GroundPath::Sample a = p.at(s);
    const double d = std::remainder(a.heading_deg - prev, 360.0) * std::numbers::pi / 180.0;
    prev = a.heading_deg;
    turned += d;
    m.total_turn_rad += std::abs(d);
    m.max_turn_rad = std::max(m.max_turn_rad, std::abs(turned));
    m.max_curvature = std::max(m.max_curvature, std::abs(a.curvature));
    if (s >= m.length) break;
  }
  return m;
}

// The files' offsets from the lead, + to its right: centred on it.
double fileOffset(const Formation& f, int file) { return (file - 0.5 * (f.files - 1)) * f.file_spacing_cm; }
double halfWidth(const Formation& f) { return 0.5 * (f.files - 1) * f.file_spacing_cm + f.jitter_cm; }

void checkSpec(const CrowdSpec& s, const std::string& source) {
  const std::string at = source + ": crowd.";
  if (s.pairs < 1 || s.pairs > kMaxCrowdPairs)
    throw InputError(at + "pairs: expected a whole number from 1 to " + std::to_string(kMaxCrowdPairs) + ", got " +
                     std::to_string(s.pairs));
  const Formation& f = s.formation;
  if (f.files < 1 || f.files > s.pairs)
    throw InputError(at + "formation.files: expected a whole number from 1 to the pairs (" + std::to_string(s.pairs) +
                     "), got " + std::to_string(f.files));
  for (const auto& [key, v] : {std::pair{"formation.file_spacing_cm", f.file_spacing_cm},
                               std::pair{"formation.rank_spacing_cm", f.rank_spacing_cm},
                               std::pair{"formation.jitter_cm", f.jitter_cm}})
    if (!(v >= 0.0 && v <= 1e5)) throw InputError(at + key + ": expected centimetres from 0 to 100000, got " + numberText(v));
  if (!(s.speed_variation >= 0.0 && s.speed_variation <= kMaxSpeedVariation))
    throw InputError(at + "speed_variation: expected a fraction from 0 to " + numberText(kMaxSpeedVariation) + ", got " +
                     numberText(s.speed_variation));
  if (!(s.start_offset_max_s >= 0.0 && s.start_offset_max_s <= kMaxStartOffsetS))
    throw InputError(at + "start_offset_max_s: expected seconds from 0 to " + numberText(kMaxStartOffsetS) + ", got " +
                     numberText(s.start_offset_max_s));
  if (!(s.gait_variation >= 0.0 && s.gait_variation <= 1.0))
    throw InputError(at + "gait_variation: expected a fraction from 0 to 1, got " + numberText(s.gait_variation));
  double total = 0.0;
  for (const auto& [name, weight] : s.profile_mix) {
    const auto& known = crowdProfiles();
    if (std::find(known.begin(), known.end(), name) == known.end())
      throw InputError(at + "profiles." + name + ": expected one of thesis, english, novice");
    // Weights are relative: up to a million keeps their sum finite whatever the mix.
    if (!(weight >= 0.0 && weight <= 1e6))
      throw InputError(at + "profiles." + name + ": expected a weight from 0 to 1e+06, got " + numberText(weight));
    total += weight;
  }
  if (!(total > 0.0)) throw InputError(at + "profiles: expected at least one profile with a weight > 0");
  for (const auto& [key, r, allowed, unit] :
       {std::tuple{"withers_height_cm", s.withers_height_cm, kWithersHeightRangeCm, " cm"},
        std::tuple{"rider_height_cm", s.rider_height_cm, kRiderHeightRangeCm, " cm"},
        std::tuple{"rider_build", s.rider_build, kRiderBuildRange, ""}})
    if (!(r.lo <= r.hi && allowed.contains(r.lo) && allowed.contains(r.hi)))
      throw InputError(at + key + ": expected a range [low, high] within " + allowedRangeText(allowed) + unit + ", got [" +
                       numberText(r.lo) + ", " + numberText(r.hi) + "]");
}

// The crowd's "characters" entries onto the pairs they name: each pair by one entry at most.
void applyCharacters(const CrowdSpec& spec, std::vector<PairSpec>& pairs, const std::string& at) {
  std::vector<int> named_by(pairs.size(), -1);
  for (std::size_t e = 0; e < spec.characters.size(); ++e) {
    const CrowdSpec::Characters& c = spec.characters[e];
    const std::string field = at + "characters[" + std::to_string(e) + "].";
    std::vector<int> which = c.pairs;
    if (which.empty())
      for (int i = 0; i < int(pairs.size()); ++i) which.push_back(i);
    for (const int i : which) {
      if (i < 0 || i >= int(pairs.size()))
        throw InputError(field + "pairs: expected pair indices from 0 to " + std::to_string(pairs.size() - 1) + ", got " + std::to_string(i));
      if (named_by[std::size_t(i)] >= 0)
        throw InputError(field + "pairs: pair " + std::to_string(i) + " is named by characters[" + std::to_string(named_by[std::size_t(i)]) +
                         "] too (expected each pair in one entry at most)");
      named_by[std::size_t(i)] = int(e);
      PairSpec& p = pairs[std::size_t(i)];
      p.horse_file = c.horse_file, p.horse_mapping = c.horse_mapping;
      p.rider_file = c.rider_file, p.rider_mapping = c.rider_mapping;
      p.animation = c.animation;
    }
  }
}

// The largest pair the spec's ranges allow.
PairExtent largestExtent(const CrowdSpec& s) {
  return pairExtent(scaledHorse(s.withers_height_cm.hi, s.rider_height_cm.hi),
                    scaledRider(s.rider_height_cm.hi, s.rider_build.hi));
}

PathClipParams leadParams(const CrowdSpec& s) {
  PathClipParams p;
  p.points = s.lead_points;
  p.speed = s.lead_speed;
  p.max_duration_s = kMaxCrowdSeconds;
  return p;
}

}  // namespace

const std::vector<std::string>& crowdProfiles() {
  static const std::vector<std::string> names = {"thesis", "english", "novice"};
  return names;
}

HorseParams PairSpec::horse() const {
  HorseParams h = scaledHorse(withers_height_cm, rider_height_cm);
  applyHorseCoat(coat, h);
  return h;
}
RiderParams PairSpec::rider() const {
  RiderParams r = scaledRider(rider_height_cm, rider_build);
  applyRiderColors(jacket, hair, skin, r);
  return r;
}

std::unique_ptr<PathClip> makePairClip(const PairSpec& pair, std::shared_ptr<const Terrain> terrain,
                                       const std::string& source) {
  PathClipParams p = pair.path;
  p.hoof_rest = pairSpecExtent(pair).hoof_rest;
  return std::make_unique<PathClip>(std::move(p), std::move(terrain), source);
}

std::shared_ptr<const Clip> pairClip(const PairSpec& pair, std::shared_ptr<const Terrain> terrain, const std::string& source) {
  if (pair.characters && pair.characters->own_clip) return pair.characters->own_clip;
  return makePairClip(pair, std::move(terrain), source);
}

PairExtent pairSpecExtent(const PairSpec& pair) {
  if (pair.characters) return pair.characters->extent;
  if (pair.ownCharacters())
    throw std::logic_error("pairSpecExtent: a pair naming its own characters, not resolved by the scene (scene/crowd_characters.h)");
  return pairExtent(pair.horse(), pair.rider());
}

int crowdFrames(const CrowdSpec& spec, std::shared_ptr<const Terrain> terrain, double fps, const std::string& source) {
  const PathClip lead(leadParams(spec), std::move(terrain), source + ": crowd.lead");
  return static_cast<int>(std::floor(lead.duration() * fps + 1e-9)) + 1;
}

Spacing minimumSpacing(const CrowdSpec& spec, const std::string& source) {
  const LeadPath lead{GroundPath(spec.lead_points, source + ": crowd.lead")};
  const LeadMeasure m = measure(lead.path);
  const PairExtent e = largestExtent(spec);
  // The largest pair on the lead path, at the fastest pair's speeds: how far its footprint reaches
  // ahead, behind and to either side of its travel frame over the whole ride, rolling into turns.
  PathClipParams fast = leadParams(spec);
  for (auto& k : fast.speed) k.speed *= 1.0 + spec.speed_variation;
  fast.hoof_rest = e.hoof_rest;
  fast.variation = spec.gait_variation;
  const PathClip clip(fast, nullptr, source + ": crowd.lead");
  double ahead = 0, behind = 0, left = 0, right = 0, roll_deg = 0;
  for (double t = 0.0; t <= clip.duration(); t += 1.0 / 48.0) {
    const HorseFrame f = clip.sample(t);
    const GroundRect g = pairFootprint(e, f);
    const glm::dvec2 d = g.center - glm::dvec2{f.travel_cm, f.travel_z_cm};
    const double along = glm::dot(d, g.axis), across = glm::dot(d, glm::dvec2{-g.axis.y, g.axis.x});
    ahead = std::max(ahead, along + g.half_length), behind = std::max(behind, g.half_length - along);
    right = std::max(right, across + g.half_width), left = std::max(left, g.half_width - across);
    roll_deg = std::max(roll_deg, std::abs(clip.turnRollDeg(t)));
  }
  // A file inside the lead turns tighter (κ / (1 − κ ℓ)) and may roll more than the lead did: the
  // crown moves out by the difference of the sines.
  const double k_in = m.max_curvature / std::max(1e-9, 1.0 - m.max_curvature * halfWidth(spec.formation));
  double v_max = 0;
  for (const auto& k : fast.speed) v_max = std::max(v_max, k.speed);
  const double roll_in = std::min(PathClipParams{}.roll_limit_deg, std::atan(v_max * v_max * k_in / kStandardGravityCmS2) * 180.0 / std::numbers::pi);
  const double more_roll = e.top_cm * std::max(0.0, std::sin(roll_in * std::numbers::pi / 180.0) -
                                                        std::sin(roll_deg * std::numbers::pi / 180.0));
  const double reach = std::max(ahead, behind);
  const double j = spec.formation.jitter_cm;
  Spacing s;
  // Files: both footprints' widths, the two jitters, the rectangle's ends leaving the curve in a turn
  // (κ a² / 2 on each of the two), and the clearance.
  s.file_cm = left + right + more_roll + 2.0 * j + k_in * reach * reach + kFormationClearanceCm;
  // Ranks: the footprint's length, the two jitters, the fastest and slowest pairs drawing apart over the
  // lead's length, the shear of two files jittered apart through the turns (Δℓ · Δheading), the turn
  // between two ranks (κ · spacing) swinging the near corners of their footprints along by up to the
  // width times that, and the clearance.
  s.rank_cm = ahead + behind + 2.0 * j + 2.0 * spec.speed_variation * m.length + 2.0 * j * m.max_turn_rad +
              (left + right) * k_in * spec.formation.rank_spacing_cm + kFormationClearanceCm;
  return s;
}

std::vector<PairSpec> generateCrowd(const CrowdSpec& spec, std::shared_ptr<const Terrain> terrain, double fps,
                                    const std::string& source, PairClips* clips, const PairResolver& resolve) {
  checkSpec(spec, source);
  const std::string at = source + ": crowd.";
  // The lead's own clip checks its points and speeds first, so their errors name crowd.lead.
  const int frames = crowdFrames(spec, terrain, fps, source);
  const LeadPath lead{GroundPath(spec.lead_points, source + ": crowd.lead")};
  const LeadMeasure m = measure(lead.path);
  const Formation& f = spec.formation;
  const double half_width = halfWidth(f);
  if (m.max_curvature * half_width > 1.0 - kMinInsideRadiusFraction)
    throw InputError(at + "formation: expected a formation at most " +
                     numberText(std::floor((1.0 - kMinInsideRadiusFraction) / m.max_curvature)) +
                     " cm to either side of the lead (half the lead path's tightest radius), got " + numberText(half_width));
  const Spacing need = minimumSpacing(spec, source);
  if (f.files > 1 && f.file_spacing_cm < need.file_cm)
    throw InputError(at + "formation.file_spacing_cm: expected at least " + numberText(std::ceil(need.file_cm)) +
                     " cm (the widest pair's footprint in the lead's hardest turn, and the jitter), got " +
                     numberText(f.file_spacing_cm));
  if (spec.pairs > f.files && f.rank_spacing_cm < need.rank_cm)
    throw InputError(at + "formation.rank_spacing_cm: expected at least " + numberText(std::ceil(need.rank_cm)) +
                     " cm (the longest pair's footprint, the jitter, the speed variation's drift and the turns), got " +
                     numberText(f.rank_spacing_cm));

  double total_weight = 0.0;
  for (const auto& pw : spec.profile_mix)
    if (pw.second > 0.0) total_weight += pw.second;
  const double first_speed = spec.lead_speed.front().speed;
  std::vector<PairSpec> pairs;
  for (int i = 0; i < spec.pairs; ++i) {
    // Pair i's own generator: its values do not depend on how many pairs follow it. The draws are
    // taken in this order, always all of them.
    Draws d{std::mt19937_64(splitmix64(spec.seed ^ splitmix64(static_cast<std::uint64_t>(i))))};
    const double along_jitter = f.jitter_cm * d.symmetric();
    const double across_jitter = f.jitter_cm * d.symmetric();
    const double speed_factor = 1.0 + spec.speed_variation * d.symmetric();
    const double offset_s = spec.start_offset_max_s * d.unit();
    const double pick = total_weight * d.unit();
    const double withers = d.between(spec.withers_height_cm);
    const double rider_height = d.between(spec.rider_height_cm);
    const double build = d.between(spec.rider_build);
    const auto clip_seed = static_cast<unsigned>(d.engine() & 0x7FFFFFFFu);
    // Colours last, so the draws above are what they were before pairs had colours.
    const auto pickName = [&d](const auto& list) { return std::string(list[d.engine() % list.size()].name); };
    const std::string coat = pickName(horseCoats()), jacket = pickName(riderJackets());
    const std::string hair = pickName(riderHair()), skin = pickName(riderSkins());

    PairSpec p;
    p.clip_offset_s = offset_s;
    p.withers_height_cm = withers;
    p.rider_height_cm = rider_height;
    p.rider_build = build;
    p.coat = coat, p.jacket = jacket, p.hair = hair, p.skin = skin;
    // The first profile whose share of the total the pick falls in (a weight of 0 is never picked).
    double cumulative = 0.0;
    for (const auto& [name, weight] : spec.profile_mix) {
      if (!(weight > 0.0)) continue;
      cumulative += weight;
      p.profile = name;
      if (pick < cumulative) break;
    }
    // Its slot: the file across (+ right of the lead), the rank behind; then the jitter.
    const int rank = i / f.files, file = i % f.files;
    const double across = fileOffset(f, file) + across_jitter;
    const double behind = -rank * f.rank_spacing_cm + along_jitter;
    // Its path starts farther back by what it rides before its phase's time, and runs on past where
    // the lead ends by what a faster pair and an outside file ride more, so it never runs out.
    const double start = behind - speed_factor * first_speed * offset_s;
    const double end = behind + speed_factor * m.length + std::abs(across) * m.total_turn_rad + kPairPathStepCm * 5.0;
    const int steps = std::min(kMaxPairPathPoints - 1, static_cast<int>(std::ceil((end - start) / kPairPathStepCm)));
    for (int k = 0; k <= steps; ++k) {
      const GroundPath::Sample a = lead.at(start + (end - start) * k / steps);
      p.path.points.push_back(a.position + glm::dvec2{-a.tangent.y, a.tangent.x} * across);
    }
    for (const SpeedProfile::Key& key : spec.lead_speed) p.path.speed.push_back({key.at + offset_s, key.speed * speed_factor});
    p.path.over = SpeedProfile::Over::Time;
    p.path.variation = spec.gait_variation;
    p.path.seed = clip_seed;
    // Where it stands at the shot's start, facing the lead's way there.
    const GroundPath::Sample slot = lead.at(behind);
    p.slot_cm = slot.position + glm::dvec2{-slot.tangent.y, slot.tangent.x} * across;
    p.slot_heading_deg = slot.heading_deg;
    pairs.push_back(std::move(p));
  }
  applyCharacters(spec, pairs, at);
  if (resolve) resolve(pairs);
  PairClips made = validatePairs(pairs, std::move(terrain), fps, frames, source, "crowd");
  if (clips) *clips = std::move(made);
  return pairs;
}

PairClips validatePairs(const std::vector<PairSpec>& pairs, std::shared_ptr<const Terrain> terrain, double fps, int frames,
                        const std::string& source, const std::string& field) {
  if (pairs.empty() || pairs.size() > static_cast<std::size_t>(kMaxCrowdPairs))
    throw InputError(source + ": " + field + ": expected 1 to " + std::to_string(kMaxCrowdPairs) + " pairs, got " +
                     std::to_string(pairs.size()));
  PairClips clips(pairs.size());
  std::vector<const Clip*> views(pairs.size());
  std::vector<double> offsets(pairs.size());
  std::vector<PairExtent> extents(pairs.size());
  parallelForFirstError(pairs.size(), [&](std::size_t i) {
    const PairSpec& p = pairs[i];
    const std::string at = source + ": " + field + "[" + std::to_string(i) + "].";
    for (const auto& [key, v, allowed, unit] :
         {std::tuple{"withers_height_cm", p.withers_height_cm, kWithersHeightRangeCm, " cm"},
          std::tuple{"rider_height_cm", p.rider_height_cm, kRiderHeightRangeCm, " cm"},
          std::tuple{"rider_build", p.rider_build, kRiderBuildRange, ""}})
      if (!allowed.contains(v))
        throw InputError(at + key + ": expected " + allowedRangeText(allowed) + unit + ", got " + numberText(v));
    if (!findHorseCoat(p.coat))
      throw InputError(at + "coat: expected one of " + paletteNames(horseCoats()) + ", got \"" + p.coat + "\"");
    for (const auto& [key, name, list] : {std::tuple{"jacket", &p.jacket, &riderJackets()},
                                          std::tuple{"hair", &p.hair, &riderHair()}, std::tuple{"skin", &p.skin, &riderSkins()}})
      if (!findNamedColor(*list, *name))
        throw InputError(at + key + ": expected one of " + paletteNames(*list) + ", got \"" + *name + "\"");
    const auto& known = crowdProfiles();
    if (std::find(known.begin(), known.end(), p.profile) == known.end())
      throw InputError(at + "profile: expected one of thesis, english, novice, got \"" + p.profile + "\"");
    if (!(p.clip_offset_s >= 0.0 && p.clip_offset_s <= kMaxStartOffsetS))
      throw InputError(at + "start_offset_s: expected seconds from 0 to " + numberText(kMaxStartOffsetS) + ", got " +
                       numberText(p.clip_offset_s));
    clips[i] = pairClip(p, terrain, source + ": " + field + "[" + std::to_string(i) + "]");
    views[i] = clips[i].get();
    offsets[i] = p.clip_offset_s;
    extents[i] = pairSpecExtent(p);
  });
  if (frames <= 0) {
    // While any pair still rides.
    double end_s = 0.0;
    for (std::size_t i = 0; i < clips.size(); ++i) {
      const double ride_s = clips[i]->duration() - offsets[i];
      if (ride_s > kMaxCrowdSeconds)
        throw InputError(source + ": " + field + "[" + std::to_string(i) + "].speed: expected a ride of at most " +
                         numberText(kMaxCrowdSeconds) + " s, got " + numberText(ride_s) + " s");
      end_s = std::max(end_s, ride_s);
    }
    frames = static_cast<int>(std::floor(end_s * fps + 1e-9)) + 1;
  }
  if (const auto o = firstOverlap(views, offsets, extents, fps, frames)) {
    const std::string when = " overlap at frame " + std::to_string(o->frame) + " (" + numberText(o->seconds) + " s): ";
    // A generated crowd names its pairs by number and the formation as the fix; a list, its entries.
    if (field == "crowd")
      throw InputError(source + ": crowd.formation: pairs " + std::to_string(o->a) + " and " + std::to_string(o->b) + when +
                       "expected a formation that keeps every two horses apart at every frame (wider spacing, less "
                       "jitter or speed variation)");
    throw InputError(source + ": " + field + ": " + field + "[" + std::to_string(o->a) + "] and " + field + "[" +
                     std::to_string(o->b) + "]" + when + "expected paths that keep every two horses apart at every frame");
  }
  return clips;
}

}  // namespace stirrup::rig
