// stirrup character make horse|rider [--param value ...] -o FILE.glb: builds a default character (or
// one with changed proportions) and writes it as a skinned glTF 2.0 binary (docs/characters.md).
// scripts/make-characters makes scenes/characters/*.glb with it.
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "render/cli/commands.h"
#include "rig/error.h"
#include "rig/io/gltf_character.h"
#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"

namespace stirrup::cli {
namespace {

struct CharacterOptions {
  std::string kind;
  std::string output;
  std::vector<std::string> params;
};

// A parameter the command line can set: a number or a vector "x,y,z" of a params struct.
template <class P>
struct Param {
  const char* name;
  std::variant<float P::*, glm::vec3 P::*> member;
};

const std::vector<Param<rig::HorseParams>>& horseParams() {
  using H = rig::HorseParams;
  static const std::vector<Param<H>> p = {
      {"withers_height", &H::withers_height}, {"withers_x", &H::withers_x},
      {"hips", &H::hips},                     {"back_mid", &H::back_mid},
      {"barrel_center", &H::barrel_center},   {"barrel_radii", &H::barrel_radii},
      {"buttock_center", &H::buttock_center}, {"buttock_radii", &H::buttock_radii},
      {"quarter_center", &H::quarter_center}, {"quarter_radii", &H::quarter_radii},
      {"chest_center", &H::chest_center},     {"chest_radii", &H::chest_radii},
      {"neck_base", &H::neck_base},           {"neck_mid", &H::neck_mid},
      {"poll", &H::poll},                     {"muzzle", &H::muzzle},
      {"neck_base_radius", &H::neck_base_radius}, {"neck_mid_radius", &H::neck_mid_radius},
      {"head_radius", &H::head_radius},       {"muzzle_radius", &H::muzzle_radius},
      {"ear_length", &H::ear_length},         {"mane_radius", &H::mane_radius},
      {"forearm_radius", &H::forearm_radius}, {"cannon_radius", &H::cannon_radius},
      {"gaskin_radius", &H::gaskin_radius},   {"hoof_radius", &H::hoof_radius},
      {"tail_root", &H::tail_root},           {"tail_length", &H::tail_length},
      {"saddle_x", &H::saddle_x},             {"saddle_seat_height", &H::saddle_seat_height},
      {"rein_radius", &H::rein_radius},       {"strap_radius", &H::strap_radius},
      {"coat", &H::coat},                     {"points", &H::points},
      {"leather", &H::leather},               {"pad", &H::pad},
      {"cell", &H::cell}};
  return p;
}

const std::vector<Param<rig::RiderParams>>& riderParams() {
  using R = rig::RiderParams;
  static const std::vector<Param<R>> p = {
      {"pelvis", &R::pelvis},           {"lower_back", &R::lower_back},   {"waist", &R::waist},
      {"chest", &R::chest},             {"upper_chest", &R::upper_chest}, {"neck", &R::neck},
      {"head", &R::head},               {"head_height", &R::head_height}, {"shoulder", &R::shoulder},
      {"upper_arm", &R::upper_arm},     {"forearm", &R::forearm},         {"hip", &R::hip},
      {"thigh", &R::thigh},             {"shin", &R::shin},               {"knee_pole_dir", &R::knee_pole_dir},
      {"hips_radii", &R::hips_radii},
      {"chest_radii", &R::chest_radii}, {"waist_radius", &R::waist_radius},
      {"thigh_radius", &R::thigh_radius}, {"calf_radius", &R::calf_radius},
      {"braid_radius", &R::braid_radius}, {"braid_length", &R::braid_length},
      {"coat_tail_length", &R::coat_tail_length},
      {"skin", &R::skin},               {"coat", &R::coat},               {"breeches", &R::breeches},
      {"boots", &R::boots},             {"hair", &R::hair},               {"cell", &R::cell}};
  return p;
}

template <class P>
std::string paramList(const std::vector<Param<P>>& params) {
  std::string s;
  for (const auto& p : params) s += " --" + std::string(p.name) + (std::holds_alternative<float P::*>(p.member) ? "" : " x,y,z");
  return s;
}

// Applies "--name value" pairs to a params struct; unknown names and bad numbers are one-line errors.
template <class P>
void applyParams(const std::vector<Param<P>>& table, const std::vector<std::string>& args, const std::string& kind, P& out) {
  const std::string cmd = "character make " + kind;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) != 0 || a.size() < 3) throw InputError(cmd + ": expected --parameter value, got \"" + a + "\"");
    std::string key = a.substr(2), value;
    if (const auto eq = key.find('='); eq != std::string::npos) {
      value = key.substr(eq + 1);
      key = key.substr(0, eq);
    } else {
      if (i + 1 >= args.size()) throw InputError(cmd + ": --" + key + ": expected a value");
      value = args[++i];
    }
    for (char& c : key)
      if (c == '-') c = '_';
    const Param<P>* found = nullptr;
    for (const auto& p : table)
      if (key == p.name) found = &p;
    if (!found) throw InputError(cmd + ": --" + key + ": unknown parameter (expected one of" + paramList(table) + ")");
    std::vector<float> numbers;
    std::size_t start = 0;
    while (start <= value.size()) {
      const std::size_t comma = value.find(',', start);
      const std::string part = value.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      char* end = nullptr;
      const double v = std::strtod(part.c_str(), &end);
      if (part.empty() || !end || *end != '\0' || !std::isfinite(v))
        throw InputError(cmd + ": --" + key + ": expected a number" +
                         (std::holds_alternative<float P::*>(found->member) ? "" : "s x,y,z") + ", got \"" + value + "\"");
      numbers.push_back(static_cast<float>(v));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    if (auto* f = std::get_if<float P::*>(&found->member)) {
      if (numbers.size() != 1) throw InputError(cmd + ": --" + key + ": expected one number, got \"" + value + "\"");
      if (!(numbers[0] > 0.0f)) throw InputError(cmd + ": --" + key + ": expected a number > 0, got \"" + value + "\"");
      out.*(*f) = numbers[0];
    } else {
      if (numbers.size() != 3) throw InputError(cmd + ": --" + key + ": expected three numbers x,y,z, got \"" + value + "\"");
      out.*std::get<glm::vec3 P::*>(found->member) = glm::vec3(numbers[0], numbers[1], numbers[2]);
    }
  }
}

void runMake(const CharacterOptions& o) {
  rig::Character c;
  if (o.kind == "horse") {
    rig::HorseParams p;
    applyParams(horseParams(), o.params, o.kind, p);
    if (!(p.cell >= 0.5f)) throw InputError("character make horse: --cell: expected at least 0.5 cm");
    c = rig::buildHorse(p);
  } else if (o.kind == "rider") {
    rig::RiderParams p;
    applyParams(riderParams(), o.params, o.kind, p);
    if (!(p.cell >= 0.5f)) throw InputError("character make rider: --cell: expected at least 0.5 cm");
    c = rig::buildRider(p, rig::HorseParams{}.mount);
  } else {
    throw InputError("character make: expected horse or rider, got \"" + o.kind + "\"");
  }
  const std::vector<unsigned char> bytes = rig::characterGlb(c);
  rig::writeFileAtomically(o.output, bytes);
  std::printf("wrote %s: %s, %zu joints, %zu vertices, %zu triangles, %zu bytes\n", o.output.c_str(), c.name.c_str(),
              c.skeleton.size(), c.mesh.vertexCount(), c.mesh.triangleCount(), bytes.size());
}

}  // namespace

void addCharacterCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("character", "Make the default horse and rider as skinned glTF 2.0");
  cmd->require_subcommand(1);
  auto make = std::make_shared<CharacterOptions>();
  CLI::App* mk = cmd->add_subcommand("make", "Build a character from its parameters and write it as .glb");
  mk->footer("Parameters (centimetres; colours linear RGB; vectors x,y,z in the bind pose):\n  horse:" +
             paramList(horseParams()) + "\n  rider:" + paramList(riderParams()) +
             "\nThe stirrup and rein places are the horse's mount (rig/characters/horse_character.h), shared by both.\n"
             "Example: stirrup character make horse -o scenes/characters/horse.glb");
  mk->add_option("kind", make->kind, "horse or rider")->required();
  mk->add_option("-o,--output", make->output, "Output file (.glb)")->required();
  mk->allow_extras();
  mk->callback([make, mk] {
    make->params = mk->remaining();
    runMake(*make);
  });
}

}  // namespace stirrup::cli
