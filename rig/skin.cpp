// Highway compiles this file once per target (foreach_target.h re-includes it); HWY_ONCE marks the
// part compiled once: the entry points of skin.h.
#include "rig/skin.h"

#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "rig/skin.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace stirrup::rig {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using DF = hn::ScalableTag<float>;
using VF = hn::Vec<DF>;

// skinVertex (below), a vector of vertices at once: the same operations in the same order (glm's, as
// the scalar code makes them), none fused, so each vertex comes out to the bit as skinVertex gives it.
// Vertices [first, last); the ones after the last whole vector are skinVertex's.
void SkinLanes(const SkinnedMesh& mesh, const glm::mat4* m, std::size_t first, std::size_t last,
               glm::vec3* positions, glm::vec3* normals) {
  const DF df;
  const hn::RebindToSigned<DF> di;
  const hn::Rebind<uint16_t, DF> d16;
  const std::size_t lanes = hn::Lanes(df);
  const float* matrices = &m[0][0][0];
  std::size_t v = first;
  for (; v + lanes <= last; v += lanes) {
    VF w[4];
    hn::LoadInterleaved4(df, &mesh.weights[v][0], w[0], w[1], w[2], w[3]);
    hn::Vec<decltype(d16)> j16[4];
    hn::LoadInterleaved4(d16, &mesh.joints[v][0], j16[0], j16[1], j16[2], j16[3]);
    // blendAt: the weighted sum of the joints' matrices, weights <= 0 skipped. Adding +0 where a weight
    // is skipped leaves the sum as it was: a sum that starts at +0 is never -0.
    hn::Vec<decltype(di)> offset[4];
    hn::Mask<DF> used[4];
    for (int i = 0; i < 4; ++i) {
      used[i] = hn::Gt(w[i], hn::Zero(df));
      // An unused slot reads joint 0 (its index need not be a joint), and adds nothing.
      offset[i] = hn::IfThenElseZero(hn::RebindMask(di, used[i]), hn::ShiftLeft<4>(hn::PromoteTo(di, j16[i])));
    }
    // The blend's rows 0-2 of its four columns (all that positions and normals read), influence by
    // influence; one no vertex of the vector uses adds nothing and is not read (most vertices have one
    // or two, and neighbours share them).
    VF b[4][3];
    for (auto& column : b)
      for (VF& e : column) e = hn::Zero(df);
    for (int i = 0; i < 4; ++i) {
      if (hn::AllFalse(df, used[i])) continue;
      // One joint for the whole vector (a run of vertices on one bone): its matrix broadcast, not gathered.
      const int32_t first_offset = hn::GetLane(offset[i]);
      const bool one_joint = hn::AllTrue(di, hn::Eq(offset[i], hn::Set(di, first_offset)));
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 3; ++r) {
          const float* element = matrices + (4 * c + r);
          const VF e = one_joint ? hn::Set(df, element[first_offset]) : hn::GatherIndex(df, element, offset[i]);
          b[c][r] = hn::Add(b[c][r], hn::IfThenElseZero(used[i], hn::Mul(w[i], e)));
        }
      }
    }
    VF px, py, pz, nx, ny, nz;
    hn::LoadInterleaved3(df, &mesh.positions[v][0], px, py, pz);
    hn::LoadInterleaved3(df, &mesh.normals[v][0], nx, ny, nz);
    // blend * vec4(p, 1): (m0 x + m1 y) + (m2 z + m3 1), as glm's mat4 * vec4.
    const VF one = hn::Set(df, 1.0f);
    VF out[3];
    for (int r = 0; r < 3; ++r)
      out[r] = hn::Add(hn::Add(hn::Mul(b[0][r], px), hn::Mul(b[1][r], py)),
                       hn::Add(hn::Mul(b[2][r], pz), hn::Mul(b[3][r], one)));
    hn::StoreInterleaved3(out[0], out[1], out[2], df, &positions[v][0]);
    // transpose(inverse(mat3(blend))) * n, as glm's inverse (its cofactors times one over the
    // determinant) and mat3 * vec3.
    auto cof = [](VF a, VF b2, VF c, VF d) { return hn::Sub(hn::Mul(a, b2), hn::Mul(c, d)); };
    const VF c00 = cof(b[1][1], b[2][2], b[2][1], b[1][2]);
    const VF c01 = cof(b[0][1], b[2][2], b[2][1], b[0][2]);
    const VF c02 = cof(b[0][1], b[1][2], b[1][1], b[0][2]);
    const VF det = hn::Add(hn::Sub(hn::Mul(b[0][0], c00), hn::Mul(b[1][0], c01)), hn::Mul(b[2][0], c02));
    const VF inv_det = hn::Div(one, det);
    // inv[col][row], glm's Inverse[col][row].
    const VF i00 = hn::Mul(c00, inv_det);
    const VF i10 = hn::Mul(hn::Neg(cof(b[1][0], b[2][2], b[2][0], b[1][2])), inv_det);
    const VF i20 = hn::Mul(cof(b[1][0], b[2][1], b[2][0], b[1][1]), inv_det);
    const VF i01 = hn::Mul(hn::Neg(c01), inv_det);
    const VF i11 = hn::Mul(cof(b[0][0], b[2][2], b[2][0], b[0][2]), inv_det);
    const VF i21 = hn::Mul(hn::Neg(cof(b[0][0], b[2][1], b[2][0], b[0][1])), inv_det);
    const VF i02 = hn::Mul(c02, inv_det);
    const VF i12 = hn::Mul(hn::Neg(cof(b[0][0], b[1][2], b[1][0], b[0][2])), inv_det);
    const VF i22 = hn::Mul(cof(b[0][0], b[1][1], b[1][0], b[0][1]), inv_det);
    // (transpose(inv) * n)[r] = inv[r][0] n.x + inv[r][1] n.y + inv[r][2] n.z
    auto row = [&](VF a, VF b2, VF c) { return hn::Add(hn::Add(hn::Mul(a, nx), hn::Mul(b2, ny)), hn::Mul(c, nz)); };
    const VF qx = row(i00, i01, i02), qy = row(i10, i11, i12), qz = row(i20, i21, i22);
    const VF len = hn::Sqrt(hn::Add(hn::Add(hn::Mul(qx, qx), hn::Mul(qy, qy)), hn::Mul(qz, qz)));
    const auto keep = hn::Gt(len, hn::Set(df, 1e-12f));
    hn::StoreInterleaved3(hn::IfThenElse(keep, hn::Div(qx, len), nx), hn::IfThenElse(keep, hn::Div(qy, len), ny),
                          hn::IfThenElse(keep, hn::Div(qz, len), nz), df, &normals[v][0]);
  }
  for (; v < last; ++v) skinVertex(mesh, m, v, positions[v], normals[v]);
}

}  // namespace HWY_NAMESPACE
}  // namespace stirrup::rig
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stirrup::rig {

HWY_EXPORT(SkinLanes);

std::vector<glm::mat4> skinningMatrices(const Skeleton& skel, std::span<const glm::mat4> jointWorld) {
  if (jointWorld.size() != skel.size())
    throw std::invalid_argument("skinning: expected one world matrix per joint");
  std::vector<glm::mat4> m(skel.size());
  for (std::size_t i = 0; i < skel.size(); ++i) m[i] = jointWorld[i] * skel.skinBind(static_cast<int>(i));
  return m;
}

namespace {

// A vertex's blended skinning matrix: skinMesh and skinPositions share it, so they agree to the bit.
inline glm::mat4 blendAt(const SkinnedMesh& mesh, const glm::mat4* m, std::size_t v) {
  const glm::u16vec4 j = mesh.joints[v];
  const glm::vec4 w = mesh.weights[v];
  glm::mat4 blend(0.0f);
  for (int i = 0; i < kMaxInfluences; ++i)
    if (w[i] > 0.0f) blend += w[i] * m[j[i]];
  return blend;
}

}  // namespace

void skinVertex(const SkinnedMesh& mesh, const glm::mat4* m, std::size_t v, glm::vec3& position, glm::vec3& normal) {
  const glm::mat4 blend = blendAt(mesh, m, v);
  position = glm::vec3(blend * glm::vec4(mesh.positions[v], 1.0f));
  // Inverse transpose of the blended 3x3 keeps normals perpendicular under non-rigid blends.
  const glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(blend)));
  const glm::vec3 nrm = nm * mesh.normals[v];
  const float len = glm::length(nrm);
  normal = len > 1e-12f ? nrm / len : mesh.normals[v];
}

void skinMesh(const SkinnedMesh& mesh, const Skeleton& skel, std::span<const glm::mat4> jointWorld,
              std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) {
  const std::vector<glm::mat4> m = skinningMatrices(skel, jointWorld);
  const std::size_t n = mesh.positions.size();
  positions.resize(n);
  normals.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    HWY_DYNAMIC_DISPATCH(SkinLanes)(mesh, m.data(), r.begin(), r.end(), positions.data(), normals.data());
  });
}

void skinPositions(const SkinnedMesh& mesh, const Skeleton& skel, std::span<const glm::mat4> jointWorld, int stride,
                   std::vector<glm::vec3>& positions) {
  if (stride < 1) throw std::invalid_argument("skinPositions: expected a stride of 1 or more");
  const std::vector<glm::mat4> m = skinningMatrices(skel, jointWorld);
  const std::size_t step = std::size_t(stride);
  const std::size_t n = (mesh.positions.size() + step - 1) / step;
  positions.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const std::size_t v = k * step;
      positions[k] = glm::vec3(blendAt(mesh, m.data(), v) * glm::vec4(mesh.positions[v], 1.0f));
    }
  });
}

}  // namespace stirrup::rig
#endif  // HWY_ONCE
