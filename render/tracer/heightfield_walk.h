// Camera rays against the heightfield's mesh in SIMD lanes, without Embree: each ray walks the grid's
// cells in the order it crosses them and stops at the first cell where it passes from one side of the
// surface to the other (issue 58: the hills' camera stream was the whole of their extra cost, and a
// heightfield's grid is a better index for it than a BVH over its triangles).
//
// Watertight by construction. Along a ray, f(t) = ray height - mesh height is linear on each triangle,
// so the walk needs its value only where the ray enters a cell, crosses the cell's diagonal and leaves
// the cell. Each value is computed once and the value where the ray leaves a cell is the value where it
// enters the next, so the signs form one sequence along the ray: a ray that starts above the mesh and
// ends below it changes sign somewhere, and that is its hit (linear within the triangle's part of the
// ray). No ray slips between two triangles, as rays did through Embree's default test (docs/
// performance.md, "Cracks in the heightfield").
//
// Blocks of kBlockCells x kBlockCells cells are skipped while the ray stays above the block's highest
// vertex (with a margin far above the rounding of a height): most of a grazing ray's run over the hills.
// Where a skipped block is left, the ray is above the next block's edge too, so the fresh value of f
// there has the sign the skipped run had.
//
// Deterministic on every dispatch target: the kernel uses only operations IEEE 754 rounds exactly
// (render/tracer/sample_lanes.h), so the same rays give the same hits on SSE4.2, AVX2 and AVX-512.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/tracer/heightfield_mesh.h"
#include "render/tracer/sample_lanes.h"

namespace stirrup::render {

class HeightfieldWalk {
 public:
  // The side of a block, in cells: a block's ray segment costs one step where its 64 cells would cost
  // about eight; at 4 the blocks skip less of a grazing ray, at 16 fewer rays clear a block at all.
  static constexpr int32_t kBlockCells = 8;
  // How far (cm) above a block's highest vertex a ray must stay to skip it: far above the rounding of
  // a ray's or the mesh's height in floats at a kilometre (about 0.01 cm).
  static constexpr float kSkipMarginCm = 0.1f;

  // The grid of a TerrainMesh (makeTerrainMesh: vertices row by row along X, each cell's triangles
  // (a c d), (a d b) meeting on its diagonal a-d). Throws std::invalid_argument for a grid under 2 x 2
  // vertices, lines not strictly ascending in floats, or 2^24 cells or more.
  explicit HeightfieldWalk(const TerrainMesh& mesh);

  // Where each of the lanes' camera rays first meets the mesh within [t_enter, t_leave] (rays with
  // t_enter > t_leave, and padding, miss), written as Embree writes a quad hit (EmbreeScene::
  // setGroundMesh) so groundHitLanes reads either: geom 0 for a hit (RTC_INVALID_GEOMETRY_ID for a
  // miss), prim the cell (j (nx - 1) + i), u its position across the cell along X, v one less its
  // position along Z, and t_leave the hit's distance. Each array holds lanes.padded entries.
  void trace(CameraLanes& lanes, unsigned* geom, unsigned* prim, float* u, float* v) const;

  // The grid as plain numbers, for the kernel.
  struct View {
    const float* lines = nullptr;    // xs (nx), zs (nz), block xs (bx + 1), block zs (bz + 1)
    const float* heights = nullptr;  // nx * nz, row by row along X
    const float* block_max = nullptr;  // bx * bz, row by row along X: the highest vertex of each block
    const int32_t* x_bucket = nullptr;  // the last line at or before each bucket's start (GridLineIndex)
    const int32_t* z_bucket = nullptr;
    int32_t nx = 0, nz = 0, bx = 0, bz = 0;
    int32_t x_buckets = 0, z_buckets = 0;
    float x_origin = 0.0f, x_inv_bucket = 0.0f, z_origin = 0.0f, z_inv_bucket = 0.0f;
  };
  View view() const;

 private:
  int32_t nx_ = 0, nz_ = 0, bx_ = 0, bz_ = 0;
  std::vector<float> lines_, heights_, block_max_;
  std::vector<int32_t> x_bucket_, z_bucket_;
  float x_origin_ = 0.0f, x_inv_bucket_ = 0.0f, z_origin_ = 0.0f, z_inv_bucket_ = 0.0f;
};

}  // namespace stirrup::render
