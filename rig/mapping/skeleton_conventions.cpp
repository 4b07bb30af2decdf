#include "rig/mapping/skeleton_conventions.h"

#include <algorithm>
#include <cctype>
#include <string>

#include <glm/geometric.hpp>

#include "rig/mapping/skeleton_topology.h"

namespace stirrup::rig {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool isUpper(char c) { return std::isupper(static_cast<unsigned char>(c)) != 0; }
bool isLower(char c) { return std::islower(static_cast<unsigned char>(c)) != 0; }
bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// "mixamorig", "mixamorig1", "character", "character12": a word and any digits.
bool wordAndDigits(std::string_view token, std::string_view word) {
  if (token.size() < word.size() || lower(token.substr(0, word.size())) != word) return false;
  for (char c : token.substr(word.size()))
    if (!isDigit(c)) return false;
  return true;
}

// The rig roles a convention names, per side for the limbs ("Shoulder" is lShoulder and rShoulder),
// each with the normalised names (JointName::key) that may carry it, the first found winning.
struct Alias {
  const char* role;
  std::vector<const char*> keys;
};

struct Convention {
  const char* name;
  const char* needs_tool;     // every name must carry this tool's prefix (nullptr: any)
  const char* refuses_tool;   // names with this tool's prefix are another convention's
  std::vector<Alias> aliases;
};

// Sources: Mixamo's rig (any character auto-rigged at mixamo.com: the HumanIK names behind
// "mixamorig:"), Autodesk's HumanIK character definition (MotionBuilder's "Character1_" prefix), the
// UE4 / UE5 mannequin (SK_Mannequin; UE5 adds the metacarpals), Rigify's human meta-rig (Blender 3.x:
// DEF- deform bones, limbs in two halves, palm.01..04 the metacarpals), VRoid Studio's exports
// (J_Bip_ humanoid bones, J_Adj_ adjustment bones) and the VRM humanoid bone names. The grip (Hand) is
// a joint in the palm: a middle metacarpal, else the middle finger's base.
const std::vector<Convention>& conventions() {
  static const std::vector<Convention> table = {
      {"mixamo", "mixamo", nullptr,
       {{"pelvis", {"hips"}}, {"neck", {"neck"}}, {"head", {"head"}}, {"Shoulder", {"arm"}}, {"Elbow", {"forearm"}},
        {"Wrist", {"hand"}}, {"Hand", {"inhandmiddle", "handmiddle1"}}, {"Hip", {"upleg"}}, {"Knee", {"leg"}},
        {"Ankle", {"foot"}}, {"Ball", {"toebase"}}}},
      {"humanik", nullptr, "mixamo",
       {{"pelvis", {"hips"}}, {"neck", {"neck"}}, {"head", {"head"}}, {"Shoulder", {"arm"}}, {"Elbow", {"forearm"}},
        {"Wrist", {"hand"}}, {"Hand", {"inhandmiddle", "handmiddle1"}}, {"Hip", {"upleg"}}, {"Knee", {"leg"}},
        {"Ankle", {"foot"}}, {"Ball", {"toebase"}}}},
      {"unreal", nullptr, nullptr,
       {{"pelvis", {"pelvis"}}, {"neck", {"neck01"}}, {"head", {"head"}}, {"Shoulder", {"upperarm"}}, {"Elbow", {"lowerarm"}},
        {"Wrist", {"hand"}}, {"Hand", {"middlemetacarpal", "middle01"}}, {"Hip", {"thigh"}}, {"Knee", {"calf"}},
        {"Ankle", {"foot"}}, {"Ball", {"ball"}}}},
      {"rigify", nullptr, nullptr,
       {{"pelvis", {"spine"}}, {"Shoulder", {"upperarm"}}, {"Elbow", {"forearm"}}, {"Wrist", {"hand"}},
        {"Hand", {"palm02", "fmiddle01"}}, {"Hip", {"thigh"}}, {"Knee", {"shin"}}, {"Ankle", {"foot"}}, {"Ball", {"toe"}}}},
      {"vrm", nullptr, nullptr,
       {{"pelvis", {"hips"}}, {"neck", {"neck"}}, {"head", {"head"}}, {"Shoulder", {"upperarm"}}, {"Elbow", {"lowerarm"}},
        {"Wrist", {"hand"}}, {"Hand", {"palm", "middleproximal", "middle1"}}, {"Hip", {"upperleg"}}, {"Knee", {"lowerleg"}},
        {"Ankle", {"foot"}}, {"Ball", {"toebase", "toes"}}}},
  };
  return table;
}

// VRM's humanoid bones for the rider roles (vrm-c/vrm-specification, VRMC_vrm-1.0/humanoid.md; VRM
// 0.x uses the same names). The grip: VRM has no metacarpals, so the middle finger's base.
const std::vector<std::pair<const char*, const char*>>& vrmBoneRoles() {
  static const std::vector<std::pair<const char*, const char*>> table = {
      {"pelvis", "hips"},           {"neck", "neck"},            {"head", "head"},
      {"lShoulder", "leftUpperArm"}, {"lElbow", "leftLowerArm"}, {"lWrist", "leftHand"},
      {"lHip", "leftUpperLeg"},     {"lKnee", "leftLowerLeg"},   {"lAnkle", "leftFoot"},   {"lBall", "leftToes"},
      {"rShoulder", "rightUpperArm"}, {"rElbow", "rightLowerArm"}, {"rWrist", "rightHand"},
      {"rHip", "rightUpperLeg"},    {"rKnee", "rightLowerLeg"},  {"rAnkle", "rightFoot"},  {"rBall", "rightToes"},
      {"lHand", "leftMiddleProximal"}, {"rHand", "rightMiddleProximal"}};
  return table;
}

bool isSpineNumber(const std::string& key) {
  if (key.size() <= 5 || key.rfind("spine", 0) != 0) return false;
  for (std::size_t i = 5; i < key.size(); ++i)
    if (!isDigit(key[i])) return false;
  return true;
}

void finishScore(NamedRoles& r, CharacterKind kind) {
  r.missing.clear();
  for (const std::string& role : requiredRoles(kind))
    if (!r.roles.count(role)) r.missing.push_back(role);
  r.score = static_cast<int>(r.roles.size());
}

NamedRoles byTable(const MappingSkeleton& s, const Convention& c, const std::vector<JointName>& names) {
  NamedRoles r;
  r.convention = c.name;
  const auto usable = [&](int j) {
    if (names[j].helper) return false;
    if (c.needs_tool && names[j].tool != c.needs_tool) return false;
    if (c.refuses_tool && names[j].tool == c.refuses_tool) return false;
    return true;
  };
  const auto lookup = [&](const std::vector<const char*>& keys, int side) {
    for (const char* key : keys)
      for (int j = 0; j < s.size(); ++j)
        if (usable(j) && names[j].key == key && names[j].side == side) return j;
    return -1;
  };
  for (const Alias& a : c.aliases) {
    const bool sided = isUpper(a.role[0]);
    for (int side : sided ? std::vector<int>{1, -1} : std::vector<int>{0}) {
      const int j = lookup(a.keys, side);
      if (j < 0) continue;
      const std::string role = sided ? std::string(side > 0 ? "l" : "r") + a.role : std::string(a.role);
      r.roles[role] = j;
      r.why[role] = "name";
    }
  }
  if (std::string_view(c.name) == "rigify" && r.roles.count("pelvis")) {
    // Rigify numbers the whole chain DEF-spine.001 .. up to the head, so the numbers do not say where
    // the neck starts: the head is the chain's last DEF-spine joint, the neck two joints below it (the
    // human meta-rig's neck is two bones, spine.004 and spine.005, under the head spine.006).
    const int pelvis = r.roles["pelvis"];
    int head = -1;
    for (int j = 0; j < s.size(); ++j)
      if (usable(j) && isSpineNumber(names[j].key) && names[j].side == 0 && s.above(pelvis, j) &&
          (head < 0 || s.depth[j] > s.depth[head]))
        head = j;
    if (head >= 0) {
      r.roles["head"] = head;
      r.why["head"] = "the last DEF-spine joint (Rigify's head)";
      const int p1 = s.parent[head], p2 = p1 >= 0 ? s.parent[p1] : -1;
      if (p2 >= 0 && s.above(pelvis, p2) && isSpineNumber(names[p2].key)) {
        r.roles["neck"] = p2;
        r.why["neck"] = "two joints below the head (Rigify's neck is two bones)";
      }
    }
  }
  return r;
}

// ---- Quadrupeds.

// A quadruped naming convention: which bone's head (its joint) plays each leg role, and the numbered
// chains of the back, neck and tail.
struct QuadrupedLegBone {
  const char* part;               // the role's part ("fUpper": lfUpper and rfUpper)
  std::vector<const char*> keys;  // the normalised names (JointName::key) that may carry it, the first found winning
};
struct QuadrupedNames {
  const char* convention;
  std::vector<QuadrupedLegBone> legs;
  std::vector<const char*> body_start;  // joints before the back's numbered chain (Biped's Pelvis)
  const char* body;                     // the back's chain: "spine001" ... or "spine", "spine1", ...
  const char* neck;
  const char* head;
  const char* tail;
  bool bare_is_first;                   // the chain's word alone is its first joint (Biped's "Spine", "Neck", "Tail")
};

// Blender's Rigify horse meta-rig (the add-on bundled with Blender 3.4, rigify/metarigs/Animals/horse.py;
// character-notes section 4): the fore leg's scapula (shoulder: its head the pivot), humerus
// (upper_arm), radius (forearm: its head the elbow), cannon (forefoot: the knee), pastern (f_toe: the
// fetlock) and f_hoof; the hind leg's femur (thigh: the hip joint), tibia (lower_leg: the stifle),
// cannon (hind_foot: the hock), pastern (r_toe: the fetlock) and r_hoof; the back spine.001 (over
// the croup, the tail's parent) .. spine.006 (the withers), the neck neck.001 .., the head, the tail
// tail.001 ... The generated rig's DEF- deform bones carry the same names.
const QuadrupedNames kRigifyHorse = {"rigify horse",
                                     {{"fPivot", {"shoulder"}}, {"fUpper", {"forearm"}}, {"fMiddle", {"forefoot"}},
                                      {"fFetlock", {"ftoe"}}, {"fHoof", {"fhoof"}}, {"bPivot", {"thigh"}},
                                      {"bUpper", {"lowerleg"}}, {"bMiddle", {"hindfoot"}}, {"bFetlock", {"rtoe"}},
                                      {"bHoof", {"rhoof"}}},
                                     {},
                                     "spine",
                                     "neck",
                                     "head",
                                     "tail",
                                     false};

// Autodesk 3ds Max's Biped (Character Studio) with four leg links, the Structure rollout's "horse
// link: an additional, lower leg bone suitable for animating quadrupeds" (3ds Max Help, Biped
// Structure rollout, "Leg Links"); its bones as MAXScript's biped.getNode lists them (3ds Max
// MAXScript Help, "Biped Node Hierarchy"): #lleg L Thigh, L Calf, L HorseLink, L Foot, toes L Toe0..;
// #larm L Clavicle, L UpperArm, L Forearm, L Hand, fingers L Finger0, L Finger01..; Pelvis, Spine,
// Spine1.., Neck, Neck1.., Head, Tail, Tail1.., each name after the biped's root name ("Bip01 L
// Thigh"). A horse built on it [E: the usual reading, the arms as fore legs]: the femur Thigh, tibia
// Calf (the stifle), cannon HorseLink (the hock), pastern Foot (the fetlock), hoof Toe0; the scapula
// Clavicle, humerus UpperArm, radius Forearm (the elbow), cannon Hand (the knee), pastern Finger0 (the
// fetlock), hoof Finger01 (or Finger0 itself when a finger has one link).
const QuadrupedNames kBipedHorse = {"3ds max biped",
                                    {{"fPivot", {"clavicle"}}, {"fUpper", {"forearm"}}, {"fMiddle", {"hand"}},
                                     {"fFetlock", {"finger0"}}, {"fHoof", {"finger01", "finger0"}}, {"bPivot", {"thigh"}},
                                     {"bUpper", {"calf"}}, {"bMiddle", {"horselink"}}, {"bFetlock", {"foot"}},
                                     {"bHoof", {"toe0"}}},
                                    {"pelvis"},
                                    "spine",
                                    "neck",
                                    "head",
                                    "tail",
                                    true};

// "spine004" with `word` "spine" -> 4; the word alone -> 0 where `bare` says so; else -1.
int numbered(const std::string& key, const std::string& word, bool bare) {
  if (key == word) return bare ? 0 : -1;
  if (key.size() <= word.size() || key.rfind(word, 0) != 0) return -1;
  for (std::size_t i = word.size(); i < key.size(); ++i)
    if (!isDigit(key[i])) return -1;
  return std::stoi(key.substr(word.size()));
}

// A quadruped's roles by one convention's names among the joints `usable` says (a form of it): legs
// by name (a split bone's first segment: its key has no ".001"); the trunk's roles by the rules the
// topology uses (horseTrunkRoles) on the numbered chains; the withers the back's joint nearest the
// scapulae's pivots (the fore Pivots).
template <typename Usable>
NamedRoles quadrupedByNames(const MappingSkeleton& s, const std::vector<JointName>& names, const QuadrupedNames& c,
                            const Usable& usable) {
  NamedRoles r;
  r.convention = c.convention;
  const auto byKey = [&](const std::string& key, int side) {
    for (int j = 0; j < s.size(); ++j)
      if (usable(j) && names[j].key == key && names[j].side == side) return j;
    return -1;
  };
  const auto chain = [&](const std::string& word) {
    std::vector<std::pair<int, int>> found;  // number, joint
    for (int j = 0; j < s.size(); ++j)
      if (const int k = numbered(names[j].key, word, c.bare_is_first); usable(j) && names[j].side == 0 && k >= 0) found.push_back({k, j});
    std::sort(found.begin(), found.end());
    std::vector<int> out;
    for (const auto& [k, j] : found) out.push_back(j);
    return out;
  };
  for (const QuadrupedLegBone& b : c.legs)
    for (const auto& [side, prefix] : {std::pair<int, const char*>{1, "l"}, {-1, "r"}})
      for (const char* key : b.keys)
        if (const int j = byKey(key, side); j >= 0) {
          r.roles[prefix + std::string(b.part)] = j;
          r.why[prefix + std::string(b.part)] = "name";
          break;
        }
  HorseChains h;
  for (const char* key : c.body_start)
    if (const int j = byKey(key, 0); j >= 0) h.body.push_back(j);
  for (int j : chain(c.body)) h.body.push_back(j);
  h.neck = chain(c.neck);
  h.tail = chain(c.tail);
  h.head = byKey(c.head, 0);
  const auto role = [&](const char* name) { return r.roles.count(name) ? r.roles.at(name) : -1; };
  h.hind_roots = {role("lbPivot"), role("rbPivot")};
  h.fore_roots = {role("lfPivot"), role("rfPivot")};
  horseTrunkRoles(s, h, std::string(c.convention) + " names", r.roles, r.why);
  for (const char* named : {"head", "neck1", "tail1"})
    if (r.roles.count(named)) r.why[named] = "name";
  if (h.fore_roots[0] >= 0 && h.fore_roots[1] >= 0 && !h.body.empty()) {
    const glm::dvec3 scapulae = 0.5 * (s.position[h.fore_roots[0]] + s.position[h.fore_roots[1]]);
    int withers = h.body.front();
    for (int j : h.body)
      if (glm::length(s.position[j] - scapulae) < glm::length(s.position[withers] - scapulae)) withers = j;
    r.roles["withers"] = withers;
    r.why["withers"] = std::string(c.convention) + " names: the back's joint nearest the scapulae's pivots";
  }
  return r;
}

// The horse conventions, each form: Rigify's generated deform bones (DEF-), its meta-rig's names (no
// prefix: an all-bones export's controls also have none, but never the leg and spine names), and
// Biped's names (after its root name).
std::vector<NamedRoles> quadrupedsByNames(const MappingSkeleton& s, const std::vector<JointName>& names) {
  const auto none = [&](int j) { return names[j].tool.empty(); };
  const auto deform = [&](int j) { return names[j].tool == "rigify" && !names[j].helper; };
  const auto biped = [&](int j) { return names[j].tool == "biped"; };
  std::vector<NamedRoles> out = {quadrupedByNames(s, names, kRigifyHorse, deform), quadrupedByNames(s, names, kRigifyHorse, none),
                                 quadrupedByNames(s, names, kBipedHorse, biped)};
  out[0].form = "deform bones";
  out[1].form = "metarig names";
  return out;
}

}  // namespace

JointName normalizeJointName(std::string_view raw) {
  JointName out;
  std::string s(raw);
  // A namespace ("mixamorig:", "rig|") goes; Mixamo's names its tool.
  if (const std::size_t cut = s.find_last_of(":|"); cut != std::string::npos) {
    if (wordAndDigits(s.substr(0, cut), "mixamorig")) out.tool = "mixamo";
    s = s.substr(cut + 1);
  }
  std::vector<std::string> tokens;
  std::string token;
  for (char c : s) {
    if (c == '.' || c == '_' || c == '-' || std::isspace(static_cast<unsigned char>(c))) {
      if (!token.empty()) tokens.push_back(token);
      token.clear();
    } else {
      token.push_back(c);
    }
  }
  if (!token.empty()) tokens.push_back(token);
  // Tool prefixes.
  if (!tokens.empty()) {
    const std::string t0 = lower(tokens[0]);
    if (wordAndDigits(tokens[0], "mixamorig")) {
      out.tool = "mixamo";
      tokens.erase(tokens.begin());
    } else if (wordAndDigits(tokens[0], "bip") && tokens[0].size() > 3 && tokens.size() > 1) {
      out.tool = "biped";  // 3ds Max Biped's root name, "Bip01 L Thigh"
      tokens.erase(tokens.begin());
    } else if (wordAndDigits(tokens[0], "character") && tokens.size() > 1) {
      out.tool = "humanik";
      tokens.erase(tokens.begin());
    } else if ((t0 == "def" || t0 == "org" || t0 == "mch") && tokens.size() > 1) {
      out.tool = "rigify";
      out.helper = t0 != "def";
      tokens.erase(tokens.begin());
    } else if (t0 == "j" && tokens.size() > 2) {
      const std::string t1 = lower(tokens[1]);
      if (t1 == "bip" || t1 == "adj" || t1 == "sec") {
        out.tool = "vroid";
        tokens.erase(tokens.begin(), tokens.begin() + 2);
        if (tokens.size() > 1 && lower(tokens[0]) == "c") tokens.erase(tokens.begin());  // VRoid's centre
      }
    }
  }
  // The side: a token of its own ("L", "r", "Left"), the last such (Rigify's horse has "r_toe.L", the
  // rear leg's toe on the left), or "Left"/"Right" starting or ending a camel-case word.
  const auto sideToken = [&](const std::string& t) {
    const std::string tl = lower(t);
    return tokens.size() > 1 && (tl == "l" || tl == "left" || tl == "r" || tl == "right");
  };
  std::size_t side_at = tokens.size();
  for (std::size_t i = 0; i < tokens.size(); ++i)
    if (sideToken(tokens[i])) side_at = i;
  if (side_at < tokens.size()) out.side = lower(tokens[side_at])[0] == 'l' ? 1 : -1;
  std::vector<std::string> kept;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    if (i == side_at) continue;
    std::string word = tokens[i];
    for (const auto& [prefix, side] : {std::pair<std::string, int>{"left", 1}, {"right", -1}}) {
      if (word.size() > prefix.size() && lower(word.substr(0, prefix.size())) == prefix &&
          (isUpper(word[prefix.size()]) || isDigit(word[prefix.size()]))) {
        if (out.side == 0) out.side = side;
        word = word.substr(prefix.size());
        break;
      }
      if (word.size() > prefix.size() && lower(word.substr(word.size() - prefix.size())) == prefix &&
          isUpper(word[word.size() - prefix.size()]) && isLower(word[word.size() - prefix.size() - 1])) {
        if (out.side == 0) out.side = side;
        word = word.substr(0, word.size() - prefix.size());
        break;
      }
    }
    kept.push_back(word);
  }
  for (const std::string& t : kept) out.key += lower(t);
  return out;
}

int jointByKey(const MappingSkeleton& s, std::string_view key, int side) {
  for (int j = 0; j < s.size(); ++j) {
    const JointName n = normalizeJointName(s.names[j]);
    if (n.key == key && n.side == side) return j;
  }
  return -1;
}

std::vector<NamedRoles> rolesByNames(const MappingSkeleton& s, CharacterKind kind) {
  std::vector<NamedRoles> found;
  // stirrup's own role names, exactly.
  {
    NamedRoles r;
    r.convention = "stirrup";
    for (const std::vector<std::string>* roles : {&requiredRoles(kind), &optionalRoles(kind)})
      for (const std::string& role : *roles)
        if (const int j = s.find(role); j >= 0) {
          r.roles[role] = j;
          r.why[role] = "name";
        }
    finishScore(r, kind);
    if (r.score > 0) found.push_back(r);
  }
  std::vector<JointName> names;
  for (const std::string& n : s.names) names.push_back(normalizeJointName(n));
  if (kind == CharacterKind::Horse)
    for (NamedRoles& r : quadrupedsByNames(s, names)) {
      finishScore(r, kind);
      if (r.score > 0) found.push_back(r);
    }
  if (kind == CharacterKind::Rider) {
    // A VRM file's own table first: it is what the file says each bone is.
    if (!s.vrm_bones.empty()) {
      NamedRoles r;
      r.convention = "vrm";
      for (const auto& [role, bone] : vrmBoneRoles())
        if (const auto it = s.vrm_bones.find(bone); it != s.vrm_bones.end()) {
          r.roles[role] = it->second;
          r.why[role] = "VRM humanBones " + std::string(bone) + " (" + s.vrm_table + ")";
        }
      // A metacarpal by name is nearer the palm's middle than VRM's finger base.
      for (const auto& [role, side] : {std::pair<const char*, int>{"lHand", 1}, {"rHand", -1}})
        for (int j = 0; j < s.size(); ++j)
          if (names[j].key == "palm" && names[j].side == side) {
            r.roles[role] = j;
            r.why[role] = "name";
            break;
          }
      finishScore(r, kind);
      r.score += 100;  // the file's own word outranks any reading of its names
      found.push_back(r);
    }
    for (const Convention& c : conventions()) {
      NamedRoles r = byTable(s, c, names);
      finishScore(r, kind);
      if (r.score > 0) found.push_back(r);
    }
  }
  std::stable_sort(found.begin(), found.end(), [](const NamedRoles& a, const NamedRoles& b) { return a.score > b.score; });
  return found;
}

}  // namespace stirrup::rig
