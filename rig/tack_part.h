// The parts of a horse's tack, as its mesh records them vertex by vertex (SkinnedMesh::tack_parts) and
// the full bake writes them, one mesh node a part (rig/io/gltf_tack.h): the names a Blender user sees.
//
//   saddle             the seat, pommel and cantle
//   saddle pad         the pad, the flaps and the girth (the shells around the barrel under the seat)
//   bridle             the headstall (crown piece, cheek pieces, the generated horse's noseband)
//   bit                the bar through the mouth
//   stirrup leather.L  the leather from under the skirt to the left iron (.R the right: Blender's sides)
//   stirrup iron.L     the left iron round its tread
//   reins              both reins, from the bit to the hand ends
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace stirrup::rig {

enum class TackPart : std::uint8_t {
  None = 0,  // not tack: the horse's body (or any other character's mesh)
  Saddle,
  SaddlePad,
  Bridle,
  Bit,
  StirrupLeatherL,
  StirrupLeatherR,
  StirrupIronL,
  StirrupIronR,
  Reins,
};

// Every part, in the order the bake writes them.
inline constexpr std::array<TackPart, 9> kTackParts = {TackPart::Saddle,          TackPart::SaddlePad,       TackPart::Bridle,
                                                       TackPart::Bit,             TackPart::StirrupLeatherL, TackPart::StirrupLeatherR,
                                                       TackPart::StirrupIronL,    TackPart::StirrupIronR,    TackPart::Reins};

// The part's name ("" for None).
constexpr std::string_view tackPartName(TackPart p) {
  switch (p) {
    case TackPart::None: return "";
    case TackPart::Saddle: return "saddle";
    case TackPart::SaddlePad: return "saddle pad";
    case TackPart::Bridle: return "bridle";
    case TackPart::Bit: return "bit";
    case TackPart::StirrupLeatherL: return "stirrup leather.L";
    case TackPart::StirrupLeatherR: return "stirrup leather.R";
    case TackPart::StirrupIronL: return "stirrup iron.L";
    case TackPart::StirrupIronR: return "stirrup iron.R";
    case TackPart::Reins: return "reins";
  }
  return "";
}

// The part a name names, or nullopt.
constexpr std::optional<TackPart> tackPartNamed(std::string_view name) {
  for (TackPart p : kTackParts)
    if (tackPartName(p) == name) return p;
  return std::nullopt;
}

// The stirrup leather or iron of a side (-1 the left, +1 the right, as the characters mirror z).
constexpr TackPart stirrupLeather(float side) { return side < 0 ? TackPart::StirrupLeatherL : TackPart::StirrupLeatherR; }
constexpr TackPart stirrupIron(float side) { return side < 0 ? TackPart::StirrupIronL : TackPart::StirrupIronR; }

}  // namespace stirrup::rig
