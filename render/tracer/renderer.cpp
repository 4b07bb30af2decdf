#include "render/tracer/renderer.h"

#include <algorithm>
#include <chrono>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#define STIRRUP_HAVE_MXCSR 1
#endif

#include "render/tracer/integrator.h"
#include "render/tracer/stopwatch.h"

namespace stirrup::render {
namespace {

constexpr int kTileSize = 16;

// Flush denormals to zero while a tile is traced (Embree's advice for speed), restoring the thread's
// previous mode afterwards: TBB workers also run other people's code. Every tile sets the same mode,
// so results do not depend on which thread traced them.
class DenormalsAreZero {
 public:
#ifdef STIRRUP_HAVE_MXCSR
  DenormalsAreZero() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040u); }  // FTZ | DAZ
  ~DenormalsAreZero() { _mm_setcsr(saved_); }

 private:
  unsigned saved_;
#endif
};

void validate(const RenderSettings& s) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("render settings: ") + what);
  };
  require(s.width > 0 && s.height > 0, "width and height must be >= 1");
  require(s.samples_per_pixel > 0, "samples_per_pixel must be >= 1");
  require(s.light_samples > 0, "light_samples must be >= 1");
  require(s.ao_samples > 0, "ao_samples must be >= 1");
  require(s.threads >= 0, "threads must be >= 0 (0 = all cores)");
  require(glm::length(s.sun_direction) > 0.0, "sun_direction must not be zero");
  require(s.sun_angular_radius_deg >= 0.0 && s.sun_angular_radius_deg < 90.0, "sun_angular_radius_deg must be in [0, 90)");
  require(s.ground_square_cm > 0.0f, "ground_square_cm must be > 0");
  require(s.ao_distance_cm > 0.0f, "ao_distance_cm must be > 0");
  require(s.haze.visibility_cm > 0.0f, "haze.visibility_cm must be > 0");
  require(s.haze.ortho_depth_cm > 0.0f, "haze.ortho_depth_cm must be > 0");
}

}  // namespace

namespace {

// Per thread: the integrator's batch buffers and one tile's results, reused from tile to tile and
// from frame to frame (they grow on a thread's first tile and are not allocated again).
struct TileBuffers {
  TileScratch scratch;
  std::vector<PixelResult> results;
};

}  // namespace

struct Renderer::State {
  // Embree's device, its first (empty) commit and the ground's BVH are made on the renderer's threads:
  // a commit runs TBB tasks in the arena it is called from, and the caller's arena is not the
  // renderer's to use (a renderer asked for one thread keeps to it).
  explicit State(const RenderSettings& s) : arena(s.threads > 0 ? s.threads : tbb::task_arena::automatic) {
    arena.execute([&] {
      scene.emplace(s.bvh_update, s.threads);
      scene->setGround(s.ground_half_extent_cm);
    });
  }

  tbb::task_arena arena;
  std::optional<EmbreeScene> scene;  // always set: made in the arena
  std::vector<std::unique_ptr<ShadingMesh>> meshes;  // by handle
  std::vector<unsigned> geometry_of_mesh;             // by handle
  std::vector<const ShadingMesh*> by_geometry;        // by geomID in the character scene
  std::shared_ptr<const rig::Terrain> terrain;        // null: the flat plane
  float ground_floor = 0.0f;                          // the lowest ground height
  std::unique_ptr<const TerrainMesh> ground_mesh;     // the terrain's heightfield, as traced
  std::unique_ptr<const SunHorizon> hills;            // where its hills certainly leave the sun open
  tbb::enumerable_thread_specific<TileBuffers> tile_buffers;
};

Renderer::Renderer(const RenderSettings& settings) : settings_(settings) {
  validate(settings_);
  state_ = std::make_unique<State>(settings_);
}

Renderer::~Renderer() = default;

void Renderer::setTerrain(std::shared_ptr<const rig::Terrain> terrain, const GroundRegion& region,
                          const TerrainMeshParams& params) {
  if (!terrain || terrain->flat()) return;
  std::unique_ptr<const TerrainMesh> mesh;
  // The sun is the renderer's for its whole life, so its horizon over the hills is worked out once too.
  const double sun_radius = std::max(0.0, settings_.sun_angular_radius_deg) * std::numbers::pi / 180.0;
  state_->arena.execute([&] {  // on the renderer's threads, as every build of the shot
    mesh = std::make_unique<const TerrainMesh>(makeTerrainMesh(*terrain, region, params));
    state_->scene->setGroundMesh(mesh->positions, mesh->indices);
    state_->hills = std::make_unique<const SunHorizon>(*mesh, settings_.sun_direction, sun_radius, region);
  });
  state_->ground_mesh = std::move(mesh);
  state_->terrain = std::move(terrain);
  state_->ground_floor = state_->ground_mesh->min_height;
}

int Renderer::addMesh(const MeshDesc& desc) {
  if (!desc.colors.empty() && desc.colors.size() != desc.vertex_count) {
    throw std::invalid_argument("addMesh: " + std::to_string(desc.colors.size()) + " colours for " +
                                std::to_string(desc.vertex_count) + " vertices");
  }
  if (!desc.rest_positions.empty() && desc.rest_positions.size() != desc.vertex_count) {
    throw std::invalid_argument("addMesh: " + std::to_string(desc.rest_positions.size()) + " rest positions for " +
                                std::to_string(desc.vertex_count) + " vertices");
  }
  if (!desc.textures.empty() || !desc.uvs.empty() || !desc.triangle_textures.empty()) {
    if (desc.uvs.size() != desc.vertex_count || desc.triangle_textures.size() != desc.indices.size() / 3)
      throw std::invalid_argument("addMesh: a textured mesh needs one uv a vertex and one texture index a triangle");
    for (const int32_t t : desc.triangle_textures)
      if (t < -1 || t >= int32_t(desc.textures.size()) || (t >= 0 && !desc.textures[size_t(t)]))
        throw std::invalid_argument("addMesh: texture index " + std::to_string(t) + " for " +
                                    std::to_string(desc.textures.size()) + " textures");
  }
  const unsigned geometry =
      state_->scene->addTriangleMesh(desc.vertex_count, desc.indices, desc.rest_positions, desc.geometry_id);
  auto mesh = std::make_unique<ShadingMesh>();
  mesh->id = desc.id;
  mesh->indices = desc.indices;
  mesh->colors = desc.colors.empty() ? std::vector<glm::vec3>(desc.vertex_count, glm::vec3(0.5f)) : desc.colors;
  mesh->normals.assign(desc.vertex_count, glm::vec3(0.0f, 1.0f, 0.0f));
  mesh->uvs = desc.uvs;
  mesh->triangle_textures = desc.triangle_textures;
  mesh->textures = desc.textures;
  if (state_->by_geometry.size() <= geometry) state_->by_geometry.resize(geometry + 1, nullptr);
  state_->by_geometry[geometry] = mesh.get();
  state_->meshes.push_back(std::move(mesh));
  state_->geometry_of_mesh.push_back(geometry);
  return int(state_->meshes.size() - 1);
}

void Renderer::updateMesh(int mesh, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals) {
  if (mesh < 0 || size_t(mesh) >= state_->meshes.size()) throw std::invalid_argument("updateMesh: no mesh " + std::to_string(mesh));
  ShadingMesh& m = *state_->meshes[size_t(mesh)];
  if (normals.size() != m.normals.size()) {
    throw std::invalid_argument("updateMesh: " + std::to_string(normals.size()) + " normals for " +
                                std::to_string(m.normals.size()) + " vertices");
  }
  state_->scene->setVertices(state_->geometry_of_mesh[size_t(mesh)], positions);  // checks the count
  std::copy(normals.begin(), normals.end(), m.normals.begin());
}

void Renderer::setMeshEnabled(int mesh, bool enabled) {
  if (mesh < 0 || size_t(mesh) >= state_->meshes.size()) throw std::invalid_argument("setMeshEnabled: no mesh " + std::to_string(mesh));
  state_->scene->setEnabled(state_->geometry_of_mesh[size_t(mesh)], enabled);
}

Image Renderer::render(const scene::Camera& camera, int frame, RayLog* log, const std::function<void()>& alongside) {
  const int w = settings_.width, h = settings_.height;
  const scene::CameraFrame camera_frame(camera, w, h);
  Image image = Image::unfilled(w, h);  // every pixel is written by its tile below
  if (settings_.passes) {
    image.depth.assign(image.pixelCount(), 0.0f);
    image.matte.assign(image.pixelCount(), 0.0f);
    image.normal.assign(image.pixelCount(), glm::vec3(0.0f));
    image.object_id.assign(image.pixelCount(), kNoObject);
  }
  struct KeptRays {
    std::vector<RTCRay> camera, occlusion;
  };
  tbb::enumerable_thread_specific<KeptRays> kept;
  auto& buffers = state_->tile_buffers;
  const size_t stride = log ? size_t(std::max(1, log->pixel_stride)) : 0;
  std::atomic<uint64_t> rays{0};
  tbb::task_group side;
  const auto traceFrame = [&] {
    const auto t0 = Clock::now();
    state_->scene->commit();
    stats_.commit_ms = msSince(t0);
    // After the commit: the refit has every thread (on two cores it scales with them, and taking
    // one away for the side task only moved its time onto the trace).
    if (alongside) side.run(alongside);
    const Integrator integrator(settings_, *state_->scene, state_->by_geometry, state_->terrain.get(),
                                state_->ground_floor, state_->hills.get(), state_->ground_mesh.get());

    const auto t1 = Clock::now();
    // simple_partitioner: tiles of at most 16 x 16, whatever the thread count.
    tbb::parallel_for(
        tbb::blocked_range2d<int>(0, h, kTileSize, 0, w, kTileSize),
        [&](const tbb::blocked_range2d<int>& tile) {
          DenormalsAreZero ftz;
          RayTally tally;
          TileBuffers& b = buffers.local();
          const int x0 = tile.cols().begin(), x1 = tile.cols().end();
          const int y0 = tile.rows().begin(), y1 = tile.rows().end();
          b.results.resize(size_t(x1 - x0) * size_t(y1 - y0));
          if (log) {
            // Keeping rays (benchmarks only): pixel by pixel, so the log holds exactly the kept pixels' rays.
            KeptRays& keep = kept.local();
            for (int y = y0; y < y1; ++y) {
              for (int x = x0; x < x1; ++x) {
                const bool keep_pixel = (size_t(y) * size_t(w) + size_t(x)) % stride == 0;
                tally.camera = keep_pixel ? &keep.camera : nullptr;
                tally.occlusion = keep_pixel ? &keep.occlusion : nullptr;
                integrator.renderTile(camera_frame, x, x + 1, y, y + 1, frame, b.scratch, tally,
                                      &b.results[size_t(y - y0) * size_t(x1 - x0) + size_t(x - x0)]);
              }
            }
          } else {
            integrator.renderTile(camera_frame, x0, x1, y0, y1, frame, b.scratch, tally, b.results.data());
          }
          const PixelResult* p = b.results.data();
          for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x, ++p) {
              const size_t i = size_t(y) * size_t(w) + size_t(x);
              image.rgba[i] = p->rgba;
              if (settings_.passes) {
                image.depth[i] = p->depth;
                image.matte[i] = p->matte;
                image.normal[i] = p->normal;
                image.object_id[i] = p->object_id;
              }
            }
          }
          rays.fetch_add(tally.rays, std::memory_order_relaxed);
        },
        tbb::simple_partitioner());
    stats_.trace_ms = msSince(t1);
  };
  state_->arena.execute([&] {
    try {
      tbb::this_task_arena::isolate([&] { traceFrame(); });
    } catch (...) {
      if (alongside) side.wait();  // its own error is dropped: the frame's is already leaving
      throw;
    }
    const auto w0 = Clock::now();
    if (alongside) side.wait();
    stats_.wait_ms = msSince(w0);
  });
  stats_.triangles = state_->scene->enabledTriangleCount();
  stats_.rays = rays.load();
  if (log) {
    log->camera.clear();
    log->occlusion.clear();
    for (KeptRays& k : kept) {
      log->camera.insert(log->camera.end(), k.camera.begin(), k.camera.end());
      log->occlusion.insert(log->occlusion.end(), k.occlusion.begin(), k.occlusion.end());
    }
    log->rays = log->camera.size() + log->occlusion.size();
  }
  return image;
}

double Renderer::replay(const RayLog& log) {
  const RTCScene ground = state_->scene->ground(), characters = state_->scene->characters();
  std::atomic<uint64_t> hits{0};
  // Streams of 256 rays, about one 16 x 16 tile of camera rays, through the same stream calls the
  // integrator makes (camera rays coherent, occlusion rays not).
  constexpr size_t kChunk = 256;
  struct Chunks {
    std::vector<RTCRayHit> camera;
    std::vector<RTCRay> occlusion;
  };
  tbb::enumerable_thread_specific<Chunks> chunks;
  const auto t0 = Clock::now();
  state_->arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, log.camera.size(), kChunk),
        [&](const tbb::blocked_range<size_t>& r) {
          DenormalsAreZero ftz;
          std::vector<RTCRayHit>& rays = chunks.local().camera;
          rays.resize(r.size());
          for (size_t i = r.begin(); i < r.end(); ++i) {
            RTCRayHit& rh = rays[i - r.begin()];
            rh.ray = log.camera[i];
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
          }
          RTCIntersectContext context;
          rtcInitIntersectContext(&context);
          context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
          rtcIntersect1M(ground, &context, rays.data(), unsigned(rays.size()), sizeof(RTCRayHit));
          rtcIntersect1M(characters, &context, rays.data(), unsigned(rays.size()), sizeof(RTCRayHit));
          uint64_t n = 0;
          for (const RTCRayHit& rh : rays) n += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
          hits.fetch_add(n, std::memory_order_relaxed);
        },
        tbb::simple_partitioner());
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, log.occlusion.size(), kChunk),
        [&](const tbb::blocked_range<size_t>& r) {
          DenormalsAreZero ftz;
          std::vector<RTCRay>& rays = chunks.local().occlusion;
          rays.assign(log.occlusion.begin() + std::ptrdiff_t(r.begin()), log.occlusion.begin() + std::ptrdiff_t(r.end()));
          RTCIntersectContext context;
          rtcInitIntersectContext(&context);
          rtcOccluded1M(characters, &context, rays.data(), unsigned(rays.size()), sizeof(RTCRay));
          uint64_t n = 0;
          for (const RTCRay& ray : rays) n += ray.tfar < 0.0f;
          hits.fetch_add(n, std::memory_order_relaxed);
        },
        tbb::simple_partitioner());
  });
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  if (hits.load() > log.rays) throw std::logic_error("replay: more hits than rays");  // keeps the work observable
  return seconds;
}

}  // namespace stirrup::render
