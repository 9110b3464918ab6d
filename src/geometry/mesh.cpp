// A closed triangle mesh and the STL reader (geometry/mesh.hpp).
#include "particula/geometry/mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <utility>

namespace particula {

namespace {

std::string at(Vec3 v) { return fmt::format("({:.6g}, {:.6g}, {:.6g})", v.x, v.y, v.z); }

/// The closest point to p on the triangle (a, b, c) (Ericson, Real-Time Collision Detection 5.1.5).
Vec3 closest_on_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const real d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const real d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const real vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const real d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const real vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const real va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const real denom = 1 / (va + vb + vc);
  return a + (vb * denom) * ab + (vc * denom) * ac;
}

/// The solid angle the triangle (a, b, c) subtends at the origin, signed by its orientation
/// (Van Oosterom and Strackee 1983).
real solid_angle(Vec3 a, Vec3 b, Vec3 c) {
  const real la = norm(a), lb = norm(b), lc = norm(c);
  const real num = dot(a, cross(b, c));
  const real den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2 * std::atan2(num, den);
}

}  // namespace

TriangleMesh TriangleMesh::from_triangles(const std::vector<Triangle>& triangles, const std::string& source) {
  if (triangles.size() < 4)
    throw MeshError(fmt::format("{}: {} triangles cannot bound a solid", source, triangles.size()));
  TriangleMesh m;
  std::map<std::array<real, 3>, std::uint32_t> index;
  real extent = 0;
  for (const Triangle& t : triangles)
    for (const Vec3& v : t) extent = std::max({extent, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    std::array<std::uint32_t, 3> f{};
    for (int c = 0; c < 3; ++c) {
      const Vec3 v = triangles[k][c];
      if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)))
        throw MeshError(fmt::format("{}: triangle {} has a non-finite coordinate", source, k + 1));
      const auto [it, added] =
          index.try_emplace({v.x, v.y, v.z}, static_cast<std::uint32_t>(m.vertices_.size()));
      if (added) m.vertices_.push_back(v);
      f[c] = it->second;
    }
    const Triangle& t = triangles[k];
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2] ||
        !(norm(cross(t[1] - t[0], t[2] - t[0])) > 1e-24 * extent * extent))
      throw MeshError(fmt::format("{}: triangle {} (corners {}, {}, {}) is degenerate: it has no area",
                                  source, k + 1, at(t[0]), at(t[1]), at(t[2])));
    m.faces_.push_back(f);
  }
  // closed and consistently oriented: each directed edge once, and its reverse once
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> edges;
  for (std::size_t k = 0; k < m.faces_.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const std::pair<std::uint32_t, std::uint32_t> e{m.faces_[k][c], m.faces_[k][(c + 1) % 3]};
      const auto [it, added] = edges.try_emplace(e, k);
      if (!added)
        throw MeshError(fmt::format(
            "{}: triangles {} and {} run along the edge from {} to {} in the same direction: the mesh is not "
            "consistently oriented, or more than two triangles share that edge",
            source, it->second + 1, k + 1, at(m.vertices_[e.first]), at(m.vertices_[e.second])));
    }
  for (const auto& [e, k] : edges)
    if (!edges.count({e.second, e.first}))
      throw MeshError(
          fmt::format("{}: the edge from {} to {} belongs to triangle {} only: the mesh is not closed",
                      source, at(m.vertices_[e.first]), at(m.vertices_[e.second]), k + 1));
  const real V = m.volume();
  if (!(std::fabs(V) > 1e-12 * extent * extent * extent))
    throw MeshError(fmt::format("{}: the mesh encloses no volume", source));
  if (V < 0) {  // consistently oriented inwards: turn it outwards
    for (auto& f : m.faces_) std::swap(f[1], f[2]);
    m.inverted_ = true;
  }
  return m;
}

real TriangleMesh::volume() const {
  real six_v = 0;
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const Triangle t = triangle(f);
    six_v += dot(t[0], cross(t[1], t[2]));
  }
  return six_v / 6;
}

Vec3 TriangleMesh::centroid() const {
  // sum over the tetrahedra (0, a, b, c): volume det / 6 at centroid (a + b + c) / 4
  Vec3 m;
  real six_v = 0;
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const Triangle t = triangle(f);
    const real d = dot(t[0], cross(t[1], t[2]));
    six_v += d;
    m += (d / 4) * (t[0] + t[1] + t[2]);
  }
  return m / six_v;
}

Mat3 TriangleMesh::second_moment() const {
  // int r r^T dV over the tetrahedron (0, a, b, c) = det / 120 (a a^T + b b^T + c c^T + s s^T),
  // s = a + b + c
  Mat3 C;
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const Triangle t = triangle(f);
    const real d = dot(t[0], cross(t[1], t[2]));
    const Vec3 s = t[0] + t[1] + t[2];
    C += (d / 120) * (outer(t[0], t[0]) + outer(t[1], t[1]) + outer(t[2], t[2]) + outer(s, s));
  }
  return C;
}

real TriangleMesh::surface_area() const {
  real a = 0;
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const Triangle t = triangle(f);
    a += 0.5 * norm(cross(t[1] - t[0], t[2] - t[0]));
  }
  return a;
}

TriangleMesh TriangleMesh::translated(Vec3 offset) const {
  TriangleMesh m = *this;
  for (Vec3& v : m.vertices_) v += offset;
  return m;
}

void TriangleMesh::distance_and_gradient(Vec3 p, real& d, Vec3& n) const {
  real best = 1e300, winding = 0;
  Vec3 q;
  std::size_t face = 0;
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const Triangle t = triangle(f);
    const Vec3 c = closest_on_triangle(p, t[0], t[1], t[2]);
    const real d2 = norm2(p - c);
    if (d2 < best) {
      best = d2;
      q = c;
      face = f;
    }
    winding += solid_angle(t[0] - p, t[1] - p, t[2] - p);
  }
  const bool inside = winding > 2 * M_PI;  // winding number above 1/2
  const real dist = std::sqrt(best);
  d = inside ? -dist : dist;
  const Triangle t = triangle(face);
  const Vec3 face_n = cross(t[1] - t[0], t[2] - t[0]);
  const Vec3 away = p - q;
  // at the surface (within round-off of the face's size) or straight off the face: the face's
  // normal; else (off an edge or a corner) the direction between p and the surface
  const real on_surface = 1e-10 * std::sqrt(norm(face_n));
  n = !(dist > on_surface) || std::fabs(dot(away, face_n)) >= (1 - 1e-12) * norm(away) * norm(face_n)
          ? face_n / norm(face_n)
          : (inside ? -1.0 : 1.0) * away / dist;
}

namespace {

TriangleMesh read_binary_stl(const std::string& bytes, std::uint32_t n, const std::string& source) {
  std::vector<TriangleMesh::Triangle> tris(n);
  for (std::uint32_t k = 0; k < n; ++k) {
    float v[12];
    std::memcpy(v, bytes.data() + 84 + 50 * static_cast<std::size_t>(k), sizeof v);
    for (int c = 0; c < 3; ++c) tris[k][c] = {v[3 + 3 * c], v[4 + 3 * c], v[5 + 3 * c]};
  }
  return TriangleMesh::from_triangles(tris, source);
}

TriangleMesh read_ascii_stl(const std::string& bytes, const std::string& source) {
  std::istringstream in(bytes);
  std::string line;
  std::vector<TriangleMesh::Triangle> tris;
  TriangleMesh::Triangle t;
  int corners = 0, line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream words(line);
    std::string w;
    if (!(words >> w) || w != "vertex") continue;
    Vec3 v;
    if (!(words >> v.x >> v.y >> v.z))
      throw MeshError(fmt::format("{}:{}: a vertex needs three numbers: '{}'", source, line_no, line));
    t[corners++] = v;
    if (corners == 3) {
      tris.push_back(t);
      corners = 0;
    }
  }
  if (corners != 0)
    throw MeshError(fmt::format("{}:{}: the last facet has {} vertices, not 3", source, line_no, corners));
  return TriangleMesh::from_triangles(tris, source);
}

}  // namespace

TriangleMesh read_stl(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::ifstream f(path, std::ios::binary);
  if (!f) throw MeshError(fmt::format("{}: cannot open the file", source));
  const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (bytes.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data() + 80, sizeof n);
    if (bytes.size() == 84 + 50 * static_cast<std::size_t>(n)) return read_binary_stl(bytes, n, source);
  }
  const std::size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start != std::string::npos && bytes.compare(start, 5, "solid") == 0)
    return read_ascii_stl(bytes, source);
  throw MeshError(fmt::format(
      "{}: not an STL file: {} bytes, neither a binary STL (84 bytes and 50 per triangle) nor an ASCII one "
      "(starting with 'solid')",
      source, bytes.size()));
}

}  // namespace particula
