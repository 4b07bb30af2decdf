// Camera rays against the heightfield's mesh by rasterizing it, without Embree (issue 58: the hills'
// camera rays were the whole of a terrain frame's extra cost). Every camera ray leaves one point (a
// perspective camera) or runs one way (an orthographic one), so which cell a ray meets first is a
// question of where the cells fall on the screen: each cell is projected once for a batch of samples
// and tested only against the samples in its footprint, where Embree walked a tree of boxes for every
// ray (ten to thirty cells a ray on a grazing view).
//
// The test is the homogeneous edge test: a ray passes inside a triangle when the three edge
// functions E = N . q (q the ray's direction, or its point on the image plane for an orthographic
// camera; N from the edge's two vertices) have one sign. Each edge's N is computed from its two
// vertices in one order (the lower vertex index first) in every cell that shares it, so two triangles
// that share an edge see the same E there with opposite signs: no ray slips between them. The hit's
// distance is then the ray's distance to the triangle's plane.
//
// Deterministic: each sample's hit is the nearest over the cells whose footprint holds it, visited in
// one global order (ties to the first), whatever batch, tile or thread the sample falls in.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/tracer/heightfield_mesh.h"
#include "render/tracer/sample_lanes.h"

namespace stirrup::render {

// What the SIMD kernels read of the camera and of one cell (heightfield_raster.cpp).
struct RasterCamera {
  bool perspective = true;
  glm::vec3 eye{0.0f}, forward{0.0f}, right{0.0f}, up{0.0f};
};
struct RasterCell {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0, near = 0;  // its box on the image plane; the nearest a ray meets it
  int32_t index = 0;
  float n_ab[3] = {}, n_ac[3] = {}, n_bd[3] = {}, n_cd[3] = {}, n_ad[3] = {};  // its edges' functions
  float n1[3] = {}, n2[3] = {};  // its triangles' normals, and their planes' offsets n . a
  float h1 = 0, h2 = 0;
};

// A row of up to 16 cells of a block projected in lanes (RasterRowLanes): the cells that show, and
// those that cross a perspective camera's near plane (worked out one by one).
struct RasterRow {
  const float* x = nullptr;  // the grid's vertices as arrays (padded: a row's reads may run past the end)
  const float* y = nullptr;
  const float* z = nullptr;
  std::size_t first_vertex = 0, row_vertices = 0;  // the row's first cell's corner a, and nx
  int32_t first_cell = 0, cells = 0;               // its index, and how many
  float screen_x0 = 0, screen_y0 = 0, screen_x1 = 0, screen_y1 = 0;
};
struct RasterRowOut {
  int32_t shown = 0, crossing = 0;
  // 16 a row at most, and room for a whole vector's store past the last.
  int32_t index[32] = {}, crossing_index[32] = {};
  float x0[32] = {}, y0[32] = {}, x1[32] = {}, y1[32] = {}, near[32] = {};
};

// Up to 16 cells' edge functions and planes, worked out in lanes (RasterSetupLanes): slot m of each.
struct RasterCellSetup {
  int32_t count = 0;
  int32_t vertex[32] = {};  // each cell's corner a (padded)
  float n[21][32] = {};      // n_ab, n_ac, n_bd, n_cd, n_ad, n1, n2, three components each
  float h1[32] = {}, h2[32] = {};
};

class HeightfieldRaster {
 public:
  // The side of a block, in cells: the unit a frame culls to the screen and a batch culls to its own
  // footprint. At 16 a frame of the largest scene's grid (656 x 293 lines) has some 750 blocks.
  static constexpr int32_t kBlockCells = 16;

  // The grid of a TerrainMesh (makeTerrainMesh: vertices row by row along X, each cell's triangles
  // (a c d), (a d b) meeting on its diagonal a-d). Throws std::invalid_argument for a grid under 2 x 2
  // vertices or 2^31 cells or more.
  explicit HeightfieldRaster(const TerrainMesh& mesh);

  // One frame's camera against the mesh: the cells on screen and within sight, each with its box on
  // the image plane, binned by the screen's squares of kBinPixels. Made once a frame (prepare), read by
  // every batch.
  static constexpr int kBinPixels = 16;
  // Measured (docs/performance.md): a cell met by a batch costs about as much as two of Embree's rays.
  static constexpr double kMaxCellsAPixel = 0.5;
  struct Frame {
    struct Cell {
      int32_t index = 0;                     // j (nx - 1) + i
      float x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // its box on the image plane
      float near = 0;                        // no ray meets it nearer than this
      float block_near = 0;                  // nor any cell of its block
    };
    std::vector<Cell> cells;                 // by block, nearest block first; by index within a block
    std::vector<uint32_t> bin_start, bin_cells;  // bin b holds cells[bin_cells[bin_start[b] .. bin_start[b + 1])]
    int bins_x = 0, bins_y = 0;
    std::vector<uint8_t> bin_embree;         // bins a block of cells too small to raster meets
    // A block with more cells a pixel of its box on screen is left to Embree (set before prepare).
    double max_cells_a_pixel = kMaxCellsAPixel;
    bool perspective = true;
    glm::vec3 eye{0.0f}, forward{0.0f}, right{0.0f}, up{0.0f};
    float pixel_dx = 1, pixel_dy = 1, half_width = 0, half_height = 0;
  };
  Frame prepare(const LaneConstants& k, int width, int height,
                double max_cells_a_pixel = kMaxCellsAPixel) const;

  // Per-batch arrays, kept by the caller between batches (padded as the lanes).
  struct Scratch {
    std::vector<float> sx, sy;      // each sample's point on the image plane (NaN: padding)
    std::vector<float> qx, qy, qz;  // what its edge functions read
    std::vector<float> ox, oy, oz;  // its ray's origin less the eye
    std::vector<float> best;        // the nearest hit so far (starts at t_leave)
    std::vector<int32_t> cell;      // its cell (-1: none), and which triangle
    std::vector<int32_t> second;
    std::vector<uint32_t> candidates, merged;  // the cells of the bins the batch meets
    RasterCellSetup setup;                     // the next cells to test, set up in lanes
  };

  // Where each camera ray of a batch first meets the mesh within [t_enter, t_leave], written as Embree
  // writes a quad hit (EmbreeScene::setGroundMesh) so groundHitLanes reads either: geom 0 for a hit
  // (RTC_INVALID_GEOMETRY_ID for a miss), prim the cell (j (nx - 1) + i), u its position across the
  // cell along X, v one less its position along Z, and t_leave the hit's distance. The batch is pixels
  // [first, first + count) of the tile at (x0, y0), tile_width wide, row by row, spp samples a pixel,
  // as Integrator::cameraPass lays them out. Each output array holds lanes.padded entries.
  //
  // Returns false, with nothing written, where the batch's bins meet a block left to Embree (one with
  // more than Frame::max_cells_a_pixel cells a pixel on screen: cells that small, a distant grid in a
  // wide view, each cost a setup for a sample or two, and Embree's tree of them costs less).
  bool trace(const Frame& frame, int x0, int tile_width, int y0, int first, int count, int spp, CameraLanes& lanes,
             Scratch& scratch, unsigned* geom, unsigned* prim, float* u, float* v) const;

 private:
  int32_t nx_ = 0, nz_ = 0, bx_ = 0, bz_ = 0;
  std::vector<float> xs_, zs_;
  std::vector<glm::vec3> positions_;
  std::vector<float> vx_, vy_, vz_;  // the same as arrays, padded
  std::vector<float> block_low_, block_high_;  // the lowest and highest vertex of each block
};

}  // namespace stirrup::render
