// A 3D test cloud: a randomly perturbed fluid lattice in a closed box with a single layer of
// wall particles on its faces, edges and corners, and brute-force neighbours (the 3D operator and
// wall tests share it).
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "particula/core/types3.hpp"

namespace box3 {

using namespace particula;

/// The box's far corner (the near one is the origin).
inline const Vec3 kBoxHi{1.2, 1.0, 0.9};

enum class Where { Interior, NearWall, Wall };

struct Cloud {
  std::vector<Vec3> x;
  std::vector<real> w;  // volumes
  std::vector<Where> where;
  std::vector<Vec3> normal;  // walls: the unit normal into the fluid (edges and corners: the mean of their
                             // faces'); fluid: 0
};

/// A 1.2 x 1 x 0.9 box at d0 = 0.1: fluid on the cell-centred lattice moved by up to 20 % of d0
/// in each direction (seeded); a single layer of wall particles at the centres of the faces' d0 x d0
/// squares, along the edges and at the corners.
inline Cloud perturbed_box(real d0, real h) {
  const Vec3 hi = kBoxHi;
  const int n[3] = {static_cast<int>(std::lround(hi.x / d0)), static_cast<int>(std::lround(hi.y / d0)),
                    static_cast<int>(std::lround(hi.z / d0))};
  std::mt19937 rng(7);
  std::uniform_real_distribution<real> jitter(-0.2 * d0, 0.2 * d0);
  Cloud c;
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) {
        const Vec3 p{(i + 0.5) * d0 + jitter(rng), (j + 0.5) * d0 + jitter(rng),
                     (k + 0.5) * d0 + jitter(rng)};
        const real to_wall = std::fmin(std::fmin(std::fmin(p.x, hi.x - p.x), std::fmin(p.y, hi.y - p.y)),
                                       std::fmin(p.z, hi.z - p.z));
        c.x.push_back(p);
        c.w.push_back(d0 * d0 * d0);
        c.where.push_back(to_wall > h ? Where::Interior : Where::NearWall);
        c.normal.push_back({});
      }
  // the six faces: axis a fixed at 0 or hi, the other two on the cell centres
  for (int a = 0; a < 3; ++a)
    for (const bool far : {false, true}) {
      const int b = (a + 1) % 3, e = (a + 2) % 3;
      for (int j = 0; j < n[b]; ++j)
        for (int k = 0; k < n[e]; ++k) {
          real p[3];
          p[a] = far ? (a == 0 ? hi.x : a == 1 ? hi.y : hi.z) : 0;
          p[b] = (j + 0.5) * d0;
          p[e] = (k + 0.5) * d0;
          c.x.push_back({p[0], p[1], p[2]});
          c.w.push_back(0.5 * d0 * d0 * d0);
          c.where.push_back(Where::Wall);
          real n[3] = {0, 0, 0};
          n[a] = far ? -1 : 1;
          c.normal.push_back({n[0], n[1], n[2]});
        }
    }
  // the twelve edges (two axes at 0 or hi, the third on the cell centres) and the eight corners
  const real top[3] = {hi.x, hi.y, hi.z};
  for (int a = 0; a < 3; ++a)
    for (int corner = 0; corner < 4; ++corner)
      for (int j = 0; j < n[a]; ++j) {
        real p[3];
        p[a] = (j + 0.5) * d0;
        p[(a + 1) % 3] = corner & 1 ? top[(a + 1) % 3] : 0;
        p[(a + 2) % 3] = corner & 2 ? top[(a + 2) % 3] : 0;
        c.x.push_back({p[0], p[1], p[2]});
        c.w.push_back(0.25 * d0 * d0 * d0);
        c.where.push_back(Where::Wall);
        real n[3] = {0, 0, 0};
        n[(a + 1) % 3] = corner & 1 ? -1 : 1;
        n[(a + 2) % 3] = corner & 2 ? -1 : 1;
        c.normal.push_back(Vec3{n[0], n[1], n[2]} / std::sqrt(2.0));
      }
  for (int corner = 0; corner < 8; ++corner) {
    c.x.push_back({corner & 1 ? hi.x : 0, corner & 2 ? hi.y : 0, corner & 4 ? hi.z : 0});
    c.w.push_back(0.125 * d0 * d0 * d0);
    c.where.push_back(Where::Wall);
    c.normal.push_back(Vec3{corner & 1 ? -1.0 : 1.0, corner & 2 ? -1.0 : 1.0, corner & 4 ? -1.0 : 1.0} /
                       std::sqrt(3.0));
  }
  return c;
}

/// Particle i's neighbours within h (j != i), by brute force.
inline std::vector<std::size_t> neighbours(const Cloud& c, std::size_t i, real h) {
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < c.x.size(); ++j)
    if (j != i && norm(c.x[i] - c.x[j]) < h) out.push_back(j);
  return out;
}

}  // namespace box3
