#include "rig/motion/terrain_mesh.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "rig/error.h"

namespace stirrup::rig {
namespace {

// A triangle whose footprint (seen from above) is smaller than this (cm²) carries no ground.
constexpr double kMinFootprintCm2 = 1e-6;
// About this many triangles share a grid cell on average.
constexpr double kTrianglesPerCell = 2.0;
// Points this close outside a triangle's footprint (cm) still count as on it: shared edges have no gap.
constexpr double kEdgeSlackCm = 1e-7;

double cross2(glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; }
glm::dvec2 xz(const glm::dvec3& p) { return {p.x, p.z}; }

}  // namespace

TerrainMesh::TerrainMesh(std::vector<glm::dvec3> vertices, std::vector<std::uint32_t> indices, const std::string& source)
    : vertices_(std::move(vertices)) {
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    const glm::dvec3& v = vertices_[i];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      throw InputError(source + ": vertex " + std::to_string(i) + ": expected finite coordinates, got (" + numberText(v.x) +
                       ", " + numberText(v.y) + ", " + numberText(v.z) + ")");
  }
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    Triangle tri{{indices[t], indices[t + 1], indices[t + 2]}};
    for (std::uint32_t k : tri.v)
      if (k >= vertices_.size())
        throw InputError(source + ": triangle " + std::to_string(t / 3) + ": expected vertex indices below " +
                         std::to_string(vertices_.size()) + ", got " + std::to_string(k));
    const glm::dvec2 a = xz(vertices_[tri.v[0]]), b = xz(vertices_[tri.v[1]]), c = xz(vertices_[tri.v[2]]);
    if (std::abs(cross2(b - a, c - a)) * 0.5 < kMinFootprintCm2) continue;
    triangles_.push_back(tri);
  }
  if (triangles_.empty()) throw InputError(source + ": expected triangles to stand on, found none");

  lower_ = upper_ = xz(vertices_[triangles_.front().v[0]]);
  lowest_ = vertices_[triangles_.front().v[0]].y;
  double footprint = 0.0;
  for (const Triangle& t : triangles_) {
    const glm::dvec2 a = xz(vertices_[t.v[0]]), b = xz(vertices_[t.v[1]]), c = xz(vertices_[t.v[2]]);
    footprint += std::abs(cross2(b - a, c - a)) * 0.5;
    for (std::uint32_t k : t.v) {
      lower_ = glm::min(lower_, xz(vertices_[k]));
      upper_ = glm::max(upper_, xz(vertices_[k]));
      lowest_ = std::min(lowest_, vertices_[k].y);
    }
  }
  // Cells about kTrianglesPerCell triangles' area each, at most 4096 a side.
  const glm::dvec2 size = glm::max(upper_ - lower_, glm::dvec2(1e-3));
  cell_cm_ = std::max(std::sqrt(footprint / double(triangles_.size()) * kTrianglesPerCell), std::max(size.x, size.y) / 4096.0);
  cells_x_ = std::max(1, int(std::ceil(size.x / cell_cm_)));
  cells_z_ = std::max(1, int(std::ceil(size.y / cell_cm_)));
  const auto cellRange = [this](const Triangle& t, int& x0, int& x1, int& z0, int& z1) {
    glm::dvec2 lo = xz(vertices_[t.v[0]]), hi = lo;
    for (std::uint32_t k : t.v) lo = glm::min(lo, xz(vertices_[k])), hi = glm::max(hi, xz(vertices_[k]));
    x0 = std::clamp(int(std::floor((lo.x - lower_.x) / cell_cm_)), 0, cells_x_ - 1);
    x1 = std::clamp(int(std::floor((hi.x - lower_.x) / cell_cm_)), 0, cells_x_ - 1);
    z0 = std::clamp(int(std::floor((lo.y - lower_.y) / cell_cm_)), 0, cells_z_ - 1);
    z1 = std::clamp(int(std::floor((hi.y - lower_.y) / cell_cm_)), 0, cells_z_ - 1);
  };
  std::vector<std::uint32_t> count(std::size_t(cells_x_) * std::size_t(cells_z_) + 1, 0);
  for (const Triangle& t : triangles_) {
    int x0, x1, z0, z1;
    cellRange(t, x0, x1, z0, z1);
    for (int z = z0; z <= z1; ++z)
      for (int x = x0; x <= x1; ++x) ++count[std::size_t(z) * std::size_t(cells_x_) + std::size_t(x) + 1];
  }
  for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
  cell_start_ = count;
  cell_triangles_.resize(count.back());
  for (std::uint32_t i = 0; i < triangles_.size(); ++i) {
    int x0, x1, z0, z1;
    cellRange(triangles_[i], x0, x1, z0, z1);
    for (int z = z0; z <= z1; ++z)
      for (int x = x0; x <= x1; ++x) cell_triangles_[count[std::size_t(z) * std::size_t(cells_x_) + std::size_t(x)]++] = i;
  }
}

std::optional<TerrainMesh::Hit> TerrainMesh::at(double x, double z) const {
  const int cx = int(std::floor((x - lower_.x) / cell_cm_)), cz = int(std::floor((z - lower_.y) / cell_cm_));
  // The footprint's far edges belong to the last cells.
  const int ix = x == upper_.x ? cells_x_ - 1 : cx, iz = z == upper_.y ? cells_z_ - 1 : cz;
  if (ix < 0 || iz < 0 || ix >= cells_x_ || iz >= cells_z_) return std::nullopt;
  const std::size_t cell = std::size_t(iz) * std::size_t(cells_x_) + std::size_t(ix);
  std::optional<Hit> best;
  const glm::dvec2 p{x, z};
  for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
    const Triangle& t = triangles_[cell_triangles_[k]];
    const glm::dvec3 &A = vertices_[t.v[0]], &B = vertices_[t.v[1]], &C = vertices_[t.v[2]];
    const glm::dvec2 a = xz(A), b = xz(B), c = xz(C);
    const double area = cross2(b - a, c - a);
    // Barycentric weights in the ground plane, scaled so an edge's slack is a distance in cm.
    const double wa = cross2(c - b, p - b) / area, wb = cross2(a - c, p - c) / area, wc = 1.0 - wa - wb;
    const double slack = kEdgeSlackCm * std::sqrt(std::abs(area)) / std::abs(area);
    if (wa < -slack || wb < -slack || wc < -slack) continue;
    const double h = wa * A.y + wb * B.y + wc * C.y;
    if (best && best->height_cm >= h) continue;
    glm::dvec3 n = glm::normalize(glm::cross(B - A, C - A));
    if (n.y < 0) n = -n;
    best = Hit{h, n};
  }
  return best;
}

std::vector<std::uint32_t> TerrainMesh::indices() const {
  std::vector<std::uint32_t> out;
  out.reserve(triangles_.size() * 3);
  for (const Triangle& t : triangles_) out.insert(out.end(), t.v, t.v + 3);
  return out;
}

}  // namespace stirrup::rig
