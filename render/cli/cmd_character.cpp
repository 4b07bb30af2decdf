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
#include "render/cli/options.h"
#include "rig/error.h"
#include "rig/io/gltf_character.h"
#include "rig/characters/character_params.h"

namespace stirrup::cli {
namespace {

struct CharacterOptions {
  std::string kind;
  std::string output;
  std::vector<std::string> params;
};

// Applies "--name value" pairs to a params struct; unknown names and bad numbers are one-line errors.
template <class P>
void applyParams(const std::vector<rig::CharacterParam<P>>& table, const std::vector<std::string>& args,
                 const std::string& kind, P& out) {
  const std::string cmd = "character make " + kind;
  for (const auto& [key, value] : namedParameters(cmd, args)) rig::setCharacterParameter(table, key, value, cmd, out);
}

void runMake(const CharacterOptions& o) {
  rig::Character c;
  if (o.kind == "horse") {
    rig::HorseParams p;
    applyParams(rig::horseParameters(), o.params, o.kind, p);
    if (!(p.cell >= 0.5f)) throw InputError("character make horse: --cell: expected at least 0.5 cm");
    c = rig::buildHorse(p);
  } else if (o.kind == "rider") {
    rig::RiderParams p;
    applyParams(rig::riderParameters(), o.params, o.kind, p);
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
             rig::characterParameterList(rig::horseParameters()) + "\n  rider:" + rig::characterParameterList(rig::riderParameters()) +
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
