// Highway compiles this file once per target (foreach_target.h re-includes it); HWY_ONCE marks the
// part compiled once: the grid's set-up and the dispatch.
#include "render/tracer/heightfield_walk.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "render/tracer/heightfield_walk.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "render/tracer/lane_math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace stirrup::render {
namespace HWY_NAMESPACE {

using VI = hn::Vec<DI>;
using MI = hn::Mask<DI>;

VF Clamp01(VF v) { return hn::Min(hn::Max(v, hn::Zero(DF())), Splat(1.0f)); }

// The cell of a coordinate along one axis: the last of the n lines at or before it, at most n - 2
// (GridLineIndex in floats). The bucket names a line at most one off; the loops settle every lane.
VI CellOf(VF v, const float* lines, int32_t n, const int32_t* bucket, int32_t buckets, float origin,
          float inv_bucket) {
  const DF df;
  const DI di;
  const VF b = hn::Floor(hn::Mul(hn::Sub(v, Splat(origin)), Splat(inv_bucket)));
  const VF b_clamped = hn::Min(hn::Max(b, hn::Zero(df)), Splat(float(buckets - 1)));
  VI i = hn::GatherIndex(di, bucket, hn::ConvertTo(di, hn::IfThenElseZero(hn::Eq(b_clamped, b_clamped), b_clamped)));
  const VI last = hn::Set(di, n - 2), one = hn::Set(di, 1);
  for (;;) {  // down while the line is past v
    const MI back = hn::And(hn::Gt(i, hn::Zero(di)), hn::RebindMask(di, hn::Gt(hn::GatherIndex(df, lines, i), v)));
    if (hn::AllFalse(di, back)) break;
    i = hn::IfThenElse(back, hn::Sub(i, one), i);
  }
  for (;;) {  // up while the next line is at or before v
    const MI on = hn::And(hn::Lt(i, last), hn::RebindMask(di, hn::Le(hn::GatherIndex(df, lines, hn::Add(i, one)), v)));
    if (hn::AllFalse(di, on)) break;
    i = hn::IfThenElse(on, hn::Add(i, one), i);
  }
  return hn::Min(i, last);
}

// The mesh's height at (s, r) of a cell (its position across the cell along X and along Z, in [0, 1])
// from the corner heights: on (a d b) where s > r, else on (a c d) (TerrainMesh::heightAt's rule).
VF CellHeight(VF s, VF r, MF lower, VF ha, VF hb, VF hc, VF hd) {
  const VF on_lower = hn::Add(hn::Add(ha, hn::Mul(hn::Sub(hb, ha), s)), hn::Mul(hn::Sub(hd, hb), r));
  const VF on_upper = hn::Add(hn::Add(ha, hn::Mul(hn::Sub(hc, ha), r)), hn::Mul(hn::Sub(hd, hc), s));
  return hn::IfThenElse(lower, on_lower, on_upper);
}

// One vector of rays: their state as they walk, a lane each.
struct Walker {
  VF t_in, f_in, s_in, r_in;  // where the ray entered its cell or block, f and (in a cell) its position there
  VI i, j;                    // its cell (also kept while it walks blocks: the cell it left last)
  VI bi, bj;                  // its block
  MF blocks;                  // walking blocks (else cells)
  MF carry;                   // f_in, s_in, r_in are the last cell's exit (else worked out afresh)
  MF active, hit;
  VF t_hit, s_hit, r_hit;
  VI cell;
};

void WalkLanes(const HeightfieldWalk::View& w, CameraLanes& L, unsigned* geom, unsigned* prim, float* u_out,
               float* v_out) {
  const DF df;
  const DI di;
  const size_t N = hn::Lanes(df);
  const VF zero = hn::Zero(df), one = Splat(1.0f), inf = Splat(std::numeric_limits<float>::infinity());
  const VI izero = hn::Zero(di), ione = hn::Set(di, 1);
  const int32_t z_at = w.nx, bx_at = w.nx + w.nz, bz_at = bx_at + w.bx + 1;
  const VF gx0 = Splat(w.lines[0]), gx1 = Splat(w.lines[w.nx - 1]);
  const VF gz0 = Splat(w.lines[z_at]), gz1 = Splat(w.lines[z_at + w.nz - 1]);
  const VF margin = Splat(HeightfieldWalk::kSkipMarginCm);
  const VI nx = hn::Set(di, w.nx), cells_a_row = hn::Set(di, w.nx - 1), bx = hn::Set(di, w.bx);
  const VI last_i = hn::Set(di, w.nx - 2), last_j = hn::Set(di, w.nz - 2);
  const VI last_bi = hn::Set(di, w.bx - 1), last_bj = hn::Set(di, w.bz - 1);
  const VI block_cells = hn::Set(di, HeightfieldWalk::kBlockCells);
  constexpr int kBlockShift = 3;
  static_assert(HeightfieldWalk::kBlockCells == 1 << kBlockShift);
  // A walk steps a line at a time, and goes up or down a level at most once a step: this bounds it.
  const size_t max_steps = 4 * size_t(w.nx + w.nz) + 16;

  for (size_t k = 0; k < L.padded; k += N) {
    const VF ox = hn::LoadU(df, L.ox.data() + k), oy = hn::LoadU(df, L.oy.data() + k), oz = hn::LoadU(df, L.oz.data() + k);
    const VF dx = hn::LoadU(df, L.dx.data() + k), dy = hn::LoadU(df, L.dy.data() + k), dz = hn::LoadU(df, L.dz.data() + k);
    const VF t_leave = hn::LoadU(df, L.t_leave.data() + k);
    const MF dx0 = hn::Eq(dx, zero), dz0 = hn::Eq(dz, zero);
    const MF dx_pos = hn::Gt(dx, zero), dz_pos = hn::Gt(dz, zero);
    const VF inv_dx = hn::Div(one, dx), inv_dz = hn::Div(one, dz);
    // The part of the ray over the grid: its slab part clipped to the grid's box in X and Z (a ray
    // parallel to an axis is in or out of that axis's range for its whole length).
    const auto axisRange = [&](VF o, VF inv, MF parallel, VF lo, VF hi, VF& t_lo, VF& t_hi) {
      const VF a = hn::Mul(hn::Sub(lo, o), inv), b = hn::Mul(hn::Sub(hi, o), inv);
      const MF inside = hn::And(hn::Ge(o, lo), hn::Le(o, hi));
      t_lo = hn::IfThenElse(parallel, hn::IfThenElse(inside, hn::Neg(inf), inf), hn::Min(a, b));
      t_hi = hn::IfThenElse(parallel, hn::IfThenElse(inside, inf, hn::Neg(inf)), hn::Max(a, b));
    };
    VF tx_lo, tx_hi, tz_lo, tz_hi;
    axisRange(ox, inv_dx, dx0, gx0, gx1, tx_lo, tx_hi);
    axisRange(oz, inv_dz, dz0, gz0, gz1, tz_lo, tz_hi);
    const VF t_end = hn::Min(t_leave, hn::Min(tx_hi, tz_hi));
    Walker w_;
    w_.t_in = hn::Max(hn::LoadU(df, L.t_enter.data() + k), hn::Max(tx_lo, tz_lo));
    w_.active = hn::And(Live(L.size, k), hn::Le(w_.t_in, t_end));
    {
      const VF x = hn::Min(hn::Max(hn::Add(ox, hn::Mul(w_.t_in, dx)), gx0), gx1);
      const VF z = hn::Min(hn::Max(hn::Add(oz, hn::Mul(w_.t_in, dz)), gz0), gz1);
      w_.i = CellOf(x, w.lines, w.nx, w.x_bucket, w.x_buckets, w.x_origin, w.x_inv_bucket);
      w_.j = CellOf(z, w.lines + z_at, w.nz, w.z_bucket, w.z_buckets, w.z_origin, w.z_inv_bucket);
    }
    w_.bi = hn::ShiftRight<kBlockShift>(w_.i), w_.bj = hn::ShiftRight<kBlockShift>(w_.j);
    const MF none = hn::Lt(one, zero);
    w_.blocks = w_.active, w_.carry = none;
    w_.f_in = zero, w_.s_in = zero, w_.r_in = zero;
    w_.hit = none;
    w_.t_hit = zero, w_.s_hit = zero, w_.r_hit = zero, w_.cell = izero;
    const VI step_i = hn::IfThenElse(hn::RebindMask(di, dx_pos), ione, hn::Set(di, -1));
    const VI step_j = hn::IfThenElse(hn::RebindMask(di, dz_pos), ione, hn::Set(di, -1));

    for (size_t step = 0; step < max_steps && !hn::AllFalse(df, w_.active); ++step) {
      const MI blocks_i = hn::RebindMask(di, w_.blocks);
      // The lines around the ray's cell or block, and where it leaves them.
      const VI ci = hn::IfThenElse(blocks_i, hn::Add(w_.bi, hn::Set(di, bx_at)), w_.i);
      const VI cj = hn::IfThenElse(blocks_i, hn::Add(w_.bj, hn::Set(di, bz_at)), hn::Add(w_.j, hn::Set(di, z_at)));
      const VF xl = hn::GatherIndex(df, w.lines, ci), xh = hn::GatherIndex(df, w.lines, hn::Add(ci, ione));
      const VF zl = hn::GatherIndex(df, w.lines, cj), zh = hn::GatherIndex(df, w.lines, hn::Add(cj, ione));
      const VF tx = hn::IfThenElse(dx0, inf, hn::Mul(hn::Sub(hn::IfThenElse(dx_pos, xh, xl), ox), inv_dx));
      const VF tz = hn::IfThenElse(dz0, inf, hn::Mul(hn::Sub(hn::IfThenElse(dz_pos, zh, zl), oz), inv_dz));
      const MF step_x = hn::Le(tx, tz);
      const VF t_next = hn::Min(tx, tz);
      const MF ended = hn::Le(t_end, t_next);
      const VF t_out = hn::Min(t_next, t_end);
      const VF y_in = hn::Add(oy, hn::Mul(w_.t_in, dy)), y_out = hn::Add(oy, hn::Mul(t_out, dy));

      // A block: skipped while the ray stays above it, else walked cell by cell.
      const VF top = hn::GatherIndex(df, w.block_max, hn::Add(hn::Mul(w_.bj, bx), w_.bi));
      const MF skip = hn::And(hn::And(w_.active, w_.blocks), hn::Gt(hn::Min(y_in, y_out), hn::Add(top, margin)));
      const MF descend = hn::AndNot(skip, hn::And(w_.active, w_.blocks));

      // A cell: does f change sign between where the ray enters it, crosses its diagonal and leaves it?
      const VI a = hn::Add(hn::Mul(w_.j, nx), w_.i), c = hn::Add(a, nx);
      const VF ha = hn::GatherIndex(df, w.heights, a), hb = hn::GatherIndex(df, w.heights, hn::Add(a, ione));
      const VF hc = hn::GatherIndex(df, w.heights, c), hd = hn::GatherIndex(df, w.heights, hn::Add(c, ione));
      const VF wx = hn::Sub(xh, xl), wz = hn::Sub(zh, zl);
      VF s_out = Clamp01(hn::Div(hn::Sub(hn::Add(ox, hn::Mul(t_out, dx)), xl), wx));
      VF r_out = Clamp01(hn::Div(hn::Sub(hn::Add(oz, hn::Mul(t_out, dz)), zl), wz));
      const MF leaves_x = hn::AndNot(ended, step_x), leaves_z = hn::AndNot(ended, hn::Not(step_x));
      s_out = hn::IfThenElse(leaves_x, hn::IfThenElseZero(dx_pos, one), s_out);
      r_out = hn::IfThenElse(leaves_z, hn::IfThenElseZero(dz_pos, one), r_out);
      const MF fresh = hn::Not(w_.carry);
      const VF s_in = hn::IfThenElse(fresh, Clamp01(hn::Div(hn::Sub(hn::Add(ox, hn::Mul(w_.t_in, dx)), xl), wx)), w_.s_in);
      const VF r_in = hn::IfThenElse(fresh, Clamp01(hn::Div(hn::Sub(hn::Add(oz, hn::Mul(w_.t_in, dz)), zl), wz)), w_.r_in);
      const VF e_in = hn::Sub(s_in, r_in), e_out = hn::Sub(s_out, r_out);
      const MF lower_in = hn::Gt(e_in, zero), lower_out = hn::Gt(e_out, zero);
      const VF f_in = hn::IfThenElse(fresh, hn::Sub(y_in, CellHeight(s_in, r_in, lower_in, ha, hb, hc, hd)), w_.f_in);
      const VF f_out = hn::Sub(y_out, CellHeight(s_out, r_out, lower_out, ha, hb, hc, hd));
      const MF crosses = hn::Xor(lower_in, lower_out);
      const VF wd = hn::Div(e_in, hn::Sub(e_in, e_out));
      const VF t_d = hn::Add(w_.t_in, hn::Mul(hn::Sub(t_out, w_.t_in), wd));
      const VF s_d = hn::Add(s_in, hn::Mul(hn::Sub(s_out, s_in), wd));
      const VF f_d = hn::Sub(hn::Add(oy, hn::Mul(t_d, dy)), hn::Add(ha, hn::Mul(hn::Sub(hd, ha), s_d)));
      const VF t_m = hn::IfThenElse(crosses, t_d, t_out), f_m = hn::IfThenElse(crosses, f_d, f_out);
      const VF s_m = hn::IfThenElse(crosses, s_d, s_out), r_m = hn::IfThenElse(crosses, s_d, r_out);
      const MF above_in = hn::Gt(f_in, zero), above_m = hn::Gt(f_m, zero), above_out = hn::Gt(f_out, zero);
      const MF first = hn::Xor(above_in, above_m);
      const MF second = hn::And(crosses, hn::Xor(above_m, above_out));
      const MF cells = hn::AndNot(w_.blocks, w_.active);
      const MF now = hn::And(cells, hn::Or(first, second));
      if (!hn::AllFalse(df, now)) {
        const VF fa = hn::IfThenElse(first, f_in, f_m), fb = hn::IfThenElse(first, f_m, f_out);
        const VF ta = hn::IfThenElse(first, w_.t_in, t_m), tb = hn::IfThenElse(first, t_m, t_out);
        const VF sa = hn::IfThenElse(first, s_in, s_m), sb = hn::IfThenElse(first, s_m, s_out);
        const VF ra = hn::IfThenElse(first, r_in, r_m), rb = hn::IfThenElse(first, r_m, r_out);
        const VF wh = hn::Div(fa, hn::Sub(fa, fb));
        w_.t_hit = hn::IfThenElse(now, hn::Add(ta, hn::Mul(hn::Sub(tb, ta), wh)), w_.t_hit);
        w_.s_hit = hn::IfThenElse(now, Clamp01(hn::Add(sa, hn::Mul(hn::Sub(sb, sa), wh))), w_.s_hit);
        w_.r_hit = hn::IfThenElse(now, Clamp01(hn::Add(ra, hn::Mul(hn::Sub(rb, ra), wh))), w_.r_hit);
        w_.cell = hn::IfThenElse(hn::RebindMask(di, now), hn::Add(hn::Mul(w_.j, cells_a_row), w_.i), w_.cell);
        w_.hit = hn::Or(w_.hit, now);
      }

      // On to the next cell or block, or off the ray's end or the grid.
      const MF moving = hn::Or(skip, hn::AndNot(now, cells));
      const MF stepping = hn::AndNot(ended, moving);
      const MI across = hn::RebindMask(di, hn::And(stepping, step_x)), along = hn::RebindMask(di, hn::AndNot(step_x, stepping));
      const MI cell_steps = hn::RebindMask(di, hn::AndNot(w_.blocks, stepping));
      const MI block_steps = hn::RebindMask(di, hn::And(w_.blocks, stepping));
      const VI i2 = hn::IfThenElse(hn::And(cell_steps, across), hn::Add(w_.i, step_i), w_.i);
      const VI j2 = hn::IfThenElse(hn::And(cell_steps, along), hn::Add(w_.j, step_j), w_.j);
      VI bi2 = hn::IfThenElse(hn::And(block_steps, across), hn::Add(w_.bi, step_i), w_.bi);
      VI bj2 = hn::IfThenElse(hn::And(block_steps, along), hn::Add(w_.bj, step_j), w_.bj);
      const auto outside = [&](VI v, VI last) { return hn::Or(hn::Lt(v, izero), hn::Gt(v, last)); };
      const MI off = hn::Or(hn::And(cell_steps, hn::Or(outside(i2, last_i), outside(j2, last_j))),
                            hn::And(block_steps, hn::Or(outside(bi2, last_bi), outside(bj2, last_bj))));
      // A cell step out of the block goes back to walking blocks, from the one it entered.
      const MI up = hn::AndNot(off, hn::And(cell_steps, hn::Or(hn::Ne(hn::ShiftRight<kBlockShift>(i2), w_.bi),
                                                                hn::Ne(hn::ShiftRight<kBlockShift>(j2), w_.bj))));
      bi2 = hn::IfThenElse(up, hn::ShiftRight<kBlockShift>(i2), bi2);
      bj2 = hn::IfThenElse(up, hn::ShiftRight<kBlockShift>(j2), bj2);
      const MF done = hn::Or(hn::And(moving, ended), hn::RebindMask(df, off));
      const MF cell_stepped = hn::RebindMask(df, cell_steps);
      w_.s_in = hn::IfThenElse(cell_stepped, hn::IfThenElse(step_x, hn::IfThenElseZero(hn::Not(dx_pos), one), s_out), s_in);
      w_.r_in = hn::IfThenElse(cell_stepped, hn::IfThenElse(step_x, r_out, hn::IfThenElseZero(hn::Not(dz_pos), one)), r_in);
      w_.f_in = hn::IfThenElse(cell_stepped, f_out, f_in);
      w_.carry = hn::Or(hn::AndNot(skip, w_.carry), cell_stepped);
      w_.t_in = hn::IfThenElse(stepping, t_out, w_.t_in);
      // Off the grid: keep the last indices, so every lane still gathers within the arrays.
      const MI keep = hn::Not(off);
      w_.i = hn::IfThenElse(keep, i2, w_.i), w_.j = hn::IfThenElse(keep, j2, w_.j);
      w_.bi = hn::IfThenElse(keep, bi2, w_.bi), w_.bj = hn::IfThenElse(keep, bj2, w_.bj);
      // Down into a block: from the cell it was left by, when it was (carry), else the cell where the ray
      // enters it, kept within the block.
      const MF found = hn::AndNot(w_.carry, descend);
      if (!hn::AllFalse(df, found)) {
        const VF x = hn::Add(ox, hn::Mul(w_.t_in, dx)), z = hn::Add(oz, hn::Mul(w_.t_in, dz));
        const VI fi = CellOf(x, w.lines, w.nx, w.x_bucket, w.x_buckets, w.x_origin, w.x_inv_bucket);
        const VI fj = CellOf(z, w.lines + z_at, w.nz, w.z_bucket, w.z_buckets, w.z_origin, w.z_inv_bucket);
        const VI i0 = hn::Mul(w_.bi, block_cells), j0 = hn::Mul(w_.bj, block_cells);
        const VI ci_found = hn::Min(hn::Max(fi, i0), hn::Min(hn::Add(i0, hn::Sub(block_cells, ione)), last_i));
        const VI cj_found = hn::Min(hn::Max(fj, j0), hn::Min(hn::Add(j0, hn::Sub(block_cells, ione)), last_j));
        const MI found_i = hn::RebindMask(di, found);
        w_.i = hn::IfThenElse(found_i, ci_found, w_.i), w_.j = hn::IfThenElse(found_i, cj_found, w_.j);
      }
      w_.blocks = hn::Or(hn::AndNot(descend, w_.blocks), hn::RebindMask(df, up));
      w_.active = hn::AndNot(hn::Or(done, now), w_.active);
    }

    const VI miss = hn::Set(di, -1);
    const MI hit_i = hn::RebindMask(di, w_.hit);
    hn::StoreU(hn::IfThenElse(hit_i, izero, miss), di, reinterpret_cast<int32_t*>(geom) + k);
    hn::StoreU(w_.cell, di, reinterpret_cast<int32_t*>(prim) + k);
    hn::StoreU(w_.s_hit, df, u_out + k);
    hn::StoreU(hn::Sub(one, w_.r_hit), df, v_out + k);
    hn::StoreU(hn::IfThenElse(w_.hit, w_.t_hit, t_leave), df, L.t_leave.data() + k);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace stirrup::render
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stirrup::render {

HWY_EXPORT(WalkLanes);

namespace {

// GridLineIndex's buckets in floats: no wider than the narrowest cell, each naming the last line at or
// before its start.
void bucketLines(const float* lines, int32_t n, std::vector<int32_t>& bucket, float& origin, float& inv_bucket) {
  float narrowest = std::numeric_limits<float>::infinity();
  for (int32_t i = 0; i + 1 < n; ++i) narrowest = std::min(narrowest, lines[i + 1] - lines[i]);
  const double span = double(lines[n - 1]) - double(lines[0]);
  // A grid far finer than its extent would need too many buckets: wider ones are settled by CellOf's loops.
  const double width = std::max(double(narrowest), span / double(1 << 22));
  origin = lines[0];
  inv_bucket = float(1.0 / width);
  bucket.resize(std::size_t(std::ceil(span / width)) + 2);
  int32_t i = 0;
  for (std::size_t b = 0; b < bucket.size(); ++b) {
    const float start = float(double(origin) + double(b) * width);
    while (i + 2 < n && lines[i + 1] <= start) ++i;
    bucket[b] = i;
  }
}

}  // namespace

HeightfieldWalk::HeightfieldWalk(const TerrainMesh& mesh) {
  const std::size_t nx = mesh.xs.size(), nz = mesh.zs.size();
  if (nx < 2 || nz < 2 || mesh.positions.size() != nx * nz)
    throw std::invalid_argument("HeightfieldWalk: expected a grid of at least 2 x 2 vertices, " + std::to_string(nx) +
                                " x " + std::to_string(nz) + " lines for " + std::to_string(mesh.positions.size()) +
                                " vertices");
  if ((nx - 1) * (nz - 1) >= (std::size_t(1) << 24))
    throw std::invalid_argument("HeightfieldWalk: " + std::to_string((nx - 1) * (nz - 1)) +
                                " cells, expected fewer than 2^24");
  nx_ = int32_t(nx), nz_ = int32_t(nz);
  bx_ = (nx_ - 1 + kBlockCells - 1) / kBlockCells, bz_ = (nz_ - 1 + kBlockCells - 1) / kBlockCells;
  lines_.reserve(nx + nz + std::size_t(bx_ + bz_) + 2);
  for (const double x : mesh.xs) lines_.push_back(float(x));
  for (const double z : mesh.zs) lines_.push_back(float(z));
  for (int32_t b = 0; b <= bx_; ++b) lines_.push_back(float(mesh.xs[std::size_t(std::min(b * kBlockCells, nx_ - 1))]));
  for (int32_t b = 0; b <= bz_; ++b) lines_.push_back(float(mesh.zs[std::size_t(std::min(b * kBlockCells, nz_ - 1))]));
  const auto ascending = [](const float* v, std::size_t n) {
    for (std::size_t i = 0; i + 1 < n; ++i)
      if (!(v[i] < v[i + 1])) return false;
    return true;
  };
  if (!ascending(lines_.data(), nx) || !ascending(lines_.data() + nx, nz))
    throw std::invalid_argument("HeightfieldWalk: grid lines not strictly ascending in floats");
  heights_.resize(nx * nz);
  for (std::size_t v = 0; v < heights_.size(); ++v) heights_[v] = mesh.positions[v].y;
  block_max_.assign(std::size_t(bx_) * std::size_t(bz_), -std::numeric_limits<float>::infinity());
  for (int32_t j = 0; j < nz_; ++j) {
    for (int32_t i = 0; i < nx_; ++i) {
      // A vertex on a block's edge is a corner of the blocks on either side.
      const float h = heights_[std::size_t(j) * nx + std::size_t(i)];
      for (int32_t bj = std::max(0, (j - 1) / kBlockCells); bj <= std::min(bz_ - 1, j / kBlockCells); ++bj)
        for (int32_t bi = std::max(0, (i - 1) / kBlockCells); bi <= std::min(bx_ - 1, i / kBlockCells); ++bi) {
          float& top = block_max_[std::size_t(bj) * std::size_t(bx_) + std::size_t(bi)];
          top = std::max(top, h);
        }
    }
  }
  bucketLines(lines_.data(), nx_, x_bucket_, x_origin_, x_inv_bucket_);
  bucketLines(lines_.data() + nx, nz_, z_bucket_, z_origin_, z_inv_bucket_);
}

HeightfieldWalk::View HeightfieldWalk::view() const {
  View v;
  v.lines = lines_.data(), v.heights = heights_.data(), v.block_max = block_max_.data();
  v.x_bucket = x_bucket_.data(), v.z_bucket = z_bucket_.data();
  v.nx = nx_, v.nz = nz_, v.bx = bx_, v.bz = bz_;
  v.x_buckets = int32_t(x_bucket_.size()), v.z_buckets = int32_t(z_bucket_.size());
  v.x_origin = x_origin_, v.x_inv_bucket = x_inv_bucket_, v.z_origin = z_origin_, v.z_inv_bucket = z_inv_bucket_;
  return v;
}

void HeightfieldWalk::trace(CameraLanes& lanes, unsigned* geom, unsigned* prim, float* u, float* v) const {
  HWY_DYNAMIC_DISPATCH(WalkLanes)(view(), lanes, geom, prim, u, v);
}

}  // namespace stirrup::render
#endif  // HWY_ONCE
