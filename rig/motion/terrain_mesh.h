// Ground given as triangles (issue 15: "a terrain ... or a glTF mesh file"): the height of the highest
// surface over a point of the ground plane, found through a uniform grid over the mesh's footprint so
// a lookup touches a handful of triangles whatever the mesh's size. Pure and immutable once built.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace stirrup::rig {

class TerrainMesh {
 public:
  // Vertices in cm (world, Y up) and three indices per triangle. Triangles standing on edge (no area
  // seen from above) carry no ground and are skipped. Throws rig::InputError "SOURCE: ..." for a
  // non-finite vertex, an index past the vertices, or no triangle with area seen from above.
  TerrainMesh(std::vector<glm::dvec3> vertices, std::vector<std::uint32_t> indices, const std::string& source);

  struct Hit {
    double height_cm = 0;
    glm::dvec3 normal{0, 1, 0};  // the triangle's, unit, facing up
  };
  // The highest triangle over (x, z), or nothing off the mesh (or over a hole in it).
  std::optional<Hit> at(double x, double z) const;

  glm::dvec2 lower() const { return lower_; }  // the footprint's bounds, (x, z) cm
  glm::dvec2 upper() const { return upper_; }
  double lowest() const { return lowest_; }    // the lowest vertex, cm
  std::size_t triangleCount() const { return triangles_.size(); }
  const std::vector<glm::dvec3>& vertices() const { return vertices_; }
  // Three vertex indices per ground triangle (the skipped ones left out).
  std::vector<std::uint32_t> indices() const;

 private:
  struct Triangle {
    std::uint32_t v[3];
  };
  std::vector<glm::dvec3> vertices_;
  std::vector<Triangle> triangles_;
  glm::dvec2 lower_{0.0}, upper_{0.0};
  double lowest_ = 0;
  // The grid: cells_x_ by cells_z_ cells of cell_cm, each listing the triangles whose footprint box
  // overlaps it (compressed rows: cell c's triangles are cell_triangles_[cell_start_[c] .. [c + 1])).
  double cell_cm_ = 1;
  int cells_x_ = 1, cells_z_ = 1;
  std::vector<std::uint32_t> cell_start_, cell_triangles_;
};

}  // namespace stirrup::rig
