#include "rig/characters/palette.h"

#include <stdexcept>

namespace stirrup::rig {

const std::vector<HorseCoat>& horseCoats() {
  const HorseParams d;
  static const std::vector<HorseCoat> list = {
      {"bay", d.coat, d.points},
      {"chestnut", {0.30f, 0.085f, 0.025f}, {0.24f, 0.07f, 0.02f}},  // points the coat's red, a shade darker
      {"black", {0.022f, 0.018f, 0.016f}, {0.014f, 0.012f, 0.010f}},
      {"grey", {0.42f, 0.42f, 0.41f}, {0.22f, 0.22f, 0.22f}},
      {"dun", {0.40f, 0.27f, 0.13f}, {0.03f, 0.02f, 0.015f}},
      {"palomino", {0.55f, 0.36f, 0.13f}, {0.70f, 0.64f, 0.52f}},      // flaxen mane and tail
      {"brown", {0.065f, 0.028f, 0.012f}, {0.02f, 0.014f, 0.01f}},
  };
  return list;
}

const std::vector<NamedColor>& riderJackets() {
  static const std::vector<NamedColor> list = {
      {"red", RiderParams{}.coat},
      {"navy", {0.018f, 0.026f, 0.09f}},
      {"black", {0.014f, 0.014f, 0.016f}},
      {"green", {0.03f, 0.10f, 0.04f}},
      {"tweed", {0.19f, 0.13f, 0.07f}},
      {"blue", {0.05f, 0.12f, 0.36f}},
      {"grey", {0.17f, 0.17f, 0.18f}},
  };
  return list;
}

const std::vector<NamedColor>& riderHair() {
  static const std::vector<NamedColor> list = {
      {"brown", RiderParams{}.hair},
      {"black", {0.012f, 0.010f, 0.009f}},
      {"blonde", {0.50f, 0.36f, 0.16f}},
      {"auburn", {0.22f, 0.06f, 0.02f}},
      {"grey", {0.40f, 0.40f, 0.40f}},
  };
  return list;
}

const std::vector<NamedColor>& riderSkins() {
  static const std::vector<NamedColor> list = {
      {"light", RiderParams{}.skin},
      {"fair", {0.80f, 0.55f, 0.42f}},
      {"olive", {0.55f, 0.33f, 0.20f}},
      {"brown", {0.36f, 0.19f, 0.10f}},
      {"dark", {0.16f, 0.08f, 0.045f}},
  };
  return list;
}

namespace {
template <class T>
std::string namesOf(const std::vector<T>& list) {
  std::string s;
  for (const T& e : list) s += (s.empty() ? "" : ", ") + std::string(e.name);
  return s;
}
}  // namespace

std::string paletteNames(const std::vector<HorseCoat>& list) { return namesOf(list); }
std::string paletteNames(const std::vector<NamedColor>& list) { return namesOf(list); }

const HorseCoat* findHorseCoat(const std::string& name) {
  for (const HorseCoat& c : horseCoats())
    if (name == c.name) return &c;
  return nullptr;
}

const NamedColor* findNamedColor(const std::vector<NamedColor>& list, const std::string& name) {
  for (const NamedColor& c : list)
    if (name == c.name) return &c;
  return nullptr;
}

void applyHorseCoat(const std::string& coat, HorseParams& horse) {
  const HorseCoat* c = findHorseCoat(coat);
  if (!c) throw std::invalid_argument("applyHorseCoat: no coat \"" + coat + "\"");
  horse.coat = c->coat;
  horse.points = c->points;
}

void applyRiderColors(const std::string& jacket, const std::string& hair, const std::string& skin, RiderParams& rider) {
  const NamedColor* j = findNamedColor(riderJackets(), jacket);
  const NamedColor* h = findNamedColor(riderHair(), hair);
  const NamedColor* s = findNamedColor(riderSkins(), skin);
  if (!j || !h || !s) throw std::invalid_argument("applyRiderColors: no colour \"" + (!j ? jacket : !h ? hair : skin) + "\"");
  rider.coat = j->color;
  rider.hair = h->color;
  rider.skin = s->color;
}

}  // namespace stirrup::rig
