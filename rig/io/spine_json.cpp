#include "rig/io/spine_json.h"

#include <cmath>

#include "rig/error.h"
#include "rig/io/json_fields.h"

namespace stirrup::rig {
namespace {

// An array of exactly N finite numbers at `path`, else one line naming the file and the field.
template <std::size_t N>
std::array<double, N> readNumbers(const std::string& file, const std::string& path, const nlohmann::json* v) {
  const auto fail = [&](const std::string& what) { throw InputError(file + ": " + path + ": " + what); };
  if (!v) fail("missing (expected " + std::to_string(N) + " numbers)");
  if (!v->is_array()) fail("expected " + std::to_string(N) + " numbers, got " + describeJson(*v));
  if (v->size() != N) fail("expected " + std::to_string(N) + " numbers, got " + std::to_string(v->size()));
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    const nlohmann::json& e = (*v)[i];
    if (!e.is_number() || !std::isfinite(e.get<double>()))
      throw InputError(file + ": " + path + "[" + std::to_string(i) + "]: expected a number, got " + describeJson(e));
    out[i] = e.get<double>();
  }
  return out;
}

glm::dvec3 toVec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

nlohmann::json toJson(const glm::dvec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

}  // namespace

SpineFile readSpineFile(const std::string& file) {
  const nlohmann::json json = readJsonFile(file);
  JsonObjectReader top(file, "", json);
  SpineFile spine;

  spine.bones = readNumbers<3>(file, "bones", top.value("bones"));
  for (std::size_t i = 0; i < 3; ++i)
    if (!(spine.bones[i] > 0.0))
      top.fail("bones[" + std::to_string(i) + "]",
               "expected a positive length in cm, got " + describeJson(json["bones"][i]));

  if (!top.has("segments")) top.fail("segments", "missing (expected a whole number from 3 to 32)");
  const nlohmann::json& seg = json["segments"];
  if (!seg.is_number_integer() || seg.get<long long>() < CurveSpine::kMinSegments ||
      seg.get<long long>() > CurveSpine::kMaxSegments)
    top.fail("segments", "expected a whole number from 3 to 32, got " + describeJson(seg));
  spine.segments = top.integer("segments", CurveSpine::kRiderSegments);

  const std::string layout = top.string("layout", "equal_arc_length");
  if (layout == "equal_chord") spine.layout = ChainLayout::EqualChord;
  else if (layout != "equal_arc_length")
    top.fail("layout", "expected \"equal_arc_length\" or \"equal_chord\", got \"" + layout + "\"");

  const nlohmann::json* poses = top.value("poses");
  if (!poses) top.fail("poses", "missing (expected an array of poses)");
  if (!poses->is_array() || poses->empty())
    top.fail("poses", "expected a non-empty array of poses, got " + describeJson(*poses));
  for (std::size_t i = 0; i < poses->size(); ++i) {
    const std::string path = "poses[" + std::to_string(i) + "]";
    JsonObjectReader pose(file, path, (*poses)[i]);
    SpinePose p;
    p.controllers.lower = toVec(readNumbers<3>(file, path + ".lower", pose.value("lower")));
    p.controllers.middle = toVec(readNumbers<3>(file, path + ".middle", pose.value("middle")));
    p.controllers.top = toVec(readNumbers<3>(file, path + ".top", pose.value("top")));
    p.stretch = pose.number("stretch", 1.0);
    if (!(p.stretch > 0.0)) pose.fail("stretch", "expected a positive factor, got " + describeJson((*poses)[i]["stretch"]));
    pose.finish();
    spine.poses.push_back(p);
  }
  top.finish();
  return spine;
}

nlohmann::json spineResultToJson(const SpineResult& r, double stretch) {
  nlohmann::json pose;
  pose["fk"] = nlohmann::json::array();
  for (const glm::dvec3& p : r.fk) pose["fk"].push_back(toJson(p));
  pose["curve_points"] = nlohmann::json::array();
  for (const glm::dvec3& p : r.curve_points) pose["curve_points"].push_back(toJson(p));
  pose["length"] = r.length;
  pose["stretch"] = stretch;
  pose["layout"] = r.layout == ChainLayout::EqualChord ? "equal_chord" : "equal_arc_length";
  pose["bone_length"] = r.bone_length;
  pose["chain_length"] = r.chain_length;
  pose["bone_chords"] = r.bone_chords;
  pose["chain_deficit"] = r.chain_deficit;
  pose["layout_converged"] = r.layout_converged;
  pose["ten_null_length"] = r.ten_null_length;
  pose["samples"] = nlohmann::json::array();
  for (const glm::dvec3& p : r.samples) pose["samples"].push_back(toJson(p));
  pose["joints"] = nlohmann::json::array();
  for (std::size_t j = 0; j < r.joints.size(); ++j) {
    const glm::dquat& q = r.joints[j].rotation;
    pose["joints"].push_back({{"position", toJson(r.joints[j].position)},
                              {"rotation", nlohmann::json::array({q.w, q.x, q.y, q.z})},
                              {"twist", r.twist_deg[j]}});
  }
  return pose;
}

}  // namespace stirrup::rig
