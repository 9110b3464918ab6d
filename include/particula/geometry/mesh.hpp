// A closed triangle mesh bounding a 3D solid, as read from an STL file (binary or ASCII): the
// vertices welded where their coordinates agree exactly, and checked at construction, so that a
// mesh that exists is a solid: every edge shared by exactly two triangles that run along it in
// opposite directions (closed and consistently oriented), no degenerate triangle, a volume above
// zero (a mesh consistently oriented inwards is turned outwards). Its volume, centroid and second
// moments come from the divergence theorem over the signed tetrahedra of the faces.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "particula/core/types3.hpp"

namespace particula {

/// A mesh that is not a solid, or a file that is not an STL file: what() names the source (the
/// file) and the defect.
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class TriangleMesh {
 public:
  using Triangle = std::array<Vec3, 3>;

  /// The mesh of `triangles` (corners counter-clockwise seen from outside, or all the other way);
  /// `source` names them in errors (a file name). Throws MeshError when they do not bound a solid.
  static TriangleMesh from_triangles(const std::vector<Triangle>& triangles, const std::string& source);

  const std::vector<Vec3>& vertices() const { return vertices_; }
  const std::vector<std::array<std::uint32_t, 3>>& faces() const { return faces_; }
  Triangle triangle(std::size_t f) const {
    return {vertices_[faces_[f][0]], vertices_[faces_[f][1]], vertices_[faces_[f][2]]};
  }
  /// Whether the triangles as given ran inwards (the mesh turned them round).
  bool was_inverted() const { return inverted_; }

  /// Volume, volume centroid, and the second moment about the origin C = int r r^T dV.
  real volume() const;
  Vec3 centroid() const;
  Mat3 second_moment() const;
  real surface_area() const;

  /// The mesh moved by `offset`.
  TriangleMesh translated(Vec3 offset) const;

  /// The closest surface point to p and the outward unit normal there (the face normal when p
  /// is on the face's plane, else the direction from the surface to p, or from p to it inside),
  /// and the signed distance (negative inside, by the winding number).
  void distance_and_gradient(Vec3 p, real& d, Vec3& n) const;

 private:
  std::vector<Vec3> vertices_;
  std::vector<std::array<std::uint32_t, 3>> faces_;
  bool inverted_ = false;
};

/// Reads an STL file, binary or ASCII (binary when its size is 84 + 50 n bytes for the n
/// triangles its header announces). Throws MeshError naming the file (and for ASCII the line)
/// when it cannot be read or does not bound a solid.
TriangleMesh read_stl(const std::filesystem::path& path);

}  // namespace particula
