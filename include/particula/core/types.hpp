// Basic value types shared by every module and by host and device code.
//
// Physics on particles and pairs is written as small inline functions on these plain
// structs, marked PARTICULA_HD so that the same source compiles for the CPU (OpenMP) and
// for CUDA kernels. No formula is written twice.
#pragma once

#include <cmath>

#if defined(__CUDACC__)
#define PARTICULA_HD __host__ __device__ inline
#else
#define PARTICULA_HD inline
#endif

namespace particula {

/// The scalar type of all physics. Keep it one alias so a float build stays possible.
using real = double;

/// A vector and a general square matrix of dimension D (2 or 3). The dimension is a parameter
/// of the types: a formula that differs between 2D and 3D differs through the overloads below
/// (the cross product, the inverse), never through a test of the dimension. The 3D
/// specializations and the quaternion are in core/types3.hpp. The 2D operations
/// are written out component by component, so that their round-off is that of plain code.
template <int D>
struct Vec;
template <int D>
struct Mat;

template <>
struct Vec<2> {
  real x = 0, y = 0;
};
using Vec2 = Vec<2>;

PARTICULA_HD Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
PARTICULA_HD Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
PARTICULA_HD Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
PARTICULA_HD Vec2 operator*(real s, Vec2 a) { return {s * a.x, s * a.y}; }
PARTICULA_HD Vec2 operator*(Vec2 a, real s) { return {s * a.x, s * a.y}; }
PARTICULA_HD Vec2 operator/(Vec2 a, real s) { return {a.x / s, a.y / s}; }
PARTICULA_HD Vec2& operator+=(Vec2& a, Vec2 b) { a.x += b.x; a.y += b.y; return a; }
PARTICULA_HD Vec2& operator-=(Vec2& a, Vec2 b) { a.x -= b.x; a.y -= b.y; return a; }
PARTICULA_HD Vec2& operator*=(Vec2& a, real s) { a.x *= s; a.y *= s; return a; }
PARTICULA_HD real dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
/// z-component of the 2D cross product a x b.
PARTICULA_HD real cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
/// Omega (along z) x r.
PARTICULA_HD Vec2 cross(real omega, Vec2 r) { return {-omega * r.y, omega * r.x}; }
PARTICULA_HD real norm2(Vec2 a) { return dot(a, a); }
PARTICULA_HD real norm(Vec2 a) { return std::sqrt(dot(a, a)); }
PARTICULA_HD bool all_finite(Vec2 a) { return std::isfinite(a.x) && std::isfinite(a.y); }
/// Rotate a by angle (radians), counter-clockwise.
PARTICULA_HD Vec2 rotate(Vec2 a, real c, real s) { return {c * a.x - s * a.y, s * a.x + c * a.y}; }

/// General 2x2 matrix, row-major: m[a][b] = xx, xy / yx, yy.
template <>
struct Mat<2> {
  real xx = 0, xy = 0, yx = 0, yy = 0;
};
using Mat2 = Mat<2>;

PARTICULA_HD Mat2 operator+(const Mat2& a, const Mat2& b) {
  return {a.xx + b.xx, a.xy + b.xy, a.yx + b.yx, a.yy + b.yy};
}
PARTICULA_HD Mat2 operator-(const Mat2& a, const Mat2& b) {
  return {a.xx - b.xx, a.xy - b.xy, a.yx - b.yx, a.yy - b.yy};
}
PARTICULA_HD Mat2 operator*(real s, const Mat2& a) { return {s * a.xx, s * a.xy, s * a.yx, s * a.yy}; }
PARTICULA_HD Mat2& operator+=(Mat2& a, const Mat2& b) {
  a.xx += b.xx; a.xy += b.xy; a.yx += b.yx; a.yy += b.yy;
  return a;
}
PARTICULA_HD Mat2 identity2() { return {1, 0, 0, 1}; }
PARTICULA_HD Mat2 transpose(const Mat2& a) { return {a.xx, a.yx, a.xy, a.yy}; }
PARTICULA_HD real trace(const Mat2& a) { return a.xx + a.yy; }
PARTICULA_HD real det(const Mat2& a) { return a.xx * a.yy - a.xy * a.yx; }
/// a (x) b: (a b^T)_{kl} = a_k b_l.
PARTICULA_HD Mat2 outer(Vec2 a, Vec2 b) { return {a.x * b.x, a.x * b.y, a.y * b.x, a.y * b.y}; }
/// M . v (matrix times column vector).
PARTICULA_HD Vec2 operator*(const Mat2& m, Vec2 v) { return {m.xx * v.x + m.xy * v.y, m.yx * v.x + m.yy * v.y}; }
/// v . M (row vector times matrix): (v.M)_l = sum_k v_k M_kl.
PARTICULA_HD Vec2 operator*(Vec2 v, const Mat2& m) { return {v.x * m.xx + v.y * m.yx, v.x * m.xy + v.y * m.yy}; }
PARTICULA_HD Mat2 operator*(const Mat2& a, const Mat2& b) {
  return {a.xx * b.xx + a.xy * b.yx, a.xx * b.xy + a.xy * b.yy, a.yx * b.xx + a.yy * b.yx,
          a.yx * b.xy + a.yy * b.yy};
}
/// Double contraction A : B = sum_kl A_kl B_kl.
PARTICULA_HD real ddot(const Mat2& a, const Mat2& b) {
  return a.xx * b.xx + a.xy * b.xy + a.yx * b.yx + a.yy * b.yy;
}
/// Symmetric part (A + A^T)/2.
PARTICULA_HD Mat2 sym(const Mat2& a) {
  const real o = 0.5 * (a.xy + a.yx);
  return {a.xx, o, o, a.yy};
}

}  // namespace particula
