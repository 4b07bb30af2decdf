// The rolling-hills ground (rig::Terrain) as a heightfield triangle mesh for the renderer (issue 15).
//
// One tensor-product grid: its lines along X and along Z are `fine_spacing_cm` apart over the region the
// horse crosses (the track plus a margin), then grow outward cell by cell to `extent_cm` beyond it, so the
// near ground is exact to a fraction of a centimetre (a hoof visibly stands on it) while the far ground
// costs few triangles. Being one grid, the fine and coarse parts share their vertices: no cracks, no
// T-junctions. Vertices lie exactly on Terrain::height; between them the mesh is linear, off the surface
// by at most about |height''| spacing² / 8 (0.03 cm for 80 cm hills 30 m apart at 25 cm).
#pragma once

#include <cstddef>
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

// The index of the cell of a sorted list of grid lines holding a coordinate, in constant time: a table of
// buckets no wider than the narrowest cell, each naming the last line at or before its start.
class GridLineIndex {
 public:
  GridLineIndex() = default;
  explicit GridLineIndex(const std::vector<double>& lines);
  // The last line at or before v, at most lines.size() - 2 (so [i, i + 1] is a cell), for v within
  // [lines.front(), lines.back()]: what std::upper_bound - 1 gives, capped.
  std::size_t cell(const std::vector<double>& lines, double v) const;
  bool empty() const { return first_.empty(); }

 private:
  double origin_ = 0.0, inv_bucket_ = 0.0;
  std::vector<uint32_t> first_;
};

struct TerrainMesh {
  std::vector<glm::vec3> positions;    // on Terrain::height, row by row along X (xs.size() a row)
  // Terrain::normal at each vertex. The renderer shades a ground hit with these interpolated across the
  // hit triangle (by Embree's barycentrics), which costs a few multiplies where evaluating the terrain's
  // noise at every hit cost more than tracing it; within a 25 cm cell the two differ by far less than
  // a degree.
  std::vector<glm::vec3> normals;
  std::vector<uint32_t> indices;       // three per triangle, counter-clockwise seen from above
  std::vector<double> xs, zs;          // the grid lines (terrainGridLines), ascending
  GridLineIndex x_index, z_index;      // cells of xs and zs by coordinate (binary search when empty)
  float min_height = 0.0f, max_height = 0.0f;

  // The mesh's own height at (x, z): linear on the triangle there, as a ray tracing the mesh meets it
  // (not Terrain::height, which it only matches at the vertices). -infinity off the mesh.
  double heightAt(double x, double z) const;
  // The steepest slope (|gradient|, rise over run) of any triangle of cell (i, j), the cell between
  // lines xs[i], xs[i + 1] and zs[j], zs[j + 1].
  double cellSlope(std::size_t i, std::size_t j) const;
};

// Grid line coordinates along one axis: fine over [lo, hi] (on multiples of the spacing, so the grid
// does not shift with the region), then growing out to lo - extent and hi + extent. Ascending.
std::vector<double> terrainGridLines(double lo, double hi, double spacing, const TerrainMeshParams& params);

// The mesh of `terrain` over `region` (fine) and around it (coarse). Rows are evaluated in parallel
// (each vertex on its own: the same mesh at every thread count).
TerrainMesh makeTerrainMesh(const rig::Terrain& terrain, const GroundRegion& region,
                            const TerrainMeshParams& params = {});

struct SunHorizonParams {
  double texel_cm = 25.0;         // the horizon map's spacing over the region (and of its sweep lines along the sun)
  double near_cm = 200.0;         // the near field's run (s0 below)
  double margin_cm = 5000.0;      // ... and how far beyond the region it reaches (the ground the views see near)
  double max_texels = 4.0e6;      // a larger region gets wider texels (16 MB of floats at most)
};

// Where the hills certainly leave the sun open: a "horizon toward the sun" map of a heightfield mesh,
// computed once a shot for one sun, so the many ground points a frame shades need no ray against the
// hills to know they are lit, and only the few near a hill's shadow's edge are traced.
//
// For each texel p of a grid over the region (plus a margin) it keeps a height `clear(p)`: any point q
// within the texel that is on or above the mesh and higher than clear(p) sees the whole sun disc past
// the mesh. Proof sketch, with G the mesh's steepest slope, e' the sun's elevation less its angular
// radius (every ray of the disc rises at least tan e' per unit run) and rho the texel's half-diagonal:
//  - near field (run s < s0): no triangle within s0 + rho of p rises faster than R(p) along any disc
//    ray's ground track (its gradient along the sun's azimuth plus its steepness times the track's
//    turn, below), so from a point on or above the mesh a ray rising tan e' > R(p) stays above it;
//  - far field (s >= s0): a disc ray's ground track turns from the sun's azimuth by at most phi
//    (sin phi = sin r / cos e), so at run s it is within s * chord(phi) of the axis's track and the mesh
//    there is at most G s chord(phi) higher; q is within rho of p, at most G rho more. So q is open
//    when q.y > max over s >= s0 of [mesh(p + s a) - s (tan e' - G chord(phi))] + G rho, the maximum
//    taken every half texel and raised by the most the function can rise between two samples.
// Past the map, or where the near field is too steep, nothing is known (the caller traces the rays).
// When even the steepest triangle rises slower than tan e', every point on or above the mesh is open,
// however far from the origin (the map's slack limit is the texels').
class SunHorizon {
 public:
  // `toward_sun` need not be unit; `angular_radius_rad` is the sun disc's (RenderSettings).
  SunHorizon(const TerrainMesh& mesh, const glm::dvec3& toward_sun, double angular_radius_rad,
             const GroundRegion& region, const SunHorizonParams& params = {});

  // True when no ray of the sun's disc from a point within `slack` (cm, in every axis) of `p` can meet
  // the mesh, for points on or above the mesh. `above_mesh_known`: p is known to be on or above the
  // mesh (a ground hit); else p is checked against heightAt.
  bool open(const glm::vec3& p, float slack, bool above_mesh_known) const;
  // open(p, slack, false) for a caller that has the mesh's height under p already (heightAt(p.x, p.z)
  // of the mesh this map was made for): one lookup of the mesh fewer.
  bool openAbove(const glm::vec3& p, float slack, double mesh_height) const;
  bool everywhereOpen() const { return everywhere_open_; }
  // The map as plain numbers, for the same test in SIMD lanes on ground points (on the mesh), in floats
  // (render/tracer/sample_lanes.cpp): p is open when everywhere_open (max_slack is then infinite), or
  // when its slack is at most max_slack, (p.x - x0) inv_texel and (p.z - z0) inv_texel fall in the map
  // and p.y less its slack and height_margin is above that texel's clear height. max_slack and
  // height_margin leave room for the floats' rounding (a texel by a hundredth of a centimetre off, a
  // height by its last bits), which the map's horizontal slack and height epsilon cover.
  struct LaneView {
    const float* clear = nullptr;  // nx * nz heights, row by row along x; null: nothing known
    bool everywhere_open = false;
    float x0 = 0.0f, z0 = 0.0f, inv_texel = 0.0f;
    int32_t nx = 0, nz = 0;
    float max_slack = 0.0f, height_margin = 0.0f;
  };
  LaneView laneView() const;
  double steepestSlope() const { return steepest_; }
  // The map's size (0 x 0 when everywhere open or the sun is too low to tell anything).
  std::size_t width() const { return nx_; }
  std::size_t depth() const { return nz_; }

 private:
  bool openOnMesh(const glm::vec3& p, float slack) const;  // open() once p is known on or above the mesh
  // Whether a point of this slack can be answered: any where the sun is open everywhere (only the map's
  // texels assume a slack under a centimetre), else within 300 m or so of the origin.
  bool answers(float slack) const;

  const TerrainMesh* mesh_;
  bool everywhere_open_ = false;
  double steepest_ = 0.0, tan_low_ = 0.0;
  double x0_ = 0.0, z0_ = 0.0, texel_ = 1.0, rho_ = 0.0;
  std::size_t nx_ = 0, nz_ = 0;
  std::vector<float> clear_;  // per texel: the height above which the sun is open (+infinity: unknown)
};

}  // namespace stirrup::render
