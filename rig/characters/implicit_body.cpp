#include "rig/characters/implicit_body.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace stirrup::rig {
namespace {

float dot2(glm::vec3 v) { return glm::dot(v, v); }

// Exact distance to a round cone (Quilez), a sphere when the segment degenerates.
float roundConeDistance(glm::vec3 p, glm::vec3 a, glm::vec3 b, float r1, float r2) {
  const glm::vec3 ba = b - a;
  const float l2 = glm::dot(ba, ba);
  if (l2 < 1e-8f) return glm::length(p - a) - std::max(r1, r2);
  const float rr = r1 - r2;
  const float a2 = l2 - rr * rr;
  // One sphere swallows the other: the bigger sphere is the shape.
  if (a2 <= 1e-6f) return r1 > r2 ? glm::length(p - a) - r1 : glm::length(p - b) - r2;
  const float il2 = 1.0f / l2;
  const glm::vec3 pa = p - a;
  const float y = glm::dot(pa, ba);
  const float z = y - l2;
  const float x2 = dot2(pa * l2 - ba * y);
  const float y2 = y * y * l2;
  const float z2 = z * z * l2;
  const float k = (rr > 0.0f ? 1.0f : rr < 0.0f ? -1.0f : 0.0f) * rr * rr * x2;
  const float sz = z > 0.0f ? 1.0f : z < 0.0f ? -1.0f : 0.0f;
  const float sy = y > 0.0f ? 1.0f : y < 0.0f ? -1.0f : 0.0f;
  if (sz * a2 * z2 > k) return std::sqrt(x2 + z2) * il2 - r2;
  if (sy * a2 * y2 < k) return std::sqrt(x2 + y2) * il2 - r1;
  return (std::sqrt(x2 * a2 * il2) + y * rr) * il2 - r1;
}

// Quilez's ellipsoid bound: exact on the surface, a good distance estimate near it.
float ellipsoidDistance(glm::vec3 p, glm::vec3 r) {
  const float k0 = glm::length(p / r);
  if (k0 < 1e-6f) return -std::min(r.x, std::min(r.y, r.z));
  const float k1 = glm::length(p / (r * r));
  return k0 * (k0 - 1.0f) / k1;
}

// Bounding sphere of a primitive, for skipping ones that cannot change the union at a point.
struct Sphere {
  glm::vec3 c;
  float r;
};
Sphere boundingSphere(const ImplicitPrimitive& prim) {
  if (prim.shape == ImplicitPrimitive::Shape::Ellipsoid)
    return {prim.center, std::max(prim.radii.x, std::max(prim.radii.y, prim.radii.z))};
  const glm::vec3 c = 0.5f * (prim.a + prim.b);
  return {c, 0.5f * glm::length(prim.b - prim.a) + std::max(prim.ra, prim.rb)};
}

// The body with each primitive's bounding sphere computed once, evaluated over a subset of
// primitives (those that can reach a block of the grid).
struct PreparedBody {
  const ImplicitBody& body;
  std::vector<Sphere> spheres;
  explicit PreparedBody(const ImplicitBody& b) : body(b) {
    for (const ImplicitPrimitive& p : b.primitives) spheres.push_back(boundingSphere(p));
  }
  template <typename Indices>
  float distance(glm::vec3 p, const Indices& subset) const;
  // Tetrahedral differences: four evaluations instead of six for the same accuracy order.
  glm::vec3 gradient(glm::vec3 p, const std::vector<int>& subset, float h) const {
    const glm::vec3 k0(1, -1, -1), k1(-1, -1, 1), k2(-1, 1, -1), k3(1, 1, 1);
    return (k0 * distance(p + k0 * h, subset) + k1 * distance(p + k1 * h, subset) +
            k2 * distance(p + k2 * h, subset) + k3 * distance(p + k3 * h, subset)) /
           (4.0f * h);
  }
};

}  // namespace

float smoothMin(float a, float b, float k) {
  if (k <= 0.0f) return std::min(a, b);
  const float h = std::max(k - std::abs(a - b), 0.0f) / k;
  return std::min(a, b) - h * h * k * 0.25f;
}

float primitiveDistance(const ImplicitPrimitive& prim, glm::vec3 p) {
  float d;
  if (prim.shape == ImplicitPrimitive::Shape::Ellipsoid)
    d = ellipsoidDistance(glm::transpose(prim.axes) * (p - prim.center), prim.radii);
  else
    d = roundConeDistance(p, prim.a, prim.b, prim.ra, prim.rb);
  const glm::vec3 outside = glm::max(prim.clip_min - p, p - prim.clip_max);
  const float box = std::max(outside.x, std::max(outside.y, outside.z));
  return prim.clip_round > 0.0f ? -smoothMin(-d, -box, prim.clip_round) : std::max(d, box);
}

ImplicitPrimitive taperedCapsule(glm::vec3 a, glm::vec3 b, float ra, float rb, int joint,
                                 glm::vec3 color, float blend) {
  ImplicitPrimitive p;
  p.shape = ImplicitPrimitive::Shape::TaperedCapsule;
  p.a = a;
  p.b = b;
  p.ra = ra;
  p.rb = rb;
  p.joint = joint;
  p.color = color;
  p.blend = blend;
  return p;
}

ImplicitPrimitive ellipsoid(glm::vec3 center, glm::vec3 radii, int joint, glm::vec3 color, float blend,
                            glm::vec3 forward) {
  ImplicitPrimitive p;
  p.shape = ImplicitPrimitive::Shape::Ellipsoid;
  p.center = center;
  p.radii = radii;
  const glm::vec3 x = glm::normalize(forward);
  glm::vec3 up(0.0f, 1.0f, 0.0f);
  if (std::abs(glm::dot(x, up)) > 0.99f) up = glm::vec3(-1.0f, 0.0f, 0.0f);
  const glm::vec3 z = glm::normalize(glm::cross(x, up));
  const glm::vec3 y = glm::cross(z, x);
  p.axes = glm::mat3(x, y, z);
  p.joint = joint;
  p.color = color;
  p.blend = blend;
  return p;
}

float ImplicitBody::distance(glm::vec3 p) const {
  float d = std::numeric_limits<float>::infinity();
  for (const ImplicitPrimitive& prim : primitives) {
    const Sphere s = boundingSphere(prim);
    // A lower bound on this primitive's distance: past d + blend it leaves the union unchanged.
    if (glm::length(p - s.c) - s.r > d + prim.blend) continue;
    const float di = primitiveDistance(prim, p);
    d = std::isinf(d) ? di : smoothMin(d, di, prim.blend);
  }
  return d;
}

glm::vec3 ImplicitBody::gradient(glm::vec3 p, float h) const {
  const glm::vec3 dx(h, 0, 0), dy(0, h, 0), dz(0, 0, h);
  return glm::vec3(distance(p + dx) - distance(p - dx), distance(p + dy) - distance(p - dy),
                   distance(p + dz) - distance(p - dz)) /
         (2.0f * h);
}

void ImplicitBody::bounds(glm::vec3& lo, glm::vec3& hi) const {
  lo = glm::vec3(std::numeric_limits<float>::infinity());
  hi = -lo;
  for (const ImplicitPrimitive& prim : primitives) {
    const Sphere s = boundingSphere(prim);
    lo = glm::min(lo, glm::max(s.c - s.r, prim.clip_min));
    hi = glm::max(hi, glm::min(s.c + s.r, prim.clip_max));
  }
}

template <typename Indices>
float PreparedBody::distance(glm::vec3 p, const Indices& subset) const {
  float d = std::numeric_limits<float>::infinity();
  for (const int i : subset) {
    const ImplicitPrimitive& prim = body.primitives[i];
    if (glm::length(p - spheres[i].c) - spheres[i].r > d + prim.blend) continue;
    const float di = primitiveDistance(prim, p);
    d = std::isinf(d) ? di : smoothMin(d, di, prim.blend);
  }
  return d;
}

namespace {

// The grid the field is sampled on: n nodes a side from `lo`, `h` apart; cells between them.
struct FieldGrid {
  glm::vec3 lo;
  float h;
  glm::ivec3 n;
  std::size_t node(int i, int j, int k) const {
    return std::size_t(i) + std::size_t(j) * std::size_t(n.x) + std::size_t(k) * std::size_t(n.x) * std::size_t(n.y);
  }
  glm::vec3 nodePos(int i, int j, int k) const { return lo + glm::vec3(i, j, k) * h; }
  glm::ivec3 cells() const { return n - 1; }
  std::size_t cell(int i, int j, int k) const {
    const glm::ivec3 nc = cells();
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(j) * nc.x + static_cast<std::size_t>(k) * nc.x * nc.y;
  }
};

std::vector<int> everyPrimitive(const ImplicitBody& body) {
  std::vector<int> all(body.primitives.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return all;
}

// 1. The field on the grid. Blocks of B^3 nodes far from the surface (|d| beyond the block's reach, with
// margin for the ellipsoid estimate) take the centre value: only the sign matters there, and no sign
// change can sit inside such a block.
std::vector<float> sampleField(const ImplicitBody& body, const PreparedBody& prepared, const FieldGrid& grid) {
  const glm::ivec3 n = grid.n;
  const float h = grid.h;
  std::vector<float> field(static_cast<std::size_t>(n.x) * n.y * n.z);
  const std::vector<int> all = everyPrimitive(body);
  constexpr int B = 4;
  const glm::ivec3 nb = (n + (B - 1)) / B;
  const float block_reach = 1.5f * (0.5f * std::sqrt(3.0f) * h * B) + h;
  tbb::parallel_for(tbb::blocked_range<int>(0, nb.x * nb.y * nb.z), [&](const tbb::blocked_range<int>& r) {
    std::vector<int> near;
    for (int b = r.begin(); b != r.end(); ++b) {
      const int bi = b % nb.x, bj = (b / nb.x) % nb.y, bk = b / (nb.x * nb.y);
      const glm::ivec3 n0(bi * B, bj * B, bk * B);
      const glm::ivec3 n1 = glm::min(n0 + B, n);
      const glm::vec3 centre = grid.lo + (glm::vec3(n0 + n1 - 1) * 0.5f) * h;
      const float dc = prepared.distance(centre, all);
      const bool far = std::abs(dc) > block_reach;
      // Primitives that can matter anywhere in the block (generous: the field is only roughly
      // 1-Lipschitz where ellipsoid estimates enter).
      near.clear();
      if (!far)
        for (int i : all)
          if (glm::length(centre - prepared.spheres[i].c) - prepared.spheres[i].r <=
              dc + 2.0f * block_reach + body.primitives[i].blend)
            near.push_back(i);
      for (int k = n0.z; k < n1.z; ++k)
        for (int j = n0.y; j < n1.y; ++j)
          for (int i = n0.x; i < n1.x; ++i)
            field[grid.node(i, j, k)] = far ? dc : prepared.distance(grid.nodePos(i, j, k), near);
    }
  });
  return field;
}

// 2. One vertex per cell whose corners disagree in sign: the mean of the edge crossings. Returns each
// cell's vertex in mesh.positions, or -1.
std::vector<std::int32_t> placeCellVertices(const std::vector<float>& field, const FieldGrid& grid, SkinnedMesh& mesh) {
  const glm::ivec3 nc = grid.cells();
  std::vector<std::int32_t> cell_vertex(static_cast<std::size_t>(nc.x) * nc.y * nc.z, -1);
  static constexpr std::array<std::array<int, 2>, 12> kEdges = {{{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                                                 {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}}};
  for (int k = 0; k < nc.z; ++k)
    for (int j = 0; j < nc.y; ++j)
      for (int i = 0; i < nc.x; ++i) {
        std::array<float, 8> v;
        int inside = 0;
        for (int c = 0; c < 8; ++c) {
          v[c] = field[grid.node(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))];
          inside += v[c] < 0.0f;
        }
        if (inside == 0 || inside == 8) continue;
        glm::vec3 sum(0.0f);
        int count = 0;
        for (const auto& e : kEdges) {
          const float a = v[e[0]], b = v[e[1]];
          if ((a < 0.0f) == (b < 0.0f)) continue;
          const float t = a / (a - b);
          const glm::vec3 pa(e[0] & 1, (e[0] >> 1) & 1, (e[0] >> 2) & 1);
          const glm::vec3 pb(e[1] & 1, (e[1] >> 1) & 1, (e[1] >> 2) & 1);
          sum += pa + (pb - pa) * t;
          ++count;
        }
        cell_vertex[grid.cell(i, j, k)] = static_cast<std::int32_t>(mesh.positions.size());
        mesh.positions.push_back(grid.lo + (glm::vec3(i, j, k) + sum / float(count)) * grid.h);
      }
  return cell_vertex;
}

// 3. One quad per sign-changing grid edge, joining the four cells around it, wound so its normal points
// from inside (negative) to outside.
void joinCells(const std::vector<float>& field, const FieldGrid& grid, const std::vector<std::int32_t>& cell_vertex,
               SkinnedMesh& mesh) {
  auto emitQuad = [&](std::size_t c0, std::size_t c1, std::size_t c2, std::size_t c3, bool flip) {
    std::array<std::uint32_t, 4> q = {std::uint32_t(cell_vertex[c0]), std::uint32_t(cell_vertex[c1]),
                                      std::uint32_t(cell_vertex[c2]), std::uint32_t(cell_vertex[c3])};
    if (flip) std::swap(q[1], q[3]);
    // Split along the shorter diagonal: fewer slivers across creases.
    const float d02 = glm::length(mesh.positions[q[0]] - mesh.positions[q[2]]);
    const float d13 = glm::length(mesh.positions[q[1]] - mesh.positions[q[3]]);
    if (d02 <= d13)
      mesh.indices.insert(mesh.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
    else
      mesh.indices.insert(mesh.indices.end(), {q[0], q[1], q[3], q[1], q[2], q[3]});
  };
  const glm::ivec3 nc = grid.cells();
  for (int k = 1; k < nc.z; ++k)
    for (int j = 1; j < nc.y; ++j)
      for (int i = 1; i < nc.x; ++i) {
        const float f = field[grid.node(i, j, k)];
        const bool in = f < 0.0f;
        // Each edge leaving node (i,j,k) in +x, +y, +z; the cells around it share that edge.
        if (in != (field[grid.node(i + 1, j, k)] < 0.0f) && i < nc.x)
          emitQuad(grid.cell(i, j - 1, k - 1), grid.cell(i, j, k - 1), grid.cell(i, j, k), grid.cell(i, j - 1, k), !in);
        if (in != (field[grid.node(i, j + 1, k)] < 0.0f) && j < nc.y)
          emitQuad(grid.cell(i - 1, j, k - 1), grid.cell(i - 1, j, k), grid.cell(i, j, k), grid.cell(i, j, k - 1), !in);
        if (in != (field[grid.node(i, j, k + 1)] < 0.0f) && k < nc.z)
          emitQuad(grid.cell(i - 1, j - 1, k), grid.cell(i, j - 1, k), grid.cell(i, j, k), grid.cell(i - 1, j, k), !in);
      }
}

// 4. Per vertex: settle onto the zero set, normal from the gradient, colour (and tack part) of the nearest
// primitive, weights falling off with distance past the nearest joint's primitives.
void settleVertices(const ImplicitBody& body, const PreparedBody& prepared, const PolygonizeParams& params,
                    SkinnedMesh& mesh) {
  const float h = params.cell;
  const std::vector<int> all = everyPrimitive(body);
  const std::size_t nv = mesh.positions.size();
  mesh.normals.resize(nv);
  mesh.colors.resize(nv);
  mesh.joints.resize(nv);
  mesh.weights.resize(nv);
  const bool tack = std::any_of(body.primitives.begin(), body.primitives.end(), [](const ImplicitPrimitive& p) { return p.tack_part != TackPart::None; });
  if (tack) mesh.tack_parts.assign(nv, TackPart::None);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<std::pair<float, int>> per_joint;
    std::vector<int> near;
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      glm::vec3 p = mesh.positions[v];
      // Primitives within reach of this vertex (it is within a cell of the surface).
      near.clear();
      for (int i : all)
        if (glm::length(p - prepared.spheres[i].c) - prepared.spheres[i].r <= 4.0f * h + body.primitives[i].blend)
          near.push_back(i);
      glm::vec3 g = prepared.gradient(p, near, 0.05f);
      for (int s = 0; s < params.project_steps; ++s) {
        const float g2 = glm::dot(g, g);
        if (g2 < 1e-8f) break;
        glm::vec3 step = prepared.distance(p, near) * g / g2;
        const float len = glm::length(step);
        if (len > 0.5f * h) step *= 0.5f * h / len;  // never leave the cell's neighbourhood
        p -= step;
        g = prepared.gradient(p, near, 0.05f);
      }
      mesh.positions[v] = p;
      const float gl = glm::length(g);
      mesh.normals[v] = gl > 1e-8f ? g / gl : glm::vec3(0, 1, 0);

      per_joint.clear();
      float nearest = std::numeric_limits<float>::infinity();
      for (int i : near) {
        const ImplicitPrimitive& prim = body.primitives[i];
        if (!prim.paints) continue;
        const float d = primitiveDistance(prim, p);
        if (d < nearest) {
          nearest = d;
          mesh.colors[v] = prim.color;
          if (tack) mesh.tack_parts[v] = prim.tack_part;
        }
        auto it = std::find_if(per_joint.begin(), per_joint.end(),
                               [&](const auto& e) { return e.second == prim.joint; });
        if (it == per_joint.end())
          per_joint.emplace_back(d, prim.joint);
        else
          it->first = std::min(it->first, d);
      }
      std::sort(per_joint.begin(), per_joint.end());
      const int count = std::min<int>(kMaxInfluences, static_cast<int>(per_joint.size()));
      glm::u16vec4 joints(0);
      glm::vec4 weights(0.0f);
      float total = 0.0f;
      for (int i = 0; i < count; ++i) {
        const float w = std::exp(-(per_joint[i].first - per_joint[0].first) / params.skin_falloff);
        joints[i] = static_cast<std::uint16_t>(per_joint[i].second);
        weights[i] = w < 1e-3f ? 0.0f : w;
        total += weights[i];
      }
      mesh.joints[v] = joints;
      mesh.weights[v] = weights / total;
    }
  });
}

}  // namespace

SkinnedMesh polygonize(const ImplicitBody& body, const PolygonizeParams& params) {
  SkinnedMesh mesh;
  if (body.primitives.empty()) return mesh;
  const float h = params.cell;
  glm::vec3 lo, hi;
  body.bounds(lo, hi);
  lo -= glm::vec3(2.0f * h);
  hi += glm::vec3(2.0f * h);
  const FieldGrid grid{lo, h, glm::ivec3(glm::ceil((hi - lo) / h)) + 1};
  const PreparedBody prepared(body);
  const std::vector<float> field = sampleField(body, prepared, grid);
  const std::vector<std::int32_t> cell_vertex = placeCellVertices(field, grid, mesh);
  joinCells(field, grid, cell_vertex, mesh);
  settleVertices(body, prepared, params, mesh);
  return mesh;
}

}  // namespace stirrup::rig
