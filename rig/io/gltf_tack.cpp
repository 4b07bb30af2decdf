#include "rig/io/gltf_tack.h"

#include <cmath>

#include <tiny_gltf.h>

#include "rig/error.h"

namespace stirrup::rig {

std::vector<GltfMeshPiece> gltfMeshPieces(const SkinnedMesh& mesh, bool split_tack) {
  const std::size_t nt = mesh.triangleCount(), nv = mesh.vertexCount();
  std::vector<GltfMeshPiece> pieces(1);
  if (!split_tack || !mesh.hasTack()) {
    pieces[0].triangles.resize(nt);
    for (std::size_t t = 0; t < nt; ++t) pieces[0].triangles[t] = std::uint32_t(t);
    return pieces;
  }
  // Piece k holds part kTackParts[k - 1]; piece 0 the body.
  std::vector<int> piece_of(kTackParts.size() + 1, -1);
  const auto index = [](TackPart p) { return std::size_t(p); };
  std::vector<std::vector<std::uint32_t>> by_part(kTackParts.size() + 1);
  for (std::size_t t = 0; t < nt; ++t) by_part[index(mesh.triangleTackPart(t))].push_back(std::uint32_t(t));
  // Vertices: a piece's triangles' and, for the body, every vertex of no part (all of them in a mesh
  // without tack, so the body is written as before).
  const auto used = [&](const std::vector<std::uint32_t>& triangles, bool body) {
    std::vector<char> in(nv, 0);
    for (std::uint32_t t : triangles)
      for (int k = 0; k < 3; ++k) in[mesh.indices[std::size_t(t) * 3 + std::size_t(k)]] = 1;
    std::vector<std::uint32_t> out;
    for (std::size_t v = 0; v < nv; ++v)
      if (in[v] || (body && mesh.tackPart(v) == TackPart::None)) out.push_back(std::uint32_t(v));
    return out;
  };
  pieces[0].triangles = std::move(by_part[0]);
  pieces[0].vertices = used(pieces[0].triangles, true);
  if (pieces[0].vertices.size() == nv) pieces[0].vertices.clear();
  for (TackPart part : kTackParts) {
    std::vector<std::uint32_t>& triangles = by_part[index(part)];
    if (triangles.empty()) continue;
    GltfMeshPiece piece;
    piece.part = part;
    piece.vertices = used(triangles, false);
    piece.triangles = std::move(triangles);
    pieces.push_back(std::move(piece));
  }
  return pieces;
}

tinygltf::Value tackNodeExtras(TackPart part, const std::string& fits, const std::string& file) {
  tinygltf::Value::Object o;
  o["stirrup_tack"] = tinygltf::Value(std::string(tackPartName(part)));
  o["stirrup_fits"] = tinygltf::Value(fits);
  if (!file.empty()) o["stirrup_fits_file"] = tinygltf::Value(file);
  return tinygltf::Value(o);
}

namespace {

std::string partList() {
  std::string out;
  for (TackPart p : kTackParts) out += (out.empty() ? "\"" : ", \"") + std::string(tackPartName(p)) + "\"";
  return out;
}

}  // namespace

TackPart gltfNodeTackPart(const tinygltf::Model& model, const tinygltf::Node& node, const std::string& where) {
  const tinygltf::Value* extras = &node.extras;
  if (!(extras->IsObject() && extras->Has("stirrup_tack")) && node.mesh >= 0 && node.mesh < int(model.meshes.size()))
    extras = &model.meshes[std::size_t(node.mesh)].extras;
  if (!extras->IsObject() || !extras->Has("stirrup_tack")) return TackPart::None;
  const tinygltf::Value& v = extras->Get("stirrup_tack");
  if (const std::optional<TackPart> p = v.IsString() ? tackPartNamed(v.Get<std::string>()) : std::nullopt) return *p;
  throw InputError(where + ".extras.stirrup_tack: expected one of the tack's parts, " + partList() +
                   (v.IsString() ? ", got \"" + v.Get<std::string>() + "\"" : ""));
}

std::vector<TackPart> tackPartsOf(const std::vector<float>& values, std::size_t count, const std::string& where) {
  if (values.size() != count) throw InputError(where + "._TACK_PART: expected one part a vertex");
  std::vector<TackPart> out(count);
  for (std::size_t v = 0; v < count; ++v) {
    const float x = values[v];
    if (!(x >= 0.0f && x <= float(kTackParts.size())) || x != std::floor(x))
      throw InputError(where + "._TACK_PART: vertex " + std::to_string(v) + ": expected a tack part's index 0 to " +
                       std::to_string(kTackParts.size()) + " (0 the body)");
    out[v] = TackPart(std::uint8_t(x));
  }
  return out;
}

}  // namespace stirrup::rig
