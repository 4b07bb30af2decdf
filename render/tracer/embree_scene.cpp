#include "render/tracer/embree_scene.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

namespace stirrup::render {
namespace {

void throwOnDeviceError(RTCDevice device, const char* what, const std::string& message) {
  const RTCError err = rtcGetDeviceError(device);
  if (err != RTC_ERROR_NONE) {
    throw std::runtime_error(std::string("embree: ") + what + " failed (error " + std::to_string(int(err)) + "): " + message);
  }
}

// Embree reports the reason for a failure only through this callback; keep it for the exception.
void rememberError(void* user, RTCError, const char* message) {
  if (message) *static_cast<std::string*>(user) = message;
}

}  // namespace

EmbreeScene::EmbreeScene(BvhUpdate update, int threads) : update_(update) {
  // Embree's builders run on TBB threads of its own choosing unless the device is told how many it
  // may use: "threads=N" caps TBB's parallelism (process-wide, at the most any live device asks for)
  // while the device lives, so a renderer asked for N threads builds on N.
  // (Embree 3.13 has no switch to ignore ~/.embree3; such a file could still pin another ISA.)
  // STIRRUP_EMBREE_CONFIG adds to the device config, e.g. "isa=sse4.2" to pin the instruction set
  // the way a farm of mixed CPUs would run it (the golden noise floor is measured so; README).
  if (threads < 0) throw std::invalid_argument("EmbreeScene: expected a thread count of 0 (all cores) or more");
  std::string config = "verbose=0";
  if (threads > 0) config += ",threads=" + std::to_string(threads);
  if (const char* extra = std::getenv("STIRRUP_EMBREE_CONFIG"); extra && *extra) config += std::string(",") + extra;
  device_ = rtcNewDevice(config.c_str());
  if (!device_) {
    throw std::runtime_error("embree: cannot create a device with the config \"" + config +
                             "\" (check STIRRUP_EMBREE_CONFIG: settings like isa=sse4.2 or isa=avx2)");
  }
  rtcSetDeviceErrorFunction(device_, rememberError, &last_error_);
  scene_ = rtcNewScene(device_);
  throwOnDeviceError(device_, "rtcNewScene", last_error_);
  // LOW at the scene level makes Embree build two levels, one BVH per geometry, which is what lets
  // per-geometry quality (REFIT, or keeping the ground's BVH) take effect. MEDIUM builds one SAH BVH.
  rtcSetSceneBuildQuality(scene_, update_ == BvhUpdate::Rebuild ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_LOW);
  rtcSetSceneFlags(scene_, update_ == BvhUpdate::Rebuild ? RTC_SCENE_FLAG_NONE : RTC_SCENE_FLAG_DYNAMIC);
  ground_ = rtcNewScene(device_);
  throwOnDeviceError(device_, "rtcNewScene", last_error_);
  rtcCommitScene(ground_);  // an empty, valid scene until setGround
  bounds_ = {1.0f, 1.0f, 1.0f, 0.0f, -1.0f, -1.0f, -1.0f, 0.0f};
}

EmbreeScene::~EmbreeScene() {
  for (Mesh& m : meshes_) rtcReleaseGeometry(m.geometry);
  if (ground_quad_) rtcReleaseGeometry(ground_quad_);
  if (ground_) rtcReleaseScene(ground_);
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

void EmbreeScene::setGround(float half_extent_cm) {
  if (ground_quad_) {
    rtcDetachGeometry(ground_, 0);
    rtcReleaseGeometry(ground_quad_);
  }
  const float e = half_extent_cm;
  ground_quad_ = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(ground_quad_, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4));
  auto* t = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(ground_quad_, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), 2));
  throwOnDeviceError(device_, "ground buffers", last_error_);
  const float corners[12] = {-e, 0, -e, -e, 0, e, e, 0, e, e, 0, -e};
  const uint32_t quad[6] = {0, 1, 2, 0, 2, 3};  // counter-clockwise seen from above: normal +Y
  std::memcpy(v, corners, sizeof(corners));
  std::memcpy(t, quad, sizeof(quad));
  rtcCommitGeometry(ground_quad_);
  rtcAttachGeometryByID(ground_, ground_quad_, 0);
  rtcCommitScene(ground_);
  throwOnDeviceError(device_, "ground commit", last_error_);
}

void EmbreeScene::setGroundMesh(std::span<const glm::vec3> positions, std::span<const uint32_t> indices) {
  if (indices.size() % 6 != 0)
    throw std::invalid_argument("ground mesh: index count is not a multiple of 6 (a cell's two triangles)");
  for (uint32_t i : indices)
    if (i >= positions.size()) throw std::invalid_argument("ground mesh: index " + std::to_string(i) + " out of range");
  // Each cell's triangles (a c d), (a d b) as Embree's quad (c d b a): Embree splits a quad (v0 v1 v2 v3)
  // into (v0 v1 v3) = (c d a) and (v2 v3 v1) = (b a d), the same two triangles wound the same way.
  const std::size_t cells = indices.size() / 6;
  for (std::size_t q = 0; q < cells; ++q) {
    const uint32_t* t = &indices[6 * q];
    if (t[3] != t[0] || t[4] != t[2])
      throw std::invalid_argument("ground mesh: triangles " + std::to_string(2 * q) + " and " + std::to_string(2 * q + 1) +
                                  " do not share their first and last vertex as (a c d), (a d b)");
  }
  if (ground_quad_) {
    rtcDetachGeometry(ground_, 0);
    rtcReleaseGeometry(ground_quad_);
  }
  ground_quad_ = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_QUAD);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(ground_quad_, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), positions.size()));
  auto* quads = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(ground_quad_, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4,
                                                               4 * sizeof(uint32_t), cells));
  throwOnDeviceError(device_, "ground mesh buffers", last_error_);
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  std::memcpy(v, positions.data(), positions.size_bytes());
  for (std::size_t q = 0; q < cells; ++q) {
    const uint32_t* t = &indices[6 * q];  // a c d, a d b
    quads[4 * q + 0] = t[1], quads[4 * q + 1] = t[2], quads[4 * q + 2] = t[5], quads[4 * q + 3] = t[0];
  }
  rtcSetGeometryBuildQuality(ground_quad_, RTC_BUILD_QUALITY_MEDIUM);
  rtcCommitGeometry(ground_quad_);
  rtcAttachGeometryByID(ground_, ground_quad_, 0);
  // Watertight: Embree's default (Moeller-Trumbore) test lets a ray through where two triangles
  // share an edge or a vertex, and a camera ray through such a crack saw the sky: a bright speck on
  // the ground in a few pixels of most hill frames. The robust test closes the cracks for 1.4% more
  // CPU on a `trail` draft frame (docs/performance-history.md, "Cracks in the heightfield").
  rtcSetSceneFlags(ground_, RTC_SCENE_FLAG_ROBUST);
  rtcCommitScene(ground_);
  throwOnDeviceError(device_, "ground mesh commit", last_error_);
}

unsigned EmbreeScene::addTriangleMesh(size_t vertex_count, std::span<const uint32_t> indices,
                                      std::span<const glm::vec3> rest_positions, int wanted_id) {
  if (wanted_id >= 0 && std::size_t(wanted_id) < meshes_.size() && meshes_[std::size_t(wanted_id)].geometry)
    throw std::invalid_argument("mesh: geometry id " + std::to_string(wanted_id) + " is taken");
  if (!rest_positions.empty() && rest_positions.size() != vertex_count)
    throw std::invalid_argument("mesh: rest positions do not match the vertex count");
  if (indices.size() % 3 != 0) throw std::invalid_argument("mesh: index count is not a multiple of 3");
  for (uint32_t i : indices) {
    if (i >= vertex_count) throw std::invalid_argument("mesh: index " + std::to_string(i) + " >= vertex count " + std::to_string(vertex_count));
  }
  RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  throwOnDeviceError(device_, "rtcNewGeometry", last_error_);
  // Embree owns both buffers (and pads the vertex buffer for its 16-byte loads).
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertex_count));
  auto* tris = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), indices.size() / 3));
  if (!vertices || !tris) {
    rtcReleaseGeometry(g);
    throwOnDeviceError(device_, "rtcSetNewGeometryBuffer", last_error_);
    throw std::runtime_error("embree: cannot allocate mesh buffers");
  }
  std::memset(vertices, 0, vertex_count * 3 * sizeof(float));
  if (!indices.empty()) std::memcpy(tris, indices.data(), indices.size_bytes());
  rtcSetGeometryBuildQuality(g, update_ == BvhUpdate::Refit              ? RTC_BUILD_QUALITY_REFIT
                                : update_ == BvhUpdate::RebuildPerMeshLow ? RTC_BUILD_QUALITY_LOW
                                                                          : RTC_BUILD_QUALITY_MEDIUM);
  rtcCommitGeometry(g);
  unsigned id = unsigned(wanted_id);
  if (wanted_id >= 0)
    rtcAttachGeometryByID(scene_, g, id);
  else
    id = rtcAttachGeometry(scene_, g);
  throwOnDeviceError(device_, "rtcAttachGeometry", last_error_);
  if (id >= meshes_.size()) meshes_.resize(id + 1);
  meshes_[id] = Mesh{g, vertex_count, {}, indices.size() / 3};
  if (update_ == BvhUpdate::Refit) meshes_[id].rest.assign(rest_positions.begin(), rest_positions.end());
  triangles_ += indices.size() / 3;
  dirty_ = true;
  return id;
}

void EmbreeScene::setVertices(unsigned geom_id, std::span<const glm::vec3> positions) {
  if (geom_id >= meshes_.size() || !meshes_[geom_id].geometry) throw std::invalid_argument("setVertices: no such mesh");
  Mesh& m = meshes_[geom_id];
  if (positions.size() != m.vertex_count) {
    throw std::invalid_argument("setVertices: " + std::to_string(positions.size()) + " positions for a mesh of " +
                                std::to_string(m.vertex_count) + " vertices");
  }
  auto* dst = static_cast<float*>(rtcGetGeometryBufferData(m.geometry, RTC_BUFFER_TYPE_VERTEX, 0));
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  std::memcpy(dst, positions.data(), positions.size_bytes());
  rtcUpdateGeometryBuffer(m.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
  rtcCommitGeometry(m.geometry);
  dirty_ = true;
}

void EmbreeScene::setEnabled(unsigned geom_id, bool enabled) {
  if (geom_id >= meshes_.size() || !meshes_[geom_id].geometry) throw std::invalid_argument("setEnabled: no such mesh");
  Mesh& m = meshes_[geom_id];
  if (m.enabled == enabled) return;
  m.enabled = enabled;
  if (enabled) {
    rtcEnableGeometry(m.geometry);
    m.needs_rest_build = true;
  } else {
    rtcDisableGeometry(m.geometry);
  }
  dirty_ = true;
}

size_t EmbreeScene::enabledTriangleCount() const {
  size_t n = 0;
  for (const Mesh& m : meshes_)
    if (m.geometry && m.enabled) n += m.triangle_count;
  return n;
}

void EmbreeScene::commit() {
  if (!dirty_) return;
  if (update_ == BvhUpdate::Refit) {
    // Build the tree of each new (or put back) mesh over its rest pose, then put its current vertices
    // back: the commit below refits. The current vertices are copied out of Embree's buffer and restored.
    std::vector<std::vector<glm::vec3>> current(meshes_.size());
    bool any_rest = false;
    for (size_t id = 0; id < meshes_.size(); ++id) {
      Mesh& m = meshes_[id];
      if (!m.geometry || !m.enabled || !m.needs_rest_build) continue;
      m.needs_rest_build = false;
      if (m.rest.empty()) continue;
      auto* v = static_cast<glm::vec3*>(rtcGetGeometryBufferData(m.geometry, RTC_BUFFER_TYPE_VERTEX, 0));
      current[id].assign(v, v + m.vertex_count);
      std::memcpy(v, m.rest.data(), m.vertex_count * sizeof(glm::vec3));
      rtcUpdateGeometryBuffer(m.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
      rtcCommitGeometry(m.geometry);
      any_rest = true;
    }
    if (any_rest) {
      rtcCommitScene(scene_);
      throwOnDeviceError(device_, "rtcCommitScene", last_error_);
      for (size_t id = 0; id < meshes_.size(); ++id) {
        Mesh& m = meshes_[id];
        if (current[id].empty()) continue;
        auto* v = static_cast<glm::vec3*>(rtcGetGeometryBufferData(m.geometry, RTC_BUFFER_TYPE_VERTEX, 0));
        std::memcpy(v, current[id].data(), m.vertex_count * sizeof(glm::vec3));
        rtcUpdateGeometryBuffer(m.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
        rtcCommitGeometry(m.geometry);
      }
    }
  }
  rtcCommitScene(scene_);
  throwOnDeviceError(device_, "rtcCommitScene", last_error_);
  rtcGetSceneBounds(scene_, &bounds_);
  dirty_ = false;
}

}  // namespace stirrup::render
