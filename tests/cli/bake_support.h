// What the bake tests share: a CSV line's cells, a default scene baked to glTF, the Khronos validator's
// verdict on a file, and a world point in pixels through a glTF camera and through stirrup's render
// camera (the baked file is read back with tests/test_files.h's readGlbModel).
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "rig/io/gltf_tack.h"
#include "rig/mesh.h"
#include "scene/camera.h"
#include "tests/cli/run_command.h"
#include "tests/test_files.h"

namespace stirrup::test {

// The vertex of stirrup's mesh each vertex of the bake's body node (`horse:horse_mesh`) was written from:
// the body piece of rig::gltfMeshPieces, the tack's parts being nodes of their own (docs/round-trip.md,
// "The tack"); a mesh without tack is written whole.
inline std::vector<std::uint32_t> bodyVertices(const rig::SkinnedMesh& mesh) {
  const rig::GltfMeshPiece body = rig::gltfMeshPieces(mesh, true).at(0);
  if (!body.vertices.empty()) return body.vertices;
  std::vector<std::uint32_t> all(mesh.vertexCount());
  std::iota(all.begin(), all.end(), 0u);
  return all;
}

// How many vertices the bake writes for a mesh: each piece's (the tack's seams in two pieces).
inline std::size_t writtenVertices(const rig::SkinnedMesh& mesh) {
  std::size_t n = 0;
  for (const rig::GltfMeshPiece& p : rig::gltfMeshPieces(mesh, true)) n += p.vertices.empty() ? mesh.vertexCount() : p.vertices.size();
  return n;
}

inline std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string c;
  while (std::getline(ss, c, ',')) cells.push_back(c);
  return cells;
}

// stirrup bake -o: one glTF with both characters, their animation and the cameras.
inline std::filesystem::path bakeGlb(const std::string& scene, const std::string& frames) {
  // A folder per scene: CTest runs the tests in parallel, and each clears only its own folder.
  const std::string stem = std::filesystem::path(scene).stem().string();
  const std::filesystem::path out = std::filesystem::path(STIRRUP_BINARY_DIR) / "test_bake_glb" / stem / (stem + ".glb");
  std::filesystem::remove_all(out.parent_path());
  const CommandResult r = runStirrup("bake " + quote(std::string(STIRRUP_SOURCE_DIR "/scenes/") + scene) + " --frames " +
                                     frames + " -o " + quote(out.string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  return out;
}

// The Khronos validator's verdict on a file: "" when it finds no error and no warning, else why not;
// skipped (a message) where node or the validator is absent.
inline std::string validatorProblems(const std::filesystem::path& glb, bool& skipped) {
  skipped = false;
  if (runCommand("command -v node >/dev/null").exit_code != 0) return skipped = true, "node is not installed";
  std::filesystem::path modules = std::filesystem::path(STIRRUP_BINARY_DIR) / "tools" / "node_modules";
  if (!std::filesystem::exists(modules / "gltf-validator")) modules = std::filesystem::path(STIRRUP_SOURCE_DIR) / "build" / "tools" / "node_modules";
  if (!std::filesystem::exists(modules / "gltf-validator")) return "gltf-validator is not installed: run scripts/setup";
  const CommandResult v = runCommand("node " + quote(STIRRUP_SOURCE_DIR "/tests/cli/validate_gltf.js") + " " +
                                     quote(modules.string()) + " " + quote(glb.string()));
  if (v.exit_code != 0) return v.err;
  if (v.out.find("\"errors\":0,") == std::string::npos || v.out.find("\"warnings\":0,") == std::string::npos) return v.out;
  return "";
}

// A world point (metres) in pixels through a glTF camera on a node with world matrix `world`
// (glTF 2.0 section 3.10: the camera looks down its local -Z, +Y up; projection matrices of 3.10.3).
inline glm::dvec2 gltfPixel(const tinygltf::Camera& cam, const glm::dmat4& world, glm::dvec3 p, int width, int height) {
  const glm::dvec3 c(glm::inverse(world) * glm::dvec4(p, 1.0));
  glm::dvec2 ndc;
  if (cam.type == "orthographic") {
    ndc = {c.x / cam.orthographic.xmag, c.y / cam.orthographic.ymag};
  } else {
    const double f = 1.0 / std::tan(0.5 * cam.perspective.yfov);
    ndc = {f / cam.perspective.aspectRatio * c.x / -c.z, f * c.y / -c.z};
  }
  return {0.5 * (ndc.x + 1.0) * width, 0.5 * (1.0 - ndc.y) * height};
}

// A world point (centimetres) in pixels through stirrup's render camera: film (u, v) with u right and
// v down, checked against the ray the renderer traces through that film point.
inline glm::dvec2 stirrupPixel(const scene::Camera& cam, glm::dvec3 p, int width, int height) {
  const scene::CameraFrame f(cam, width, height);
  const glm::dvec3 d = p - cam.position;
  double x = glm::dot(d, f.right()), y = glm::dot(d, f.upward());
  double half_h = 0.5 * cam.ortho_height_cm;
  if (cam.projection == scene::Camera::Projection::Perspective) {
    x /= glm::dot(d, f.forward()), y /= glm::dot(d, f.forward());
    half_h = std::tan(0.5 * cam.fov_deg * 3.14159265358979323846 / 180.0);
  }
  const double half_w = half_h * width / height;
  const double u = 0.5 * (x / half_w + 1.0), v = 0.5 * (1.0 - y / half_h);
  const scene::Ray ray = f.ray(u, v);
  const glm::dvec3 off = p - ray.origin;
  EXPECT_LT(glm::length(off - glm::dot(off, ray.direction) * ray.direction), 1e-6 * (1.0 + glm::length(off)))
      << "the inverse of the renderer's ray generation";
  return {u * width, v * height};
}

}  // namespace stirrup::test
