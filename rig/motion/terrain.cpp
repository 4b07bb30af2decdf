#include "rig/motion/terrain.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "rig/error.h"
#include "rig/motion/noise.h"

namespace stirrup::rig {
namespace {

double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
double fadeDerivative(double t) { return 30.0 * t * t * (t * (t - 2.0) + 1.0); }


// One octave of 2-D value noise in [-1, 1] with its gradient (per lattice unit).
double noise2(std::uint32_t seed, double x, double z, double& gx, double& gz) {
  const double ix = std::floor(x), iz = std::floor(z);
  const double fx = x - ix, fz = z - iz;
  const auto i = static_cast<std::int64_t>(ix), k = static_cast<std::int64_t>(iz);
  auto at = [&](std::int64_t a, std::int64_t b) { return hashSigned(seed, a, b); };
  const double v00 = at(i, k), v10 = at(i + 1, k), v01 = at(i, k + 1), v11 = at(i + 1, k + 1);
  const double u = fade(fx), w = fade(fz), du = fadeDerivative(fx), dw = fadeDerivative(fz);
  const double a = v00 + (v10 - v00) * u, b = v01 + (v11 - v01) * u;
  gx = du * ((v10 - v00) + ((v11 - v01) - (v10 - v00)) * w);
  gz = dw * (b - a);
  return a + (b - a) * w;
}

}  // namespace

Terrain Terrain::hills(const HillsParams& p, const std::string& source) {
  if (!(std::isfinite(p.amplitude_cm) && p.amplitude_cm >= 0.0 && p.amplitude_cm <= 5000.0))
    throw InputError(source + ": terrain.hills.amplitude_cm: expected a height from 0 to 5000 cm, got " + numberText(p.amplitude_cm));
  if (!(std::isfinite(p.wavelength_cm) && p.wavelength_cm >= 100.0 && p.wavelength_cm <= 1e6))
    throw InputError(source + ": terrain.hills.wavelength_cm: expected a length from 100 to 1000000 cm, got " +
                     numberText(p.wavelength_cm));
  if (p.octaves < 1 || p.octaves > 6)
    throw InputError(source + ": terrain.hills.octaves: expected a whole number from 1 to 6, got " + std::to_string(p.octaves));
  Terrain t;
  t.hills_ = true;
  t.params_ = p;
  double sum = 0.0;
  for (int o = 0; o < p.octaves; ++o) sum += std::ldexp(1.0, -o);
  t.scale_ = 1.0 / sum;
  return t;
}

Terrain Terrain::mesh(std::shared_ptr<const TerrainMesh> mesh) {
  Terrain t;
  t.mesh_ = std::move(mesh);
  return t;
}

double Terrain::height(double x, double z) const {
  if (mesh_) {
    const auto hit = mesh_->at(x, z);
    return hit ? hit->height_cm : mesh_->lowest();
  }
  if (!hills_) return 0.0;
  double dx = 0.0, dz = 0.0;
  double h = 0.0;
  for (int o = 0; o < params_.octaves; ++o) {
    const double f = std::ldexp(1.0, o) / params_.wavelength_cm;
    h += std::ldexp(1.0, -o) * noise2(params_.seed + std::uint32_t(o) * 7919u, x * f, z * f, dx, dz);
  }
  return params_.amplitude_cm * scale_ * h;
}

void Terrain::gradient(double x, double z, double& gx, double& gz) const {
  gx = gz = 0.0;
  if (mesh_) {
    // The triangle's plane: flat between its edges, so the slope steps at them.
    if (const auto hit = mesh_->at(x, z)) gx = -hit->normal.x / hit->normal.y, gz = -hit->normal.z / hit->normal.y;
    return;
  }
  if (!hills_) return;
  for (int o = 0; o < params_.octaves; ++o) {
    const double f = std::ldexp(1.0, o) / params_.wavelength_cm;
    double dx = 0.0, dz = 0.0;
    noise2(params_.seed + std::uint32_t(o) * 7919u, x * f, z * f, dx, dz);
    gx += std::ldexp(1.0, -o) * dx * f;
    gz += std::ldexp(1.0, -o) * dz * f;
  }
  gx *= params_.amplitude_cm * scale_;
  gz *= params_.amplitude_cm * scale_;
}

glm::dvec3 Terrain::normal(double x, double z) const {
  double gx = 0.0, gz = 0.0;
  gradient(x, z, gx, gz);
  return glm::normalize(glm::dvec3(-gx, 1.0, -gz));
}

void Terrain::triangulate(glm::dvec2 lower, glm::dvec2 upper, double cell_cm, int max_cells,
                          std::vector<glm::vec3>& vertices, std::vector<std::uint32_t>& indices) const {
  vertices.clear();
  indices.clear();
  if (mesh_) {
    for (const glm::dvec3& v : mesh_->vertices()) vertices.push_back(glm::vec3(v));
    indices = mesh_->indices();
    return;
  }
  if (flat()) return;
  const glm::dvec2 size = glm::max(upper - lower, glm::dvec2(1.0));
  const double cell = std::max(cell_cm, std::max(size.x, size.y) / std::max(max_cells, 1));
  const int nx = std::max(1, int(std::ceil(size.x / cell))), nz = std::max(1, int(std::ceil(size.y / cell)));
  for (int z = 0; z <= nz; ++z)
    for (int x = 0; x <= nx; ++x) {
      const double px = lower.x + x * cell, pz = lower.y + z * cell;
      vertices.push_back(glm::vec3(float(px), float(height(px, pz)), float(pz)));
    }
  const auto row = std::uint32_t(nx + 1);
  for (int z = 0; z < nz; ++z)
    for (int x = 0; x < nx; ++x) {
      const auto k = std::uint32_t(z) * row + std::uint32_t(x);
      // Wound counter-clockwise seen from above (+Y): glTF's front face up.
      indices.insert(indices.end(), {k, k + row, k + 1, k + 1, k + row, k + row + 1});
    }
}

}  // namespace stirrup::rig
