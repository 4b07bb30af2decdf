// The heightfield rasterized for the camera rays (render/tracer/heightfield_raster.cpp), against
// Embree's watertight test on the same mesh: the same rays meet it, at the same distances and cells;
// no ray slips between two triangles; and a sample's hit is its own, whatever batch it is traced in.
#include "render/tracer/heightfield_raster.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <random>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "render/tracer/embree_scene.h"
#include "render/tracer/heightfield_mesh.h"
#include "tests/render/tracer/steep_hills.h"

namespace stirrup::render {
namespace {

constexpr int kWidth = 160, kHeight = 90, kTile = HeightfieldRaster::kBinPixels;

// A camera at `eye` looking at `target` as the integrator's lanes see it (CameraFrame::laneView).
LaneConstants camera(const TerrainMesh& mesh, glm::vec3 eye, glm::vec3 target, bool perspective) {
  LaneConstants k;
  k.perspective = perspective;
  k.position = eye;
  k.forward = glm::normalize(target - eye);
  k.right = glm::normalize(glm::cross(k.forward, glm::vec3(0.0f, 1.0f, 0.0f)));
  k.up = glm::cross(k.right, k.forward);
  // 50 degrees across in perspective; 60 m across orthographic.
  k.half_width = perspective ? std::tan(0.5f * 50.0f * 3.14159265f / 180.0f) : 3000.0f;
  k.half_height = k.half_width * float(kHeight) / float(kWidth);
  k.pixel_dx = 2.0f * k.half_width / float(kWidth), k.pixel_dy = 2.0f * k.half_height / float(kHeight);
  k.t_visible = 1e6f;
  k.slab_low = mesh.min_height - 1.0f, k.slab_high = mesh.max_height + 1.0f;
  return k;
}

struct Hit {
  bool hit = false;
  unsigned cell = 0;
  float t = 0.0f;
};

// Every sample of every tile, `spp` a pixel at random points within it, traced by the raster in
// batches of `batch_pixels` pixels; and the same rays in Embree's robust test.
struct Traced {
  std::vector<Hit> raster, embree;
};

Traced traceImage(const TerrainMesh& mesh, const LaneConstants& k, int spp, int batch_pixels, uint32_t seed) {
  const HeightfieldRaster raster(mesh);
  // The raster itself, wherever.
  const HeightfieldRaster::Frame frame = raster.prepare(k, kWidth, kHeight, std::numeric_limits<double>::infinity());
  EmbreeScene scene;
  scene.setGroundMesh(mesh.positions, mesh.indices);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 0.999999f);
  Traced out;
  CameraLanes lanes;
  HeightfieldRaster::Scratch scratch;
  std::vector<unsigned> geom, prim;
  std::vector<float> u, v;
  for (int y0 = 0; y0 < kHeight; y0 += kTile) {
    for (int x0 = 0; x0 < kWidth; x0 += kTile) {
      const int tw = std::min(kTile, kWidth - x0), th = std::min(kTile, kHeight - y0);
      for (int first = 0; first < tw * th; first += batch_pixels) {
        const int count = std::min(batch_pixels, tw * th - first);
        lanes.resize(std::size_t(count * spp));
        for (int p = 0; p < count; ++p) {
          for (int s = 0; s < spp; ++s) {
            const std::size_t j = std::size_t(p * spp + s);
            lanes.cx[j] = float(x0 + (first + p) % tw) + 0.5f, lanes.cy[j] = float(y0 + (first + p) / tw) + 0.5f;
            lanes.ux[j] = unit(rng), lanes.uy[j] = unit(rng);
          }
        }
        cameraRayLanes(k, lanes, false);
        const std::vector<float> t_enter(lanes.t_enter.begin(), lanes.t_enter.end());
        const std::vector<float> t_leave(lanes.t_leave.begin(), lanes.t_leave.end());
        geom.assign(lanes.padded, 0u), prim.assign(lanes.padded, 0u), u.assign(lanes.padded, 0.0f), v.assign(lanes.padded, 0.0f);
        EXPECT_TRUE(raster.trace(frame, x0, tw, y0, first, count, spp, lanes, scratch, geom.data(), prim.data(),
                                 u.data(), v.data()));
        for (std::size_t j = 0; j < lanes.size; ++j) {
          out.raster.push_back({geom[j] == 0u, prim[j], lanes.t_leave[j]});
          RTCRayHit rh{};
          rh.ray.org_x = lanes.ox[j], rh.ray.org_y = lanes.oy[j], rh.ray.org_z = lanes.oz[j];
          rh.ray.dir_x = lanes.dx[j], rh.ray.dir_y = lanes.dy[j], rh.ray.dir_z = lanes.dz[j];
          rh.ray.tnear = t_enter[j], rh.ray.tfar = t_leave[j], rh.ray.mask = 0xffffffffu;
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
          RTCIntersectContext context;
          rtcInitIntersectContext(&context);
          if (t_enter[j] <= t_leave[j]) rtcIntersect1(scene.ground(), &context, &rh);
          out.embree.push_back({rh.hit.geomID != RTC_INVALID_GEOMETRY_ID, rh.hit.primID, rh.ray.tfar});
        }
      }
    }
  }
  return out;
}

void expectAsEmbree(const Traced& traced, const char* view) {
  ASSERT_EQ(traced.raster.size(), traced.embree.size());
  std::size_t hits = 0, disagree = 0, other_cell = 0;
  for (std::size_t r = 0; r < traced.raster.size(); ++r) {
    const Hit &a = traced.raster[r], &b = traced.embree[r];
    hits += b.hit;
    if (a.hit != b.hit) {
      ++disagree;
      continue;
    }
    if (!a.hit) continue;
    if (std::abs(a.t - b.t) > 1e-4f * b.t + 0.01f) {
      ++disagree;  // one grazed a hill's rim that the other passed, and met the ground beyond it
      continue;
    }
    other_cell += a.cell != b.cell;
  }
  EXPECT_GT(hits, traced.raster.size() / 4) << view;  // the views see mostly ground
  // A ray within the rounding of a hill's rim may pass it in one test and graze it in the other: rare.
  // One within the rounding of an edge may take the cell on the other side of it (at the same distance).
  EXPECT_LE(disagree, traced.raster.size() / 5000) << view << ": " << disagree << " of " << traced.raster.size();
  EXPECT_LE(other_cell, hits / 100) << view << ": " << other_cell << " of " << hits;
}

TEST(HeightfieldRaster, MeetsTheMeshWhereEmbreeDoes) {
  const TerrainMesh mesh = makeTerrainMesh(test::rollingHillsTerrain(), {0.0, 0.0, 4000.0, 4000.0});
  // Low and far (a perspective view's grazing rays over many hills), high and steep, and orthographic
  // side and top views.
  expectAsEmbree(traceImage(mesh, camera(mesh, {-1500.0f, 400.0f, -900.0f}, {2000.0f, 0.0f, 2000.0f}, true), 4, 256, 1),
                 "low perspective");
  expectAsEmbree(traceImage(mesh, camera(mesh, {2000.0f, 3000.0f, -500.0f}, {2000.0f, 0.0f, 1500.0f}, true), 1, 256, 2),
                 "high perspective");
  expectAsEmbree(traceImage(mesh, camera(mesh, {2000.0f, 1500.0f, -3000.0f}, {2000.0f, 0.0f, 0.0f}, false), 4, 256, 3),
                 "orthographic side");
  expectAsEmbree(traceImage(mesh, camera(mesh, {2000.0f, 5000.0f, 2000.0f}, {2000.1f, 0.0f, 2001.0f}, false), 1, 256, 4),
                 "orthographic top");
}

TEST(HeightfieldRaster, MeetsSteepHillsWhereEmbreeDoes) {
  const TerrainMesh mesh = makeTerrainMesh(test::steepHillsTerrain(), {0.0, 0.0, 3000.0, 3000.0});
  expectAsEmbree(traceImage(mesh, camera(mesh, {-800.0f, 700.0f, 1500.0f}, {1500.0f, 0.0f, 1500.0f}, true), 4, 256, 5),
                 "steep hills");
}

// A sample's hit is its own: the same rays traced a tile at a time and a few pixels at a time give
// the same hits, bit for bit.
TEST(HeightfieldRaster, AHitIsTheSameWhateverTheBatch) {
  const TerrainMesh mesh = makeTerrainMesh(test::rollingHillsTerrain(), {0.0, 0.0, 4000.0, 4000.0});
  const LaneConstants k = camera(mesh, {-1500.0f, 400.0f, -900.0f}, {2000.0f, 0.0f, 2000.0f}, true);
  const Traced whole = traceImage(mesh, k, 2, 256, 9), pieces = traceImage(mesh, k, 2, 7, 9);
  ASSERT_EQ(whole.raster.size(), pieces.raster.size());
  for (std::size_t r = 0; r < whole.raster.size(); ++r) {
    ASSERT_EQ(whole.raster[r].hit, pieces.raster[r].hit) << r;
    if (!whole.raster[r].hit) continue;
    ASSERT_EQ(whole.raster[r].cell, pieces.raster[r].cell) << r;
    ASSERT_EQ(whole.raster[r].t, pieces.raster[r].t) << r;
  }
}

// Watertight: rays aimed at the cells' shared edges (sides and diagonals) and at their vertices, where
// six triangles meet, all meet the mesh (Embree's robust test lets about 1.4% of the vertex rays
// through: embree_scene_test.cpp).
TEST(HeightfieldRaster, RaysAtSharedEdgesAndVerticesMeetIt) {
  const TerrainMesh mesh = makeTerrainMesh(test::rollingHillsTerrain(), {0.0, 0.0, 4000.0, 4000.0});
  const LaneConstants k = camera(mesh, {-1500.0f, 400.0f, -900.0f}, {2000.0f, 0.0f, 2000.0f}, true);
  const HeightfieldRaster raster(mesh);
  const HeightfieldRaster::Frame frame = raster.prepare(k, kWidth, kHeight, std::numeric_limits<double>::infinity());
  const std::size_t nx = mesh.xs.size();
  CameraLanes lanes;
  HeightfieldRaster::Scratch scratch;
  std::vector<unsigned> geom(CameraLanes::kPad), prim(CameraLanes::kPad);
  std::vector<float> u(CameraLanes::kPad), v(CameraLanes::kPad);
  std::size_t aimed = 0, missed = 0;
  // One ray a batch, in the pixel its direction falls in.
  auto aim = [&](const glm::vec3& target) {
    const glm::vec3 d = glm::normalize(target - k.position);
    const float w = glm::dot(d, k.forward);
    const float px = (glm::dot(d, k.right) / w + k.half_width) / k.pixel_dx;
    const float py = (k.half_height - glm::dot(d, k.up) / w) / k.pixel_dy;
    const int x = int(std::floor(px)), y = int(std::floor(py));
    if (x < 0 || y < 0 || x >= kWidth || y >= kHeight) return;
    lanes.resize(1);
    lanes.ox[0] = k.position.x, lanes.oy[0] = k.position.y, lanes.oz[0] = k.position.z;
    lanes.dx[0] = d.x, lanes.dy[0] = d.y, lanes.dz[0] = d.z;
    lanes.t_enter[0] = 0.0f, lanes.t_leave[0] = 1e9f;
    EXPECT_TRUE(raster.trace(frame, x, 1, y, 0, 1, 1, lanes, scratch, geom.data(), prim.data(), u.data(), v.data()));
    ++aimed;
    missed += geom[0] != 0u;
  };
  for (std::size_t j = 0; j + 1 < mesh.zs.size(); j += 3) {
    for (std::size_t i = 0; i + 1 < nx; i += 3) {
      if (!(mesh.xs[i] >= 0.0 && mesh.xs[i + 1] <= 4000.0 && mesh.zs[j] >= 0.0 && mesh.zs[j + 1] <= 4000.0)) continue;
      const glm::vec3 a = mesh.positions[j * nx + i], b = mesh.positions[j * nx + i + 1];
      const glm::vec3 c = mesh.positions[(j + 1) * nx + i], d = mesh.positions[(j + 1) * nx + i + 1];
      for (const glm::vec3& target : {0.5f * (a + d), 0.25f * a + 0.75f * d, 0.5f * (a + b), 0.5f * (a + c), a}) aim(target);
    }
  }
  ASSERT_GT(aimed, 5000u);
  EXPECT_EQ(missed, 0u) << "of " << aimed << " rays at shared edges and vertices";
}

// Where the cells are many to a pixel (a distant grid), the raster leaves the batch to Embree.
TEST(HeightfieldRaster, LeavesCrowdedBinsToEmbree) {
  const TerrainMesh mesh = makeTerrainMesh(test::rollingHillsTerrain(), {0.0, 0.0, 4000.0, 4000.0});
  const LaneConstants k = camera(mesh, {2000.0f, 30000.0f, -40000.0f}, {2000.0f, 0.0f, 2000.0f}, true);  // 50 m up, 420 m off
  const HeightfieldRaster raster(mesh);
  const HeightfieldRaster::Frame frame = raster.prepare(k, kWidth, kHeight);
  CameraLanes lanes;
  lanes.resize(16);
  for (int p = 0; p < 16; ++p) lanes.cx[std::size_t(p)] = float(80 + p) + 0.5f, lanes.cy[std::size_t(p)] = 45.5f, lanes.ux[std::size_t(p)] = lanes.uy[std::size_t(p)] = 0.5f;
  cameraRayLanes(k, lanes, false);
  HeightfieldRaster::Scratch scratch;
  std::vector<unsigned> geom(16, 7u), prim(16);
  std::vector<float> u(16), v(16);
  EXPECT_FALSE(raster.trace(frame, 80, 16, 45, 0, 16, 1, lanes, scratch, geom.data(), prim.data(), u.data(), v.data()));
  EXPECT_EQ(geom[0], 7u);  // nothing written
  const HeightfieldRaster::Frame everywhere = raster.prepare(k, kWidth, kHeight, std::numeric_limits<double>::infinity());
  EXPECT_TRUE(raster.trace(everywhere, 80, 16, 45, 0, 16, 1, lanes, scratch, geom.data(), prim.data(), u.data(), v.data()));
  EXPECT_EQ(geom[0], 0u);
}

TEST(HeightfieldRaster, RejectsAGridTooSmall) {
  TerrainMesh mesh;
  mesh.xs = {0.0};
  mesh.zs = {0.0, 1.0};
  mesh.positions = {glm::vec3(0.0f), glm::vec3(0.0f)};
  EXPECT_THROW(HeightfieldRaster{mesh}, std::invalid_argument);
}

}  // namespace
}  // namespace stirrup::render
