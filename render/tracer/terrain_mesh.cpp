#include "render/tracer/terrain_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace stirrup::render {
namespace {

// The lines outward from `edge` (exclusive) to edge + sign * extent, cells growing from `spacing`.
void growOutward(double edge, double sign, double spacing, const TerrainMeshParams& p, std::vector<double>& out) {
  double cell = spacing, reached = 0.0;
  while (reached < p.extent_cm) {
    cell *= p.growth;
    if (reached < p.mid_reach_cm) cell = std::min(cell, std::max(p.mid_cell_cm, spacing));
    reached = std::min(p.extent_cm, reached + cell);
    out.push_back(edge + sign * reached);
  }
}

}  // namespace

std::vector<double> terrainGridLines(double lo, double hi, double spacing, const TerrainMeshParams& params) {
  if (!(spacing > 0.0) || !(lo <= hi) || !(params.growth > 1.0))
    throw std::invalid_argument("terrainGridLines: needs lo <= hi, spacing > 0 and growth > 1");
  const double first = std::floor(lo / spacing) * spacing, last = std::ceil(hi / spacing) * spacing;
  std::vector<double> below, lines;
  growOutward(first, -1.0, spacing, params, below);
  lines.assign(below.rbegin(), below.rend());
  const long cells = std::max(1L, std::lround((last - first) / spacing));
  for (long i = 0; i <= cells; ++i) lines.push_back(first + double(i) * spacing);
  growOutward(lines.back(), 1.0, spacing, params, lines);
  return lines;
}

TerrainMesh makeTerrainMesh(const rig::Terrain& terrain, const GroundRegion& region, const TerrainMeshParams& params) {
  const double width = std::max(region.x1 - region.x0, 0.0), depth = std::max(region.z1 - region.z0, 0.0);
  double spacing = params.fine_spacing_cm;
  if ((width / spacing + 1.0) * (depth / spacing + 1.0) > params.max_fine_vertices)
    spacing = std::max(spacing, std::sqrt(width * depth / params.max_fine_vertices) * 1.01);
  const std::vector<double> xs = terrainGridLines(region.x0, region.x0 + width, spacing, params);
  const std::vector<double> zs = terrainGridLines(region.z0, region.z0 + depth, spacing, params);
  TerrainMesh mesh;
  mesh.positions.reserve(xs.size() * zs.size());
  mesh.min_height = std::numeric_limits<float>::infinity();
  mesh.max_height = -std::numeric_limits<float>::infinity();
  for (double z : zs) {
    for (double x : xs) {
      const float h = float(terrain.height(x, z));
      mesh.positions.emplace_back(float(x), h, float(z));
      mesh.min_height = std::min(mesh.min_height, h);
      mesh.max_height = std::max(mesh.max_height, h);
    }
  }
  const uint32_t nx = uint32_t(xs.size());
  mesh.indices.reserve((xs.size() - 1) * (zs.size() - 1) * 6);
  for (uint32_t j = 0; j + 1 < zs.size(); ++j) {
    for (uint32_t i = 0; i + 1 < nx; ++i) {
      const uint32_t a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;  // a (x0 z0), b (x1 z0), c (x0 z1), d (x1 z1)
      // The flat ground quad's winding (embree_scene.cpp): (x0 z0) (x0 z1) (x1 z1), (x0 z0) (x1 z1) (x1 z0).
      mesh.indices.insert(mesh.indices.end(), {a, c, d, a, d, b});
    }
  }
  return mesh;
}

}  // namespace stirrup::render
