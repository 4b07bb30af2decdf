// The ground a path crosses (issue 15): flat, rolling hills from a seed, an amplitude and a
// wavelength, or a triangle mesh (rig/motion/terrain_mesh.h, read from glTF by rig/io/gltf_terrain.h). Heights are a pure function of (x, z), cm, so a clip, the renderer and a test all see the
// same ground on any machine, in any frame order.
//
// Hills: 2-D value noise on a square lattice of `wavelength_cm` spacing, blended with the quintic fade
// 6t⁵ − 15t⁴ + 10t³ (Perlin 2002, "Improving noise", SIGGRAPH), so slope and curvature are continuous
// and a horse's pitch over the ground never jumps; `octaves` halve the wavelength and the amplitude
// each, and the sum is scaled so the height stays within ±amplitude_cm.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include <glm/vec3.hpp>

#include "rig/motion/terrain_mesh.h"

namespace stirrup::rig {

struct HillsParams {
  std::uint32_t seed = 1;
  double amplitude_cm = 100;    // the highest hill top (and deepest hollow) from 0
  double wavelength_cm = 4000;  // lattice spacing of the first octave: hills about this far apart
  int octaves = 2;
};

class Terrain {
 public:
  Terrain() = default;  // flat, at height 0
  // Rolling hills. Throws rig::InputError "SOURCE: terrain.FIELD: expected ..., got ..." for an
  // amplitude outside 0-5000 cm, a wavelength outside 100-1 000 000 cm, or octaves outside 1-6.
  static Terrain hills(const HillsParams& params, const std::string& source);
  // A mesh. Off it (or over a hole) the ground is at the mesh's lowest vertex; covers() says where it is.
  static Terrain mesh(std::shared_ptr<const TerrainMesh> mesh);

  bool flat() const { return !hills_ && !mesh_; }
  const TerrainMesh* triangles() const { return mesh_.get(); }  // null unless a mesh
  // Whether (x, z) is on the ground the terrain describes (always, but for a mesh: over a triangle).
  bool covers(double x, double z) const { return !mesh_ || mesh_->at(x, z).has_value(); }
  double height(double x, double z) const;          // cm
  // (d height / dx, d height / dz): the slope, analytic.
  void gradient(double x, double z, double& dx, double& dz) const;
  glm::dvec3 normal(double x, double z) const;       // unit, up

  // The ground as triangles, for a file another tool opens (stirrup bake): a mesh terrain's own
  // triangles; hills sampled on a grid over [lower, upper] (x, z cm) of at most `max_cells` a side,
  // cells of `cell_cm` or larger; nothing for flat ground. Vertices in cm, three indices a triangle.
  void triangulate(glm::dvec2 lower, glm::dvec2 upper, double cell_cm, int max_cells, std::vector<glm::vec3>& vertices,
                   std::vector<std::uint32_t>& indices) const;

 private:
  bool hills_ = false;
  std::shared_ptr<const TerrainMesh> mesh_;
  HillsParams params_;
  double scale_ = 1;  // 1 / the sum of the octaves' amplitudes
};

}  // namespace stirrup::rig
