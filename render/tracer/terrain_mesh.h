// The rolling-hills ground (rig::Terrain) as a heightfield triangle mesh for the renderer (issue 15).
//
// One tensor-product grid: its lines along X and along Z are `fine_spacing_cm` apart over the region the
// horse crosses (the track plus a margin), then grow outward cell by cell to `extent_cm` beyond it, so the
// near ground is exact to a fraction of a centimetre (a hoof visibly stands on it) while the far ground
// costs few triangles. Being one grid, the fine and coarse parts share their vertices: no cracks, no
// T-junctions. Vertices lie exactly on Terrain::height; between them the mesh is linear, off the surface
// by at most about |height''| spacing² / 8 (0.03 cm for 80 cm hills 30 m apart at 25 cm).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "rig/motion/terrain.h"

namespace stirrup::render {

// A box of the ground plane, cm.
struct GroundRegion {
  double x0 = 0.0, z0 = 0.0, x1 = 0.0, z1 = 0.0;
};

struct TerrainMeshParams {
  double fine_spacing_cm = 25.0;       // grid spacing over the region
  // The fine grid's vertex budget: a region too large for it (a path kilometres long) gets a wider
  // spacing, sqrt(area / budget), rather than gigabytes of mesh. 2 M vertices: ~50 MB with the BVH.
  double max_fine_vertices = 2.0e6;
  double growth = 1.25;                // each cell outside the region this much wider than the last
  double mid_cell_cm = 400.0;          // ... up to this width while within mid_reach_cm of the region
  double mid_reach_cm = 20000.0;       // (so hills 200 m off still read), then growing freely
  double extent_cm = 100000.0;         // how far beyond the region the ground goes (the flat plane's 1 km)
};

struct TerrainMesh {
  std::vector<glm::vec3> positions;    // on Terrain::height
  std::vector<uint32_t> indices;       // three per triangle, counter-clockwise seen from above
  float min_height = 0.0f, max_height = 0.0f;
};

// Grid line coordinates along one axis: fine over [lo, hi] (on multiples of the spacing, so the grid
// does not shift with the region), then growing out to lo - extent and hi + extent. Ascending.
std::vector<double> terrainGridLines(double lo, double hi, double spacing, const TerrainMeshParams& params);

// The mesh of `terrain` over `region` (fine) and around it (coarse).
TerrainMesh makeTerrainMesh(const rig::Terrain& terrain, const GroundRegion& region,
                            const TerrainMeshParams& params = {});

}  // namespace stirrup::render
