#include "rig/mapping/auto_mapping.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <sstream>
#include <tuple>

#include <glm/geometric.hpp>

#include "rig/error.h"
#include "rig/mapping/skeleton_conventions.h"
#include "rig/mapping/skeleton_topology.h"

namespace stirrup::rig {
namespace {

struct Unit {
  const char* name;
  double cm;
};
// The units files come in: glTF's metres, the centimetres of Maya, FBX and Mixamo, millimetres, and the
// inches and feet of older tools.
constexpr std::array<Unit, 5> kUnits = {{{"metres", 100.0}, {"centimetres", 1.0}, {"millimetres", 0.1}, {"inches", 2.54}, {"feet", 30.48}}};

// A direction as the report writes it: "+Y", or its components.
std::string directionText(const glm::dvec3& v) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(std::abs(v[k]) - 1.0) < 1e-12) return std::string(v[k] > 0 ? "+" : "-") + "XYZ"[k];
  return "[" + fixedNumber(v.x, 3) + ", " + fixedNumber(v.y, 3) + ", " + fixedNumber(v.z, 3) + "]";
}

// The nearest file axis when within kAxisSnapDeg of `v`, else `v` itself (normalised).
glm::dvec3 snapped(const glm::dvec3& v, bool& snap) {
  const glm::dvec3 n = glm::normalize(v);
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(n[i]) > std::abs(n[k])) k = i;
  glm::dvec3 axis(0.0);
  axis[k] = n[k] > 0 ? 1.0 : -1.0;
  snap = std::abs(n[k]) >= std::cos(kAxisSnapDeg * std::numbers::pi / 180.0);
  return snap ? axis : n;
}

int roleJoint(const std::map<std::string, int>& roles, const std::string& role) {
  const auto it = roles.find(role);
  return it == roles.end() ? -1 : it->second;
}

// The optional roles the mapping looks for; the rest of the optional roles it leaves to the rig.
std::vector<std::string> lookedForOptional(CharacterKind kind) {
  if (kind == CharacterKind::Horse) return {"lfPivot", "rfPivot", "lbPivot", "rbPivot"};
  return {"upperChest", "lHand", "rHand", "lBall", "rBall"};
}

std::string joinList(const std::vector<std::string>& v, const char* sep = ", ") {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + v[i];
  return out;
}

std::string kindName(CharacterKind kind) { return std::string(characterKindName(kind)); }

// Sides: the group of roles whose "l" and "r" members change places together, and the role that says
// which side each is on.
struct SideGroup {
  std::vector<std::string> parts;
  std::string reference;
};

std::vector<SideGroup> sideGroups(CharacterKind kind) {
  if (kind == CharacterKind::Rider)
    return {{{"Shoulder", "Elbow", "Wrist", "Hand"}, "Shoulder"}, {{"Hip", "Knee", "Ankle", "Ball"}, "Hip"}};
  return {{{"fPivot", "fUpper", "fMiddle", "fFetlock", "fHoof"}, "fUpper"},
          {{"bPivot", "bUpper", "bMiddle", "bFetlock", "bHoof"}, "bUpper"},
          {{"Stirrup"}, "Stirrup"},
          {{"Rein"}, "Rein"}};
}

// A convention as the report names it: "mixamo", "rigify horse (deform bones)".
std::string conventionText(const NamedRoles& n) { return n.form.empty() ? n.convention : n.convention + " (" + n.form + ")"; }
std::string conventionText(const AutoMappingReport& r) { return r.method_form.empty() ? r.method : r.method + " (" + r.method_form + ")"; }

// How the roles were found, as the report's first line says it: "mixamo joint names", "rigify horse
// (deform bones)", "by topology (names ignored)".
std::string methodText(const AutoMappingReport& r) {
  if (r.method == "topology") return "by topology (" + r.method_note + ")";
  return r.method_form.empty() ? r.method + " joint names" : conventionText(r);
}

// What the roles are and why, found by step 1 or 2.
struct Roles {
  std::map<std::string, int> at;
  std::map<std::string, std::string> why;
};

// The parents the importer will pose the roles in: a horse's legs hung from their pivots where the
// file lost what held them (hangLegsFromPivots; the mapping skeleton's hung joints were roots of it).
std::vector<int> posingParents(const MappingSkeleton& s, CharacterKind kind, const std::map<std::string, int>& roles) {
  std::vector<int> parent = s.parent;
  if (kind == CharacterKind::Horse) hangLegsFromPivots(roles, parent, s.hung);
  return parent;
}

// Steps 1 and 2: names when one convention names every required role on chains that hang together,
// else the skeleton's shape (and a horse's tack by name); then a rider's upperChest.
Roles chooseRoles(const MappingSkeleton& s, CharacterKind kind, const AutoMappingParams& params, AutoMappingReport& rep) {
  Roles out;
  const std::vector<NamedRoles> named = rolesByNames(s, kind);
  const NamedRoles* chosen = nullptr;
  std::string first_problem;
  for (const NamedRoles& n : named) {
    if (!params.use_names) break;
    if (!n.missing.empty()) continue;
    const std::string problem = roleChainProblem(kind, n.roles, posingParents(s, kind, n.roles), s.names);
    if (problem.empty()) {
      chosen = &n;
      break;
    }
    if (first_problem.empty()) first_problem = conventionText(n) + " names, but " + problem;
  }
  if (chosen) {
    rep.method = chosen->convention;
    rep.method_form = chosen->form;
    out.at = chosen->roles;
    out.why = chosen->why;
  } else {
    const std::size_t required = requiredRoles(kind).size();
    if (!params.use_names)
      rep.method_note = "names ignored" + (named.empty() || named.front().missing.size() == required ? std::string()
                                           : "; they look like " + conventionText(named.front()));
    else if (!first_problem.empty())
      rep.method_note = first_problem;
    else if (!named.empty() && named.front().score >= 3)
      rep.method_note = "names partly " + conventionText(named.front()) + " (" +
                        std::to_string(required - named.front().missing.size()) + " of " + std::to_string(required) +
                        " required roles)";
    else
      rep.method_note = "no joint names it knows";
    TopologyRoles t;
    try {
      t = kind == CharacterKind::Rider ? riderByTopology(s) : horseByTopology(s);
    } catch (const InputError& e) {
      // What the names nearly said is worth knowing when the shape says nothing.
      if (!params.use_names || named.empty() || named.front().score < 3) throw;
      const NamedRoles& best = named.front();
      throw InputError(std::string(e.what()) + "; its joint names look like " + conventionText(best) +
                       (first_problem.empty() ? " but name no " + joinList(best.missing)
                                              : " but " + first_problem.substr(first_problem.find("but ") + 4)));
    }
    rep.method = "topology";
    out.at = std::move(t.roles);
    out.why = std::move(t.why);
    rep.warnings = std::move(t.warnings);
    if (kind == CharacterKind::Horse && params.use_names)  // tack has no shape of its own: only joints named for it
      for (const auto& [role, key, side] : {std::tuple<const char*, const char*, int>{"saddle", "saddle", 0},
                                            {"lStirrup", "stirrup", 1}, {"rStirrup", "stirrup", -1},
                                            {"lRein", "rein", 1}, {"rRein", "rein", -1}})
        if (const int j = s.find(role) >= 0 ? s.find(role) : jointByKey(s, key, side); j >= 0) {
          out.at[role] = j;
          out.why[role] = "name";
        }
  }
  if (kind == CharacterKind::Rider && !out.at.count("upperChest"))
    if (const int j = upperChestJoint(s, out.at); j >= 0) {
      out.at["upperChest"] = j;
      out.why["upperChest"] = "hierarchy: the spine joint both shoulders hang from";
    }
  return out;
}

// A rider's forward when her toes do not say it: the feet's vertices ahead of the ankles, else the
// chest's vertices ahead of the spine.
glm::dvec3 riderForwardFromMesh(const MappingSkeleton& s, const std::map<std::string, int>& roles, const glm::dvec3& up, double tiny,
                                AutoMappingReport& rep) {
  const auto flat = [&](const glm::dvec3& v) { return v - glm::dot(v, up) * up; };
  const int la = roles.at("lAnkle"), ra = roles.at("rAnkle");
  glm::dvec3 forward(0.0), sum(0.0);
  std::size_t n = 0;
  for (std::size_t v = 0; v < s.vertices.size(); ++v) {
    const int j = s.vertex_joint[v];
    if (s.contains(la, j)) sum += s.vertices[v] - s.position[la], ++n;
    if (s.contains(ra, j)) sum += s.vertices[v] - s.position[ra], ++n;
  }
  if (n > 0) forward = flat(sum / static_cast<double>(n));
  rep.forward_how = "the feet's vertices lie ahead of the ankles";
  if (glm::length(forward) > tiny) return forward;
  const std::vector<int> spine = s.pathDown(roles.at("pelvis"), roles.at("neck"));
  glm::dvec3 joints(0.0);
  sum = glm::dvec3(0.0);
  n = 0;
  for (int j : spine) joints += s.position[j] / static_cast<double>(spine.size());
  for (std::size_t v = 0; v < s.vertices.size(); ++v)
    if (std::find(spine.begin(), spine.end(), s.vertex_joint[v]) != spine.end()) sum += s.vertices[v], ++n;
  const glm::dvec3 across = glm::normalize(flat(s.position[roles.at("lHip")] - s.position[roles.at("rHip")]));
  if (n > 0) {
    const glm::dvec3 f = flat(sum / static_cast<double>(n) - joints);
    forward = f - glm::dot(f, across) * across;
  }
  rep.forward_how = "the chest's vertices lie ahead of the spine";
  return forward;
}

// A horse stands on its hooves in its rest pose: the way from the hooves up to the back lies within
// kMaxHorseTiltDeg of the file's up, glTF's +Y or a Z-up file's +Z. A horse lying on its side, or a
// skeleton turned so its legs point sideways, is refused rather than mapped with its side as up.
void checkHorseStands(const MappingSkeleton& s, const std::map<std::string, int>& roles, const glm::dvec3& up_measured) {
  const glm::dvec3 u = glm::normalize(up_measured);
  const double cos_max = std::cos(kMaxHorseTiltDeg * std::numbers::pi / 180.0);
  if (u.y >= cos_max || u.z >= cos_max) return;
  bool snap = false;
  const glm::dvec3 down = snapped(-u, snap);
  throw InputError(s.file + ": cannot map as a horse: its rest pose does not stand on its hooves: its legs reach from the back (\"" +
                   s.names[roles.at("root")] + "\") to the hooves (\"" + s.names[roles.at("lfHoof")] + "\", ...) toward " +
                   directionText(down) + " (expected down, -Y in glTF or -Z in a Z-up file: turn the horse upright in its file, "
                   "standing on its hooves, and export it again)");
}

// Step 3: up from the feet toward the head (a horse: from the hooves toward the back), forward the
// way the toes point (a horse: from the hips toward the chest), each snapped to the file's nearest
// axis within kAxisSnapDeg.
std::pair<glm::dvec3, glm::dvec3> findAxes(const MappingSkeleton& s, CharacterKind kind, const std::map<std::string, int>& roles,
                                           AutoMappingReport& rep) {
  const std::string kind_name = kindName(kind);
  const auto pos = [&](const std::string& role) { return s.position[static_cast<std::size_t>(roles.at(role))]; };
  glm::dvec3 up_measured, forward_measured(0.0);
  if (kind == CharacterKind::Rider) {
    up_measured = pos("head") - 0.5 * (pos("lAnkle") + pos("rAnkle"));
    rep.up_how = "from the ankles up to the head";
  } else {
    glm::dvec3 hooves(0.0);
    int n = 0;
    for (const char* leg : {"lfHoof", "rfHoof", "lbHoof", "rbHoof"})
      if (roles.count(leg)) hooves += pos(leg), ++n;
    if (n == 0 || !roles.count("root") || !roles.count("chest"))
      throw InputError(s.file + ": cannot map as a horse: no legs, hips or chest found");
    up_measured = 0.5 * (pos("root") + pos("chest")) - hooves / static_cast<double>(n);
    rep.up_how = "from the hooves up to the back";
  }
  if (!(glm::length(up_measured) > 0.0))
    throw InputError(s.file + ": cannot map as a " + kind_name + ": cannot tell up (its " +
                     (kind == CharacterKind::Rider ? "head and ankles" : "back and hooves") + " are at one height)");
  if (kind == CharacterKind::Horse && roles.count("lfHoof")) checkHorseStands(s, roles, up_measured);
  bool up_snapped = false;
  const glm::dvec3 up = snapped(up_measured, up_snapped);
  const auto flat = [&](const glm::dvec3& v) { return v - glm::dot(v, up) * up; };
  double size = 0.0;
  for (const glm::dvec3& p : s.position) size = std::max(size, glm::length(p - s.position[0]));
  const double tiny = 1e-6 * std::max(size, 1e-30);
  if (kind == CharacterKind::Rider) {
    if (roles.count("lBall") && roles.count("rBall")) {
      forward_measured = flat(pos("lBall") - pos("lAnkle") + pos("rBall") - pos("rAnkle"));
      rep.forward_how = "the toes point ahead of the ankles";
    }
    if (!(glm::length(forward_measured) > tiny)) forward_measured = riderForwardFromMesh(s, roles, up, tiny, rep);
  } else {
    forward_measured = flat(pos("chest") - pos("root"));
    rep.forward_how = "from the hips toward the chest, the end the neck and head leave";
  }
  if (!(glm::length(forward_measured) > tiny))
    throw InputError(s.file + ": cannot map as a " + kind_name + ": cannot tell which way it faces (" +
                     (kind == CharacterKind::Rider ? "no toes, feet or chest ahead of the ankles and spine" : "hips and chest at one place") + ")");
  bool forward_snapped = false;
  glm::dvec3 forward = snapped(forward_measured, forward_snapped);
  if (!forward_snapped || !up_snapped) forward = glm::normalize(flat(forward_measured));
  if (!up_snapped) rep.warnings.push_back("up is " + directionText(up) + ", not along one of the file's axes");
  if (!forward_snapped) rep.warnings.push_back("forward is " + directionText(forward) + ", not along one of the file's axes");
  rep.up = directionText(up);
  rep.forward = directionText(forward);
  return {up, forward};
}

// Sides: the character's right is forward x up; a group whose "l" member lies on the right changes
// places with its "r" member.
void settleSides(const MappingSkeleton& s, CharacterKind kind, const glm::dvec3& right, bool by_names, Roles& roles,
                 AutoMappingReport& rep) {
  for (const SideGroup& g : sideGroups(kind)) {
    const auto name = [](const char* side, const std::string& part) { return std::string(side) + part; };  // "l" + "fUpper"
    const int l = roleJoint(roles.at, name("l", g.reference)), r = roleJoint(roles.at, name("r", g.reference));
    if (l < 0 || r < 0 || !(glm::dot(s.position[l] - s.position[r], right) > 0.0)) continue;
    for (const std::string& part : g.parts) {
      const std::string lrole = name("l", part), rrole = name("r", part);
      const int lj = roleJoint(roles.at, lrole), rj = roleJoint(roles.at, rrole);
      roles.at.erase(lrole), roles.at.erase(rrole);
      if (rj >= 0) roles.at[lrole] = rj;
      if (lj >= 0) roles.at[rrole] = lj;
      std::swap(roles.why[lrole], roles.why[rrole]);
      if (roles.why[lrole].empty()) roles.why.erase(lrole);
      if (roles.why[rrole].empty()) roles.why.erase(rrole);
    }
    if (by_names)
      rep.warnings.push_back("the " + conventionText(rep) + " names put the " + g.reference +
                             " called left on the character's right (a mirrored file?): sides swapped");
  }
}

// Step 4: the mesh's height along up read in the common units, the one giving the most plausible
// height; a horse's lowest point put on the ground.
void findScale(const MappingSkeleton& s, CharacterKind kind, const glm::dvec3& up, AutoMappingReport& rep, CharacterMapping& m) {
  const std::string kind_name = kindName(kind);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const glm::dvec3& v : s.vertices) lo = std::min(lo, glm::dot(v, up)), hi = std::max(hi, glm::dot(v, up));
  rep.height_file = hi - lo;
  if (!(rep.height_file > 0.0) || !std::isfinite(rep.height_file))
    throw InputError(s.file + ": cannot map as a " + kind_name + ": its mesh has no height along " + rep.up);
  const bool rider = kind == CharacterKind::Rider;
  const double min_cm = rider ? kRiderHeightMinCm : kHorseHeightMinCm, max_cm = rider ? kRiderHeightMaxCm : kHorseHeightMaxCm;
  const double nominal = rider ? kRiderNominalCm : kHorseNominalCm;
  const std::string measured = rider ? "sole to crown" : "ground to the top of the head";
  double scale = 0.0, best = std::numeric_limits<double>::infinity();
  for (const Unit& u : kUnits) {
    const double cm = rep.height_file * u.cm;
    if (cm < min_cm || cm > max_cm) continue;
    if (const double d = std::abs(std::log(cm / nominal)); d < best) best = d, scale = u.cm, rep.unit = u.name;
  }
  const std::string height_text = "height " + fixedNumber(rep.height_file, rep.height_file < 10 ? 3 : 1) + " file units, " + measured;
  if (scale > 0.0) {
    rep.scale_how = height_text + ", read as " + rep.unit + ": " + fixedNumber(rep.height_file * scale, 0) + " cm";
  } else {
    scale = nominal / rep.height_file;
    rep.scale_how = height_text + ": no common unit makes a " + fixedNumber(min_cm, 0) + "-" + fixedNumber(max_cm, 0) + " cm " + kind_name +
                    ", so scaled to " + fixedNumber(nominal, 0) + " cm";
    rep.warnings.push_back("no common unit gives a plausible height: scaled to " + fixedNumber(nominal, 0) + " cm");
  }
  m.scale_cm = scale;
  if (rider) {
    rep.offset_how = "none (the rig seats her on the horse)";
  } else {
    m.offset_cm = {0.0, -lo * scale, 0.0};
    rep.offset_how = "the lowest point of the mesh on the ground (" + fixedNumber(-lo * scale, 2) + " cm up)";
  }
}

}  // namespace

AutoMapping autoMapCharacter(const MappingSkeleton& s, CharacterKind kind, const AutoMappingParams& params) {
  if (s.size() > kMaxAutoMappedJoints)
    throw InputError(s.file + ": " + std::to_string(s.size()) + " joints: too many to map by itself (at most " +
                     std::to_string(kMaxAutoMappedJoints) + "); write a mapping file (docs/characters.md, \"User characters\")");
  AutoMapping out;
  AutoMappingReport& rep = out.report;
  rep.file = s.file;
  rep.kind = kind;
  Roles roles = chooseRoles(s, kind, params, rep);
  const auto [up, forward] = findAxes(s, kind, roles.at, rep);
  settleSides(s, kind, glm::cross(forward, up), rep.method != "topology", roles, rep);
  CharacterMapping& m = out.mapping;
  m.up = {up.x, up.y, up.z};
  m.forward = {forward.x, forward.y, forward.z};
  findScale(s, kind, up, rep, m);

  // The roles, checked once more as the importer will check them.
  if (const std::string problem = roleChainProblem(kind, roles.at, posingParents(s, kind, roles.at), s.names); !problem.empty())
    throw InputError(s.file + ": " + problem + " (the automatic mapping chose it; write a mapping file)");
  if (kind == CharacterKind::Rider) {
    const glm::dvec3 spine = s.position[roles.at.at("neck")] - s.position[roles.at.at("pelvis")];
    const double tilt = std::acos(std::clamp(glm::dot(glm::normalize(spine), up), -1.0, 1.0)) * 180.0 / std::numbers::pi;
    if (!(tilt < kMaxSpineTiltDeg))
      throw InputError(s.file + ": cannot map as a rider: her spine from \"" + s.names[roles.at.at("pelvis")] + "\" to \"" +
                       s.names[roles.at.at("neck")] + "\" leans " + fixedNumber(tilt, 0) +
                       " degrees from the vertical (expected a character standing upright; a four-legged one? try --as horse)");
  }
  for (const std::vector<std::string>* list : {&requiredRoles(kind), &optionalRoles(kind)})
    for (const std::string& role : *list)
      if (const auto it = roles.at.find(role); it != roles.at.end()) {
        m.roles[role] = s.names[it->second];
        rep.roles.push_back({role, s.names[it->second], roles.why.count(role) ? roles.why.at(role) : std::string("name")});
      }
  for (const std::string& role : requiredRoles(kind))
    if (!roles.at.count(role)) rep.not_mapped.push_back(role);
  for (const std::string& role : lookedForOptional(kind))
    if (!roles.at.count(role)) rep.optional_not_mapped.push_back(role);
  if (kind == CharacterKind::Rider) rep.left_to_rig = {"lowerBack", "waist", "chest", "braid1", "braid2", "braid3", "coatTail"};
  return out;
}

nlohmann::ordered_json autoMappingJson(const AutoMapping& a) {
  const AutoMappingReport& r = a.report;
  std::string comment = "made by stirrup character map from " + std::filesystem::path(r.file).filename().string() + " (" +
                        (r.method == "topology" ? "by topology: " + r.method_note : methodText(r)) + "; up " + r.up + ": " + r.up_how +
                        "; forward " + r.forward + ": " + r.forward_how + "; " + r.scale_how;
  if (!r.not_mapped.empty()) comment += "; not mapped: " + joinList(r.not_mapped);
  if (!r.optional_not_mapped.empty()) comment += "; optional, not found: " + joinList(r.optional_not_mapped);
  comment += ")";
  nlohmann::ordered_json j;
  j["comment"] = comment;
  j["character"] = kindName(r.kind);
  j["scale_cm"] = a.mapping.scale_cm;
  j["forward"] = a.mapping.forward;
  j["up"] = a.mapping.up;
  j["offset_cm"] = a.mapping.offset_cm;
  nlohmann::ordered_json roles = nlohmann::ordered_json::object();
  for (const RoleChoice& c : r.roles) roles[c.role] = c.joint;
  j["roles"] = roles;
  return j;
}

std::string autoMappingFileText(const AutoMapping& a) {
  const nlohmann::ordered_json j = autoMappingJson(a);
  std::string out = "{\n";
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it != j.begin()) out += ",\n";
    out += "  " + nlohmann::json(it.key()).dump() + ": ";
    if (it.key() != "roles") {
      out += it.value().dump();
      continue;
    }
    out += "{";
    for (auto r = it.value().begin(); r != it.value().end(); ++r)
      out += std::string(r == it.value().begin() ? "\n" : ",\n") + "    " + nlohmann::json(r.key()).dump() + ": " + r.value().dump();
    out += "\n  }";
  }
  return out + "\n}\n";
}

std::string autoMappingReportText(const AutoMapping& a) {
  const AutoMappingReport& r = a.report;
  std::ostringstream o;
  o << r.file << " as a " << kindName(r.kind) << ": "
    << methodText(r) << "\n";
  o << "  up       " << r.up << "  (" << r.up_how << ")\n";
  o << "  forward  " << r.forward << "  (" << r.forward_how << ")\n";
  o << "  scale    " << fixedNumber(a.mapping.scale_cm, a.mapping.scale_cm < 10 ? 4 : 2) << " cm per file unit  (" << r.scale_how << ")\n";
  o << "  offset   " << r.offset_how << "\n";
  std::size_t width = 0, jwidth = 0;
  for (const RoleChoice& c : r.roles) width = std::max(width, c.role.size()), jwidth = std::max(jwidth, c.joint.size());
  o << "  roles:\n";
  for (const RoleChoice& c : r.roles)
    o << "    " << c.role << std::string(width - c.role.size() + 2, ' ') << c.joint << std::string(jwidth - c.joint.size() + 2, ' ')
      << c.why << "\n";
  if (!r.not_mapped.empty()) o << "  not mapped: " << joinList(r.not_mapped, " ") << "\n";
  if (!r.optional_not_mapped.empty()) o << "  optional, not found: " << joinList(r.optional_not_mapped, " ") << "\n";
  if (!r.left_to_rig.empty()) o << "  optional, left to the rig: " << joinList(r.left_to_rig, " ") << "\n";
  for (const std::string& w : r.warnings) o << "  warning: " << w << "\n";
  return o.str();
}

std::string autoMappingSummary(const AutoMapping& a) {
  const AutoMappingReport& r = a.report;
  const std::size_t required = requiredRoles(r.kind).size();
  std::string line1 = r.file + ": no role table: mapped as a " + kindName(r.kind) + " by " +
                      (r.method == "topology" ? "topology" : methodText(r)) + "; up " + r.up + ", forward " +
                      r.forward + ", " + fixedNumber(a.mapping.scale_cm, a.mapping.scale_cm < 10 ? 4 : 2) + " cm per unit" +
                      (r.unit.empty() ? "" : " (" + r.unit + ")");
  std::string line2 = "  " + std::to_string(required - r.not_mapped.size()) + " of " + std::to_string(required) + " roles";
  if (!r.not_mapped.empty()) line2 += "; not mapped: " + joinList(r.not_mapped);
  if (!r.optional_not_mapped.empty()) line2 += "; optional, not found: " + joinList(r.optional_not_mapped);
  if (!r.warnings.empty()) line2 += "; " + std::to_string(r.warnings.size()) + (r.warnings.size() == 1 ? " warning" : " warnings");
  line2 += " (stirrup character map " + r.file + " --as " + kindName(r.kind) + " lists every choice)";
  return line1 + "\n" + line2 + "\n";
}

}  // namespace stirrup::rig
