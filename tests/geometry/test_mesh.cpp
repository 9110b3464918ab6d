// Closed triangle meshes and STL files (geometry/mesh.hpp): binary and ASCII files read to the
// same solid, and every kind of mesh that is not a solid refused with the file and the defect named.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "particula/geometry/mesh.hpp"
#include "scratch_dir.hpp"

using namespace particula;
namespace fs = std::filesystem;

namespace {

using Triangles = std::vector<TriangleMesh::Triangle>;

/// A tetrahedron and a unit cube, counter-clockwise seen from outside.
Triangles tetrahedron() {
  const Vec3 o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  return {{o, y, x}, {o, x, z}, {o, z, y}, {x, y, z}};
}
Triangles cube() {
  const auto v = [](int i) { return Vec3{real(i & 1), real((i >> 1) & 1), real((i >> 2) & 1)}; };
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  Triangles t;
  for (const auto& q : quads) {
    t.push_back({v(q[0]), v(q[1]), v(q[2])});
    t.push_back({v(q[0]), v(q[2]), v(q[3])});
  }
  return t;
}

void write_binary(const fs::path& p, const Triangles& t) {
  std::ofstream f(p, std::ios::binary);
  const std::string header(80, ' ');
  f.write(header.data(), 80);
  const std::uint32_t n = static_cast<std::uint32_t>(t.size());
  f.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& tri : t) {
    float v[12] = {0, 0, 0};
    for (int c = 0; c < 3; ++c) {
      v[3 + 3 * c] = static_cast<float>(tri[c].x);
      v[4 + 3 * c] = static_cast<float>(tri[c].y);
      v[5 + 3 * c] = static_cast<float>(tri[c].z);
    }
    f.write(reinterpret_cast<const char*>(v), sizeof v);
    const std::uint16_t attr = 0;
    f.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

void write_ascii(const fs::path& p, const Triangles& t) {
  std::ofstream f(p);
  f << "solid test\n";
  for (const auto& tri : t) {
    f << "  facet normal 0 0 0\n    outer loop\n";
    for (const Vec3& v : tri) f << "      vertex " << v.x << " " << v.y << " " << v.z << "\n";
    f << "    endloop\n  endfacet\n";
  }
  f << "endsolid test\n";
}

/// The message of the MeshError that reading `p` throws ("" if none).
std::string refusal(const fs::path& p) {
  try {
    read_stl(p);
  } catch (const MeshError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Mesh, BinaryAndAsciiFilesReadToTheSameSolid) {
  const fs::path dir = test_scratch::scratch_dir("mesh_read");
  write_binary(dir / "cube.stl", cube());
  write_ascii(dir / "cube_ascii.stl", cube());
  const TriangleMesh b = read_stl(dir / "cube.stl"), a = read_stl(dir / "cube_ascii.stl");
  for (const TriangleMesh* m : {&b, &a}) {
    EXPECT_EQ(m->vertices().size(), 8U);  // welded
    EXPECT_EQ(m->faces().size(), 12U);
    EXPECT_NEAR(m->volume(), 1, 1e-15);
    EXPECT_NEAR(norm(m->centroid() - Vec3{0.5, 0.5, 0.5}), 0, 1e-15);
    EXPECT_NEAR(m->surface_area(), 6, 1e-15);
    EXPECT_FALSE(m->was_inverted());
  }
  // the tetrahedron's second moment about its right-angle corner: int x^2 dV = 1/60, int xy dV = 1/120
  const TriangleMesh t = TriangleMesh::from_triangles(tetrahedron(), "tet");
  EXPECT_NEAR(t.volume(), 1.0 / 6, 1e-16);
  EXPECT_NEAR(t.second_moment().xx, 1.0 / 60, 1e-16);
  EXPECT_NEAR(t.second_moment().xy, 1.0 / 120, 1e-16);
  // a mesh consistently oriented inwards is turned outwards
  Triangles inward = cube();
  for (auto& f : inward) std::swap(f[1], f[2]);
  const TriangleMesh turned = TriangleMesh::from_triangles(inward, "inward");
  EXPECT_TRUE(turned.was_inverted());
  EXPECT_NEAR(turned.volume(), 1, 1e-15);
}

TEST(Mesh, MeshesThatAreNotSolidsAreRefused) {
  const fs::path dir = test_scratch::scratch_dir("mesh_refused");
  Triangles open = cube();
  open.pop_back();
  write_binary(dir / "open.stl", open);
  EXPECT_NE(refusal(dir / "open.stl").find("open.stl: the edge from"), std::string::npos)
      << refusal(dir / "open.stl");
  EXPECT_NE(refusal(dir / "open.stl").find("not closed"), std::string::npos);
  Triangles flipped = cube();
  std::swap(flipped[3][1], flipped[3][2]);
  write_ascii(dir / "flipped.stl", flipped);
  EXPECT_NE(refusal(dir / "flipped.stl").find("not consistently oriented"), std::string::npos)
      << refusal(dir / "flipped.stl");
  Triangles degenerate = cube();
  degenerate.push_back({Vec3{0, 0, 0}, Vec3{0.5, 0, 0}, Vec3{1, 0, 0}});
  write_binary(dir / "degenerate.stl", degenerate);
  EXPECT_NE(refusal(dir / "degenerate.stl").find("triangle 13"), std::string::npos)
      << refusal(dir / "degenerate.stl");
  // two cubes sharing an edge: four triangles along it
  Triangles two = cube();
  for (auto f : cube()) {
    for (Vec3& v : f) v += Vec3{1, 1, 0};
    two.push_back(f);
  }
  EXPECT_THROW(TriangleMesh::from_triangles(two, "two"), MeshError);
  // not an STL file, a bad ASCII vertex (with its line), a missing file
  {
    std::ofstream(dir / "text.stl") << "hello\n";
    std::ofstream f(dir / "bad.stl");
    f << "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n";
  }
  EXPECT_NE(refusal(dir / "text.stl").find("not an STL file"), std::string::npos);
  EXPECT_NE(refusal(dir / "bad.stl").find("bad.stl:5: a vertex needs three numbers"), std::string::npos)
      << refusal(dir / "bad.stl");
  EXPECT_NE(refusal(dir / "missing.stl").find("cannot open"), std::string::npos);
}
