// The 3D value types: Vec<3>, Mat<3> (the specializations of core/types.hpp's Vec<D>, Mat<D>)
// and the unit quaternion that holds a body's orientation in 3D. Plain structs with PARTICULA_HD
// operations, like the 2D ones, so that the same physics compiles for the CPU and CUDA.
#pragma once

#include <cmath>

#include "particula/core/types.hpp"

namespace particula {

template <>
struct Vec<3> {
  real x = 0, y = 0, z = 0;
};
using Vec3 = Vec<3>;

PARTICULA_HD Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
PARTICULA_HD Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
PARTICULA_HD Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
PARTICULA_HD Vec3 operator*(real s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
PARTICULA_HD Vec3 operator*(Vec3 a, real s) { return {s * a.x, s * a.y, s * a.z}; }
PARTICULA_HD Vec3 operator/(Vec3 a, real s) { return {a.x / s, a.y / s, a.z / s}; }
PARTICULA_HD Vec3& operator+=(Vec3& a, Vec3 b) {
  a.x += b.x;
  a.y += b.y;
  a.z += b.z;
  return a;
}
PARTICULA_HD Vec3& operator-=(Vec3& a, Vec3 b) {
  a.x -= b.x;
  a.y -= b.y;
  a.z -= b.z;
  return a;
}
PARTICULA_HD Vec3& operator*=(Vec3& a, real s) {
  a.x *= s;
  a.y *= s;
  a.z *= s;
  return a;
}
PARTICULA_HD real dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
/// The cross product a x b (in 2D its z-component is the scalar cross(Vec2, Vec2)).
PARTICULA_HD Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
PARTICULA_HD real norm2(Vec3 a) { return dot(a, a); }
PARTICULA_HD real norm(Vec3 a) { return std::sqrt(dot(a, a)); }
/// A unit vector perpendicular to the unit vector n (crossed with the axis least aligned with it).
PARTICULA_HD Vec3 any_perpendicular(Vec3 n) {
  const real ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  const Vec3 e = ax <= ay && ax <= az ? Vec3{1, 0, 0} : (ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
  const Vec3 t = cross(n, e);
  return t / norm(t);
}
PARTICULA_HD bool all_finite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

/// General 3x3 matrix, row-major: xx xy xz / yx yy yz / zx zy zz.
template <>
struct Mat<3> {
  real xx = 0, xy = 0, xz = 0, yx = 0, yy = 0, yz = 0, zx = 0, zy = 0, zz = 0;
};
using Mat3 = Mat<3>;

PARTICULA_HD Mat3 operator+(const Mat3& a, const Mat3& b) {
  return {a.xx + b.xx, a.xy + b.xy, a.xz + b.xz, a.yx + b.yx, a.yy + b.yy,
          a.yz + b.yz, a.zx + b.zx, a.zy + b.zy, a.zz + b.zz};
}
PARTICULA_HD Mat3 operator-(const Mat3& a, const Mat3& b) {
  return {a.xx - b.xx, a.xy - b.xy, a.xz - b.xz, a.yx - b.yx, a.yy - b.yy,
          a.yz - b.yz, a.zx - b.zx, a.zy - b.zy, a.zz - b.zz};
}
PARTICULA_HD Mat3 operator*(real s, const Mat3& a) {
  return {s * a.xx, s * a.xy, s * a.xz, s * a.yx, s * a.yy, s * a.yz, s * a.zx, s * a.zy, s * a.zz};
}
PARTICULA_HD Mat3& operator+=(Mat3& a, const Mat3& b) {
  a = a + b;
  return a;
}
PARTICULA_HD Mat3 identity3() { return {1, 0, 0, 0, 1, 0, 0, 0, 1}; }
PARTICULA_HD Mat3 diagonal(Vec3 d) { return {d.x, 0, 0, 0, d.y, 0, 0, 0, d.z}; }
PARTICULA_HD Mat3 transpose(const Mat3& a) { return {a.xx, a.yx, a.zx, a.xy, a.yy, a.zy, a.xz, a.yz, a.zz}; }
PARTICULA_HD real trace(const Mat3& a) { return a.xx + a.yy + a.zz; }
PARTICULA_HD real det(const Mat3& a) {
  return a.xx * (a.yy * a.zz - a.yz * a.zy) - a.xy * (a.yx * a.zz - a.yz * a.zx) +
         a.xz * (a.yx * a.zy - a.yy * a.zx);
}
/// a (x) b: (a b^T)_{kl} = a_k b_l.
PARTICULA_HD Mat3 outer(Vec3 a, Vec3 b) {
  return {a.x * b.x, a.x * b.y, a.x * b.z, a.y * b.x, a.y * b.y, a.y * b.z, a.z * b.x, a.z * b.y, a.z * b.z};
}
/// M . v (matrix times column vector).
PARTICULA_HD Vec3 operator*(const Mat3& m, Vec3 v) {
  return {m.xx * v.x + m.xy * v.y + m.xz * v.z, m.yx * v.x + m.yy * v.y + m.yz * v.z,
          m.zx * v.x + m.zy * v.y + m.zz * v.z};
}
/// v . M (row vector times matrix): (v.M)_l = sum_k v_k M_kl.
PARTICULA_HD Vec3 operator*(Vec3 v, const Mat3& m) { return transpose(m) * v; }
PARTICULA_HD Mat3 operator*(const Mat3& a, const Mat3& b) {
  const Vec3 c0 = a * Vec3{b.xx, b.yx, b.zx}, c1 = a * Vec3{b.xy, b.yy, b.zy},
             c2 = a * Vec3{b.xz, b.yz, b.zz};
  return {c0.x, c1.x, c2.x, c0.y, c1.y, c2.y, c0.z, c1.z, c2.z};
}
/// Double contraction A : B = sum_kl A_kl B_kl.
PARTICULA_HD real ddot(const Mat3& a, const Mat3& b) {
  return a.xx * b.xx + a.xy * b.xy + a.xz * b.xz + a.yx * b.yx + a.yy * b.yy + a.yz * b.yz + a.zx * b.zx +
         a.zy * b.zy + a.zz * b.zz;
}
/// Symmetric part (A + A^T)/2.
PARTICULA_HD Mat3 sym(const Mat3& a) { return 0.5 * (a + transpose(a)); }
/// The largest magnitude of an entry, max_kl |A_kl|.
PARTICULA_HD real max_abs_entry(const Mat3& a) {
  const real e[9] = {a.xx, a.xy, a.xz, a.yx, a.yy, a.yz, a.zx, a.zy, a.zz};
  real m = 0;
  for (const real x : e) m = std::fmax(m, std::fabs(x));
  return m;
}
/// The inverse by cofactors; false (m_inv untouched) when |det| is not above rel_tol times the
/// cube of the largest entry.
PARTICULA_HD bool inverse(const Mat3& a, Mat3& a_inv, real rel_tol = 1e-14) {
  const Mat3 cof = {a.yy * a.zz - a.yz * a.zy, a.yz * a.zx - a.yx * a.zz, a.yx * a.zy - a.yy * a.zx,
                    a.xz * a.zy - a.xy * a.zz, a.xx * a.zz - a.xz * a.zx, a.xy * a.zx - a.xx * a.zy,
                    a.xy * a.yz - a.xz * a.yy, a.xz * a.yx - a.xx * a.yz, a.xx * a.yy - a.xy * a.yx};
  const real d = a.xx * cof.xx + a.xy * cof.xy + a.xz * cof.xz;
  const real s = max_abs_entry(a);
  if (!(std::fabs(d) > rel_tol * s * s * s)) return false;
  a_inv = (1 / d) * transpose(cof);
  return true;
}

/// The identity matrix of dimension D.
template <int D>
PARTICULA_HD Mat<D> unit_matrix();
template <>
PARTICULA_HD Mat2 unit_matrix<2>() {
  return identity2();
}
template <>
PARTICULA_HD Mat3 unit_matrix<3>() {
  return identity3();
}

/// A unit quaternion q = (w; x, y, z) = (cos(theta/2); sin(theta/2) axis): the rotation by theta
/// about `axis` that takes a body-frame vector to the world frame, v_world = q v q*.
struct Quat {
  real w = 1, x = 0, y = 0, z = 0;
};

/// The Hamilton product a b: the rotation b, then a.
PARTICULA_HD Quat operator*(const Quat& a, const Quat& b) {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}
PARTICULA_HD Quat conjugate(const Quat& q) { return {q.w, -q.x, -q.y, -q.z}; }
/// q / |q|: keeps a quaternion advanced by many products a rotation to round-off.
PARTICULA_HD Quat normalized(const Quat& q) {
  const real s = 1 / std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return {s * q.w, s * q.x, s * q.y, s * q.z};
}
/// The rotation by `angle` (radians, right-handed) about the unit vector `axis`.
PARTICULA_HD Quat axis_angle(Vec3 axis, real angle) {
  const real s = std::sin(0.5 * angle);
  return {std::cos(0.5 * angle), s * axis.x, s * axis.y, s * axis.z};
}
/// The rotation matrix R of q (v_world = R v_body).
PARTICULA_HD Mat3 rotation_matrix(const Quat& q) {
  const real xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
  const real xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z, wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
  return {1 - 2 * (yy + zz), 2 * (xy - wz), 2 * (xz + wy), 2 * (xy + wz),    1 - 2 * (xx + zz),
          2 * (yz - wx),     2 * (xz - wy), 2 * (yz + wx), 1 - 2 * (xx + yy)};
}
/// q v q*: a body-frame vector in the world frame.
PARTICULA_HD Vec3 rotate(const Quat& q, Vec3 v) { return rotation_matrix(q) * v; }
/// q* v q: a world-frame vector in the body frame.
PARTICULA_HD Vec3 rotate_back(const Quat& q, Vec3 v) { return transpose(rotation_matrix(q)) * v; }

/// The Cayley rotation of the vector phi: the rotation about phi by 2 atan(|phi| / 2), whose
/// matrix is (I - phi^/2)^-1 (I + phi^/2) (phi^ v = phi x v): the quaternion (1; phi/2) made
/// unit. It agrees with the exponential exp(phi^) to second order in |phi|, and it is the exact
/// rotation of the implicit midpoint rule (bodies/rigid_rotation.hpp).
PARTICULA_HD Quat cayley_rotation(Vec3 phi) {
  return normalized(Quat{1, 0.5 * phi.x, 0.5 * phi.y, 0.5 * phi.z});
}

}  // namespace particula
