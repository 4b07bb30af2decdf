#include "render/tracer/heightfield_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace stirrup::render {
namespace {

// The lines outward from `edge` (exclusive) to edge + sign * extent, cells growing from `spacing`.
void growOutward(double edge, double sign, double spacing, const TerrainMeshParams& p, std::vector<double>& out) {
  double cell = spacing, reached = 0.0;
  while (reached < p.extent_cm) {
    cell *= p.growth;
    if (reached < p.mid_reach_cm) cell = std::min(cell, std::max(p.mid_cell_cm, spacing));
    reached = std::min(p.extent_cm, reached + cell);
    out.push_back(edge + sign * reached);
  }
}

}  // namespace

GridLineIndex::GridLineIndex(const std::vector<double>& lines) {
  if (lines.size() < 2) return;
  double narrowest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) narrowest = std::min(narrowest, lines[i + 1] - lines[i]);
  if (!(narrowest > 0.0)) return;
  const double span = lines.back() - lines.front();
  const double buckets = std::ceil(span / narrowest) + 1.0;
  if (!(buckets < 4.0e7)) return;  // absurdly fine: left to binary search
  origin_ = lines.front();
  inv_bucket_ = 1.0 / narrowest;
  first_.resize(std::size_t(buckets) + 1);
  std::size_t i = 0;
  for (std::size_t b = 0; b < first_.size(); ++b) {
    const double start = origin_ + double(b) * narrowest;
    while (i + 1 < lines.size() && lines[i + 1] <= start) ++i;
    first_[b] = uint32_t(i);
  }
}

std::size_t GridLineIndex::cell(const std::vector<double>& lines, double v) const {
  std::size_t i;
  if (first_.empty()) {
    i = std::size_t(std::upper_bound(lines.begin(), lines.end(), v) - lines.begin());
    i = i == 0 ? 0 : i - 1;
  } else {
    const double f = (v - origin_) * inv_bucket_;
    i = first_[std::size_t(std::clamp(f, 0.0, double(first_.size() - 1)))];
    // The bucket's rounding may be one off either way; a bucket is never wider than a cell.
    while (i > 0 && lines[i] > v) --i;
    while (i + 1 < lines.size() && lines[i + 1] <= v) ++i;
  }
  return std::min(i, lines.size() - 2);
}

std::vector<double> terrainGridLines(double lo, double hi, double spacing, const TerrainMeshParams& params) {
  if (!(spacing > 0.0) || !(lo <= hi) || !(params.growth > 1.0))
    throw std::invalid_argument("terrainGridLines: needs lo <= hi, spacing > 0 and growth > 1");
  const double first = std::floor(lo / spacing) * spacing, last = std::ceil(hi / spacing) * spacing;
  std::vector<double> below, lines;
  growOutward(first, -1.0, spacing, params, below);
  lines.assign(below.rbegin(), below.rend());
  const long cells = std::max(1L, std::lround((last - first) / spacing));
  for (long i = 0; i <= cells; ++i) lines.push_back(first + double(i) * spacing);
  growOutward(lines.back(), 1.0, spacing, params, lines);
  return lines;
}

TerrainMesh makeTerrainMesh(const rig::Terrain& terrain, const GroundRegion& region, const TerrainMeshParams& params) {
  const double width = std::max(region.x1 - region.x0, 0.0), depth = std::max(region.z1 - region.z0, 0.0);
  double spacing = params.fine_spacing_cm;
  if ((width / spacing + 1.0) * (depth / spacing + 1.0) > params.max_fine_vertices)
    spacing = std::max(spacing, std::sqrt(width * depth / params.max_fine_vertices) * 1.01);
  const std::vector<double> xs = terrainGridLines(region.x0, region.x0 + width, spacing, params);
  const std::vector<double> zs = terrainGridLines(region.z0, region.z0 + depth, spacing, params);
  // The renderer finds a hit cell's row in floats (groundHitLanes): exact below 2^24 cells.
  if (double(xs.size() - 1) * double(zs.size() - 1) >= double(1 << 24))
    throw std::invalid_argument("terrain mesh: " + std::to_string(xs.size() - 1) + " x " + std::to_string(zs.size() - 1) +
                                " cells, expected fewer than 2^24 (a wider fine spacing)");
  TerrainMesh mesh;
  mesh.xs = xs;
  mesh.zs = zs;
  mesh.x_index = GridLineIndex(mesh.xs);
  mesh.z_index = GridLineIndex(mesh.zs);
  const std::size_t nx_lines = xs.size();
  mesh.positions.resize(xs.size() * zs.size());
  mesh.normals.resize(xs.size() * zs.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, zs.size()), [&](const tbb::blocked_range<std::size_t>& rows) {
    for (std::size_t j = rows.begin(); j < rows.end(); ++j) {
      for (std::size_t i = 0; i < nx_lines; ++i) {
        mesh.positions[j * nx_lines + i] = glm::vec3(float(xs[i]), float(terrain.height(xs[i], zs[j])), float(zs[j]));
        mesh.normals[j * nx_lines + i] = glm::vec3(terrain.normal(xs[i], zs[j]));
      }
    }
  });
  mesh.min_height = std::numeric_limits<float>::infinity();
  mesh.max_height = -std::numeric_limits<float>::infinity();
  for (const glm::vec3& p : mesh.positions) {
    mesh.min_height = std::min(mesh.min_height, p.y);
    mesh.max_height = std::max(mesh.max_height, p.y);
  }
  const uint32_t nx = uint32_t(xs.size());
  mesh.indices.reserve((xs.size() - 1) * (zs.size() - 1) * 6);
  for (uint32_t j = 0; j + 1 < zs.size(); ++j) {
    for (uint32_t i = 0; i + 1 < nx; ++i) {
      const uint32_t a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;  // a (x0 z0), b (x1 z0), c (x0 z1), d (x1 z1)
      // The flat ground quad's winding (embree_scene.cpp): (x0 z0) (x0 z1) (x1 z1), (x0 z0) (x1 z1) (x1 z0).
      mesh.indices.insert(mesh.indices.end(), {a, c, d, a, d, b});
    }
  }
  return mesh;
}

double TerrainMesh::heightAt(double x, double z) const {
  if (xs.size() < 2 || zs.size() < 2 || !(x >= xs.front() && x <= xs.back() && z >= zs.front() && z <= zs.back()))
    return -std::numeric_limits<double>::infinity();
  const std::size_t i = x_index.cell(xs, x), j = z_index.cell(zs, z);
  const std::size_t nx = xs.size(), a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
  const double tx = (x - xs[i]) / (xs[i + 1] - xs[i]), tz = (z - zs[j]) / (zs[j + 1] - zs[j]);
  const double ha = positions[a].y, hb = positions[b].y, hc = positions[c].y, hd = positions[d].y;
  // The cell's two triangles meet on its diagonal a (x0 z0) - d (x1 z1): (a c d) where tz >= tx, (a d b) below.
  if (tz >= tx) return ha + tz * (hc - ha) + tx * (hd - hc);
  return ha + tx * (hb - ha) + tz * (hd - hb);
}

double TerrainMesh::cellSlope(std::size_t i, std::size_t j) const {
  const std::size_t nx = xs.size(), a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
  const double dx = xs[i + 1] - xs[i], dz = zs[j + 1] - zs[j];
  const double ha = positions[a].y, hb = positions[b].y, hc = positions[c].y, hd = positions[d].y;
  const double upper = std::hypot((hd - hc) / dx, (hc - ha) / dz);  // (a c d)
  const double lower = std::hypot((hb - ha) / dx, (hd - hb) / dz);  // (a d b)
  return std::max(upper, lower);
}

namespace {

// How far a ray origin may be from the point the map is asked about (the renderer's ray offset: 2e-3 cm
// plus 3e-5 of the coordinates, under 1 cm within 300 m; render/tracer/shading_lanes.cpp). Farther points are
// not answered from the map (traced); where the sun is open everywhere there is no map to miss, and a
// point of any slack is open once its origins are known on or above the mesh.
constexpr double kMaxSlackCm = 1.0;
// Heights are stored in floats: this much more is asked of a point than the bound in doubles says.
constexpr double kHeightEpsilonCm = 0.01;
// The lanes' test (laneView) finds a point's texel and its height less the slack in floats: over the
// map (a kilometre at most) its texel is off by well under this much of the horizontal slack
// the map allows, and this much more height is asked of the point for its rounding.
constexpr double kLaneSlackMarginCm = 0.05;
constexpr double kLaneHeightMarginCm = 1e-3;

// `v` stored in a float rounded up: the map's bounds may only grow.
float roundedUp(double v) {
  float stored = float(v);
  if (double(stored) < v) stored = std::nextafter(stored, std::numeric_limits<float>::infinity());
  return stored;
}

// The steepest slope of any cell of the mesh.
double steepestCellSlope(const TerrainMesh& mesh) {
  const std::size_t cells_x = mesh.xs.size() - 1, cells_z = mesh.zs.size() - 1;
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, cells_z), 0.0,
      [&](const tbb::blocked_range<std::size_t>& rows, double most) {
        for (std::size_t j = rows.begin(); j < rows.end(); ++j)
          for (std::size_t i = 0; i < cells_x; ++i) most = std::max(most, mesh.cellSlope(i, j));
        return most;
      },
      [](double a, double b) { return std::max(a, b); });  // exact in any order
}

// The sun's azimuth on the ground (ax, az) and how far a disc ray's ground track can turn from it, as a
// chord of the unit circle.
struct SunTrack {
  double ax = 1.0, az = 0.0, chord = 2.0;
};

SunTrack sunTrack(const glm::dvec3& toward_sun, double length, double elevation, double angular_radius_rad) {
  SunTrack t;
  const double horizontal = std::hypot(toward_sun.x, toward_sun.z);
  if (horizontal > 0.0) t.ax = toward_sun.x / horizontal, t.az = toward_sun.z / horizontal;
  const double cos_e = horizontal / length;
  if (angular_radius_rad < std::numbers::pi / 2.0 - elevation && cos_e > 0.0) {
    const double sin_phi = std::min(1.0, std::sin(angular_radius_rad) / cos_e);
    t.chord = std::sqrt(std::max(0.0, 2.0 - 2.0 * std::sqrt(1.0 - sin_phi * sin_phi)));
  }
  return t;
}

// The map's texels: nx by nz squares of `texel` cm from (x0, z0).
struct TexelGrid {
  double x0 = 0.0, z0 = 0.0, texel = 1.0;
  std::size_t nx = 0, nz = 0;
  double centreX(std::size_t ti) const { return x0 + (double(ti) + 0.5) * texel; }
  double centreZ(std::size_t tj) const { return z0 + (double(tj) + 0.5) * texel; }
};

// The mesh's cells [first, last) that `lines` (cell boundaries) put within [lo, hi].
std::pair<std::size_t, std::size_t> cellRange(const std::vector<double>& lines, double lo, double hi) {
  const std::size_t first = std::size_t(std::max<std::ptrdiff_t>(
      0, std::upper_bound(lines.begin(), lines.end(), lo) - lines.begin() - 1));
  const std::size_t last = std::min<std::size_t>(std::lower_bound(lines.begin(), lines.end(), hi) - lines.begin(),
                                                 lines.size() - 1);
  return {first, last};
}

// Near field: the fastest any triangle within near + rho of a texel's centre rises along a disc ray's ground
// track (its gradient along the sun's azimuth, plus its steepness times the track's turn), the maximum
// over a box of cells taken row by row (each cell row's maximum over each texel column's cells), then
// over the rows of each texel row's box.
class NearFieldRise {
 public:
  NearFieldRise(const TerrainMesh& mesh, const SunTrack& track, const TexelGrid& grid, double near, double rho) : nx_(grid.nx) {
    std::vector<std::pair<std::size_t, std::size_t>> columns(grid.nx);
    rows_.resize(grid.nz);
    for (std::size_t ti = 0; ti < grid.nx; ++ti)
      columns[ti] = cellRange(mesh.xs, grid.centreX(ti) - near - rho, grid.centreX(ti) + near + rho);
    for (std::size_t tj = 0; tj < grid.nz; ++tj)
      rows_[tj] = cellRange(mesh.zs, grid.centreZ(tj) - near - rho, grid.centreZ(tj) + near + rho);
    row_first_ = rows_.front().first;  // boxes are monotone
    const std::size_t row_last = rows_.back().second;
    const std::size_t col_first = columns.front().first, col_last = columns.back().second;
    row_rise_.resize((row_last - row_first_) * nx_);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(row_first_, row_last), [&](const tbb::blocked_range<std::size_t>& r) {
      std::vector<double> rise(col_last - col_first);
      for (std::size_t j = r.begin(); j < r.end(); ++j) {
        for (std::size_t i = col_first; i < col_last; ++i) rise[i - col_first] = cellRise(mesh, track, i, j);
        for (std::size_t ti = 0; ti < nx_; ++ti) {
          double most = 0.0;
          for (std::size_t i = columns[ti].first; i < columns[ti].second; ++i) most = std::max(most, rise[i - col_first]);
          row_rise_[(j - row_first_) * nx_ + ti] = roundedUp(most);
        }
      }
    });
  }

  // The fastest rise near texel (ti, tj), or the first row's maximum at or past `enough`.
  double at(std::size_t ti, std::size_t tj, double enough) const {
    double local = 0.0;
    for (std::size_t j = rows_[tj].first; j < rows_[tj].second && local < enough; ++j)
      local = std::max(local, double(row_rise_[(j - row_first_) * nx_ + ti]));
    return local;
  }

 private:
  // The faster of cell (i, j)'s two triangles along the track.
  static double cellRise(const TerrainMesh& mesh, const SunTrack& track, std::size_t i, std::size_t j) {
    const std::size_t n = mesh.xs.size(), a = j * n + i, b = a + 1, c = a + n, d = c + 1;
    const double dx = mesh.xs[i + 1] - mesh.xs[i], dz = mesh.zs[j + 1] - mesh.zs[j];
    const double ha = mesh.positions[a].y, hb = mesh.positions[b].y, hc = mesh.positions[c].y, hd = mesh.positions[d].y;
    auto rise = [&](double gx, double gz) { return gx * track.ax + gz * track.az + std::hypot(gx, gz) * track.chord; };
    return std::max(rise((hd - hc) / dx, (hc - ha) / dz), rise((hb - ha) / dx, (hd - hb) / dz));  // (a c d), (a d b)
  }

  std::size_t nx_, row_first_ = 0;
  std::vector<std::pair<std::size_t, std::size_t>> rows_;  // per texel row: its box's cell rows
  std::vector<float> row_rise_;                            // [cell row - row_first][texel column]
};

// Far field: the highest the mesh comes above a line rising tan_far along the sun's track, from s0 on.
// With a the sun's azimuth and G(q) = max over s >= 0 of [mesh(q + s a) - s tan_far], a texel's far field
// is G(p + s0 a) - s0 tan_far. G is swept once along lines parallel to a, `step` apart (G(q) =
// max(mesh(q), G(q + step a) - step tan_far) at the samples), instead of marching from every texel.
// Between the samples along a line G rises at most a known amount; off them, G changes no faster than
// the mesh's steepest slope (each shifted copy of the mesh does not), so a texel takes the nearest sample
// plus steepest times the distance to it.
class FarFieldSweep {
 public:
  // G over the points s0 along the track from every texel, sampled `step` apart and `run` past them.
  FarFieldSweep(const TerrainMesh& mesh, const SunTrack& track, const TexelGrid& grid, double s0, double step,
                double run, double tan_far)
      : ax_(track.ax), az_(track.az), wx_(-track.az), wz_(track.ax), step_(step) {
    double u_hi = -std::numeric_limits<double>::infinity(), v_hi = u_hi;
    u_lo_ = v_lo_ = std::numeric_limits<double>::infinity();
    for (const double cx : {grid.x0, grid.x0 + double(grid.nx) * grid.texel})
      for (const double cz : {grid.z0, grid.z0 + double(grid.nz) * grid.texel}) {
        const double qx = cx + s0 * ax_, qz = cz + s0 * az_;
        u_lo_ = std::min(u_lo_, qx * ax_ + qz * az_), u_hi = std::max(u_hi, qx * ax_ + qz * az_);
        v_lo_ = std::min(v_lo_, qx * wx_ + qz * wz_), v_hi = std::max(v_hi, qx * wx_ + qz * wz_);
      }
    lines_ = std::size_t(std::ceil((v_hi - v_lo_) / step)) + 1;
    samples_ = std::size_t(std::ceil((u_hi - u_lo_ + run + step) / step)) + 1;
    swept_.resize(lines_ * samples_);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lines_), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t l = r.begin(); l < r.end(); ++l) {
        const double v = v_lo_ + double(l) * step;
        double g = -std::numeric_limits<double>::infinity();
        for (std::size_t k = samples_; k-- > 0;) {
          const double u = u_lo_ + double(k) * step;
          g = std::max(mesh.heightAt(u * ax_ + v * wx_, u * az_ + v * wz_), g - step * tan_far);
          swept_[l * samples_ + k] = roundedUp(g);
        }
      }
    });
  }

  // G at the sample nearest (qx, qz), and the ground distance to that sample.
  struct Sample {
    double g, off;
  };
  Sample nearest(double qx, double qz) const {
    const double u = qx * ax_ + qz * az_, v = qx * wx_ + qz * wz_;
    const std::size_t k = std::min(samples_ - 1, std::size_t(std::max(0.0, std::round((u - u_lo_) / step_))));
    const std::size_t l = std::min(lines_ - 1, std::size_t(std::max(0.0, std::round((v - v_lo_) / step_))));
    return {double(swept_[l * samples_ + k]), std::hypot(u - (u_lo_ + double(k) * step_), v - (v_lo_ + double(l) * step_))};
  }

 private:
  double ax_, az_, wx_, wz_, step_;  // along the track (a) and across it (w)
  double u_lo_, v_lo_;
  std::size_t lines_ = 0, samples_ = 0;
  std::vector<float> swept_;  // [line][sample]
};

}  // namespace

SunHorizon::SunHorizon(const TerrainMesh& mesh, const glm::dvec3& toward_sun, double angular_radius_rad,
                       const GroundRegion& region, const SunHorizonParams& params)
    : mesh_(&mesh) {
  if (mesh.xs.size() < 2 || mesh.zs.size() < 2) return;
  steepest_ = steepestCellSlope(mesh);
  const double length = std::sqrt(toward_sun.x * toward_sun.x + toward_sun.y * toward_sun.y + toward_sun.z * toward_sun.z);
  if (!(length > 0.0)) return;
  const double elevation = std::asin(std::clamp(toward_sun.y / length, -1.0, 1.0));
  const double low = elevation - angular_radius_rad;  // the lowest ray of the disc
  if (!(low > 0.0)) return;                            // the disc reaches the horizon: nothing is known
  tan_low_ = std::tan(low);
  if (steepest_ < tan_low_) {
    everywhere_open_ = true;
    return;
  }
  const SunTrack track = sunTrack(toward_sun, length, elevation, angular_radius_rad);
  const double tan_far = tan_low_ - steepest_ * track.chord;  // the far field's slowest rise, against the axis's track
  if (!(tan_far > 0.0)) return;

  const double x0 = region.x0 - params.margin_cm, z0 = region.z0 - params.margin_cm;
  const double width = std::max(region.x1 - region.x0, 0.0) + 2.0 * params.margin_cm;
  const double depth = std::max(region.z1 - region.z0, 0.0) + 2.0 * params.margin_cm;
  texel_ = params.texel_cm;
  if ((width / texel_ + 1.0) * (depth / texel_ + 1.0) > params.max_texels)
    texel_ = std::sqrt(width * depth / params.max_texels) * 1.01;
  x0_ = x0, z0_ = z0;
  nx_ = std::size_t(std::ceil(width / texel_)), nz_ = std::size_t(std::ceil(depth / texel_));
  const TexelGrid grid{x0_, z0_, texel_, nx_, nz_};
  // A point asked about is within the texel (half-diagonal) and the slack of its centre.
  rho_ = texel_ * std::sqrt(0.5) + kMaxSlackCm * std::sqrt(2.0);
  const double near = std::max(params.near_cm, texel_);  // s0
  const double step = 0.5 * texel_;                      // the far field's samples along the sun's track
  const double run = (double(mesh.max_height) - double(mesh.min_height)) / tan_far + step;  // past it nothing rises above the lowest point
  const double between = (steepest_ + tan_far) * step * 0.5;  // the most the maximised function rises between samples
  const NearFieldRise near_field(mesh, track, grid, near, rho_);
  const FarFieldSweep far_field(mesh, track, grid, near, step, run, tan_far);

  clear_.assign(nx_ * nz_, std::numeric_limits<float>::infinity());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nz_), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t tj = r.begin(); tj < r.end(); ++tj) {
      const double pz = grid.centreZ(tj);
      for (std::size_t ti = 0; ti < nx_; ++ti) {
        if (!(near_field.at(ti, tj, tan_low_) < tan_low_)) continue;  // too steep near by to tell: traced
        const double px = grid.centreX(ti);
        const FarFieldSweep::Sample far = far_field.nearest(px + near * track.ax, pz + near * track.az);
        const double highest = far.g + between + steepest_ * far.off - near * tan_far;
        clear_[tj * nx_ + ti] = roundedUp(highest + steepest_ * rho_ + kHeightEpsilonCm);
      }
    }
  });
}

bool SunHorizon::open(const glm::vec3& p, float slack, bool above_mesh_known) const {
  if (!above_mesh_known) return openAbove(p, slack, mesh_->heightAt(p.x, p.z));
  if (!answers(slack)) return false;
  return openOnMesh(p, slack);
}

bool SunHorizon::answers(float slack) const {
  return everywhere_open_ ? !std::isnan(slack) : double(slack) <= kMaxSlackCm;
}

bool SunHorizon::openAbove(const glm::vec3& p, float slack, double mesh_height) const {
  if (!answers(slack)) return false;
  // Every point within the slack must be on or above the mesh, which rises at most `steepest_` per unit run.
  const double floor = mesh_height + steepest_ * double(slack) * std::sqrt(2.0) + kHeightEpsilonCm;
  if (!(double(p.y) - double(slack) >= floor)) return false;
  return openOnMesh(p, slack);
}

SunHorizon::LaneView SunHorizon::laneView() const {
  LaneView v;
  v.everywhere_open = everywhere_open_;
  v.max_slack = everywhere_open_ ? std::numeric_limits<float>::infinity() : float(kMaxSlackCm - kLaneSlackMarginCm);
  v.height_margin = float(kLaneHeightMarginCm);
  if (nx_ > 0 && !everywhere_open_) {
    v.clear = clear_.data();
    v.x0 = float(x0_), v.z0 = float(z0_), v.inv_texel = float(1.0 / texel_);
    v.nx = int32_t(nx_), v.nz = int32_t(nz_);
  }
  return v;
}

bool SunHorizon::openOnMesh(const glm::vec3& p, float slack) const {
  if (everywhere_open_) return true;
  if (nx_ == 0) return false;
  const double fx = (double(p.x) - x0_) / texel_, fz = (double(p.z) - z0_) / texel_;
  if (!(fx >= 0.0 && fz >= 0.0 && fx < double(nx_) && fz < double(nz_))) return false;
  return double(p.y) - double(slack) > double(clear_[std::size_t(fz) * nx_ + std::size_t(fx)]);
}

}  // namespace stirrup::render
