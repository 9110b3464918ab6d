#include "particula/solver/solver.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <numeric>

#include "particula/bodies/collision.hpp"
#include "particula/bodies/rigid_motion.hpp"
#include "particula/boundary/wall_pressure.hpp"
#include "particula/fluid/fluid.hpp"
#include "particula/sph/operators.hpp"

namespace particula {

Solver::Solver(PhysicsParams params, Domain domain, Particles particles, std::vector<RigidGroup> groups,
               SolverStart start, real t0, std::int64_t step0)
    : prm_(params), domain_(domain), P_(std::move(particles)), groups_(std::move(groups)), kernel_(params.h),
      t_(t0), steps_(step0) {
  grid_.setup(domain_, prm_.h);
  if (start == SolverStart::Restart) return;  // the checkpoint holds positions, pressures, everything
  place_boundary(t_);
  refresh_geometry();
  // Initial wall pressure consistent with the initial fluid state (P.20): iterate the Jacobi
  // sweeps to convergence once, since boundary particles start without a pressure.
  compute_velocity_derivatives(P_.v);
  const int sweeps = prm_.wall_pressure_sweeps;
  prm_.wall_pressure_sweeps = 50;
  boundary_pressure(P_.rho);
  prm_.wall_pressure_sweeps = sweeps;
}

// ---------------------------------------------------------------------------------------------
// Geometry: everything that depends on positions (and start-of-step volumes) only.

void Solver::update_volumes() {
  const std::size_t n = P_.size();
  vol_.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) vol_[i] = P_.m[i] / P_.rho[i];
}

void Solver::refresh_geometry() {
  build_neighbor_list(P_.x, domain_, kernel_, grid_, nl_);
  update_volumes();
  geometry_sweep();
}

void Solver::geometry_sweep() {
  const std::size_t n = P_.size();
  B_.resize(n);
  Bhat_.resize(n);
  rbar_.resize(n);
  nsum_.resize(P_.n_boundary);
  std::int64_t bad_B = 0, bad_Bhat = 0, bad_normal = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad_B, bad_Bhat, bad_normal)
  for (std::size_t i = 0; i < n; ++i) {
    if (P_.kind[i] == Kind::Dummy) {
      B_[i] = identity2();
      Bhat_[i] = identity2();
      continue;
    }
    Mat2 S;
    LaplacianMoments mom;
    Vec2 ns;
    real rsum = 0;
    const auto b = nl_.start[i], e = nl_.start[i + 1];
    for (auto k = b; k < e; ++k) {
      const real w = vol_[nl_.j[k]];
      const real r = nl_.r[k];
      S += renormalization_pair(w, nl_.F[k], nl_.rij[k]);
      laplacian_moments_pair(mom, w, r, nl_.F[k] * r, nl_.rij[k] / r);
      ns += (w * nl_.F[k]) * nl_.rij[k];
      rsum += r;
    }
    if (!renormalization_tensor(S, B_[i])) ++bad_B;
    if (!laplacian_correction_tensor(mom, B_[i], Bhat_[i], i < P_.n_boundary)) ++bad_Bhat;
    rbar_[i] = e > b ? rsum / static_cast<real>(e - b) : prm_.d0;
    // P.18 normal; on failure the analytic normal set by place_boundary stays.
    if (i < P_.n_boundary && prm_.kernel_normals && P_.kind[i] == Kind::Boundary) {
      if (!kernel_normal(ns, P_.normal[i])) ++bad_normal;
    }
  }
  counters_.singular_B += bad_B;
  counters_.singular_Bhat += bad_Bhat;
  counters_.normal_fallback += bad_normal;
}

// ---------------------------------------------------------------------------------------------
// Sweeps over the pair list. Every sum is a gather over i's own neighbours in list order, so
// the result does not depend on the number of threads.

void Solver::compute_velocity_derivatives(const std::vector<Vec2>& v) {
  const std::size_t n = P_.size();
  gradV_.resize(n);
  lapV_.resize(n);
  div_v_.resize(n);
  const bool fm = prm_.fatehi_manzari;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (P_.kind[i] == Kind::Dummy) {
      gradV_[i] = Mat2{};
      lapV_[i] = Vec2{};
      div_v_[i] = 0;
      continue;
    }
    const auto b = nl_.start[i], e = nl_.start[i + 1];
    const Mat2 Bi = B_[i];
    Mat2 L;
    for (auto k = b; k < e; ++k) {
      const auto j = nl_.j[k];
      L += vector_gradient_pair((vol_[j] * nl_.F[k]) * (Bi * nl_.rij[k]), v[j] - v[i]);
    }
    Vec2 lap;
    const Mat2 Bh = Bhat_[i];
    for (auto k = b; k < e; ++k) {
      const auto j = nl_.j[k];
      const real r = nl_.r[k];
      const Vec2 eij = nl_.rij[k] / r;
      const real dW = nl_.F[k] * r;
      if (fm) {
        lap += fm_laplacian_pair(fm_pair_weight(Bh, vol_[j], dW, eij), v[i] - v[j], r, eij, L);
      } else {
        lap += (morris_pair_weight(vol_[j], dW) / r) * (v[i] - v[j]);
      }
    }
    gradV_[i] = L;
    lapV_[i] = lap;
    div_v_[i] = trace(L);
  }
}

void Solver::compute_pressure_gradient(const std::vector<real>& p, const std::vector<real>& rho) {
  const std::size_t n = P_.size();
  G_.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    Vec2 g;
    const Mat2 Bi = B_[i];
    for (auto k = nl_.start[i]; k < nl_.start[i + 1]; ++k) {
      const auto j = nl_.j[k];
      g += gradient_pair((vol_[j] * nl_.F[k]) * (Bi * nl_.rij[k]), p[j] - p[i]);
    }
    G_[i] = g / rho[i];
  }
}

void Solver::rhie_chow_sweep(const std::vector<real>& p, const std::vector<real>& rho) {
  const std::size_t n = P_.size();
  rc_.assign(n, 0);
  const bool fm = prm_.fatehi_manzari;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (P_.kind[i] == Kind::Dummy) continue;
    const Mat2 Bi = B_[i], Bh = Bhat_[i];
    const Vec2 Gi = G_[i];
    real div_g = 0, lap_p = 0;
    for (auto k = nl_.start[i]; k < nl_.start[i + 1]; ++k) {
      const auto j = nl_.j[k];
      const real r = nl_.r[k];
      const Vec2 eij = nl_.rij[k] / r;
      const real dW = nl_.F[k] * r;
      // <div <grad P/rho>>: the first-derivative scheme applied twice.
      div_g += dot((vol_[j] * nl_.F[k]) * (Bi * nl_.rij[k]), G_[j] - Gi);
      // <div (grad P/rho)>: the second-derivative scheme applied once.
      const real dp = (p[i] - p[j]) / (0.5 * (rho[i] + rho[j]));
      if (fm) {
        lap_p += fm_laplacian_pair(fm_pair_weight(Bh, vol_[j], dW, eij), dp, r, eij, Gi);
      } else {
        lap_p += morris_pair_weight(vol_[j], dW) * dp / r;
      }
    }
    rc_[i] = div_g - lap_p;
  }
}

// ---------------------------------------------------------------------------------------------
// Boundary

void Solver::place_boundary(real t) {
  (void)t;  // group poses are advanced by body_update
  for (auto& g : groups_) {
    const real c = std::cos(g.angle), s = std::sin(g.angle);
    for (std::size_t i = g.first; i < g.first + g.count; ++i) {
      P_.x[i] = domain_.wrap(g.pos + rotate(P_.local[i], c, s));
      // Analytic normal; replaced by P.18 in the geometry sweep when kernel normals are used.
      P_.normal[i] = rotate(P_.normal_local[i], c, s);
    }
  }
  set_boundary_kinematics();
}

void Solver::set_boundary_kinematics() {
  for (const auto& g : groups_) {
    const real c = std::cos(g.angle), s = std::sin(g.angle);
    for (std::size_t i = g.first; i < g.first + g.count; ++i) {
      const Vec2 R = rotate(P_.local[i], c, s);
      P_.v[i] = g.vel + cross(g.omega, R);
      P_.acc[i] = g.acc + cross(g.alpha, R) - (g.omega * g.omega) * R;  // a + alpha x R - |Omega|^2 R
    }
  }
}

void Solver::boundary_pressure(const std::vector<real>& rho_ref) {
  (void)rho_ref;
  const std::size_t nb = P_.n_boundary;
  if (nb == 0) return;
  if (!prm_.single_layer) {
    // Dummy-particle baseline: surface particles evolve rho by continuity (done by the
    // stages); dummies copy P and rho of their nearest surface particle.
    for (std::size_t i = 0; i < nb; ++i)
      if (P_.kind[i] == Kind::Dummy) {
        P_.p[i] = P_.p[P_.source[i]];
        P_.rho[i] = P_.rho[P_.source[i]];
      }
    return;
  }
  const Vec2 f = prm_.body_force + (prm_.gravity_in_fluid ? prm_.gravity : Vec2{});
  std::vector<real> p_new(nb);
  std::int64_t kept = 0;
  for (int sweep = 0; sweep < prm_.wall_pressure_sweeps; ++sweep) {
#pragma omp parallel for schedule(static) reduction(+ : kept)
    for (std::size_t i = 0; i < nb; ++i) {
      p_new[i] = P_.p[i];
      if (P_.kind[i] != Kind::Boundary) continue;
      WallPressureSums s;
      const Vec2 n = P_.normal[i];
      const Mat2 Bi = B_[i];
      for (auto k = nl_.start[i]; k < nl_.start[i + 1]; ++k) {
        const auto j = nl_.j[k];
        const Vec2 wBgW = (vol_[j] * nl_.F[k]) * (Bi * nl_.rij[k]);
        wall_pressure_pair(s, wBgW, n, P_.p[j], 0.5 * (P_.rho[i] + P_.rho[j]), j >= nb);
      }
      if (!wall_pressure(s, P_.acc[i], prm_.nu * lapV_[i], f, n, p_new[i])) ++kept;
    }
    for (std::size_t i = 0; i < nb; ++i) {
      if (P_.kind[i] != Kind::Boundary) continue;
      P_.p[i] = p_new[i];
      P_.rho[i] = density_from_pressure(p_new[i], prm_.rho0, prm_.c, prm_.p0);
    }
  }
  counters_.wall_pressure_kept += kept;
}

void Solver::group_loads() {
  const real mu = prm_.nu * prm_.rho0;
  for (auto& g : groups_) {
    Vec2 fp, fv;
    real torque = 0;
    for (std::size_t i = g.first; i < g.first + g.count; ++i) {
      if (P_.kind[i] != Kind::Boundary) continue;
      const Vec2 n = P_.normal[i];
      const Mat2 tau = mu * (gradV_[i] + transpose(gradV_[i]));
      const Vec2 tp = (-P_.p[i] * P_.ds[i]) * n;
      const Vec2 tv = P_.ds[i] * (n * tau);
      fp += tp;
      fv += tv;
      torque += cross(domain_.separation(P_.x[i], g.pos), tp + tv);
    }
    g.force_pressure = fp;
    g.force_viscous = fv;
    g.torque = torque;
  }
}

// ---------------------------------------------------------------------------------------------
// Time step

real Solver::max_speed() const {
  real vmax2 = 0;
  const std::size_t n = P_.size();
#pragma omp parallel for schedule(static) reduction(max : vmax2)
  for (std::size_t i = 0; i < n; ++i) vmax2 = std::max(vmax2, norm2(P_.v[i]));
  return std::sqrt(vmax2);
}

real Solver::stable_dt() const {
  const real dmin = nl_.min_distance > 0 && std::isfinite(nl_.min_distance) ? nl_.min_distance : prm_.d0;
  const real vmax = max_speed();
  real dt = prm_.cfl * dmin / (prm_.c + vmax);  // P.30: Courant condition
  if (prm_.nu > 0) dt = std::min(dt, prm_.cfl * dmin * dmin / prm_.nu);  // P.31: viscous diffusion
  if (prm_.dt_max > 0) dt = std::min(dt, prm_.dt_max);
  return dt;
}

std::optional<Failure> Solver::step(real dt_cap) {
  if (prm_.reorder_interval > 0 && steps_ % prm_.reorder_interval == 0) reorder_fluid();
  refresh_geometry();
  if (auto f = collisions()) return f;
  dt_ = stable_dt();
  if (dt_cap > 0) dt_ = std::min(dt_, dt_cap);
  const real dt = dt_;
  const real g_dt = prm_.rhie_chow_factor * dt;
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  const Vec2 f = prm_.body_force + (prm_.gravity_in_fluid ? prm_.gravity : Vec2{});
  const real nu = prm_.nu;
  // In the dummy baseline, surface particles evolve their density like fluid particles.
  const std::size_t first_evolved = prm_.single_layer ? nb : 0;
  // One explicit stage of the fluid momentum (V = V_start + dt A) and of the modified continuity
  // equation (rho = rho_start + dt D, with the velocity derivatives of the new V), then the EOS.
  auto momentum_stage = [&](const std::vector<Vec2>& v_start) {
#pragma omp parallel for schedule(static)
    for (std::size_t i = nb; i < n; ++i) P_.v[i] = v_start[i] + dt * momentum_rate(G_[i], lapV_[i], nu, f);
  };
  auto continuity_stage = [&](const std::vector<real>& rho_start) {
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      if (i >= first_evolved && P_.kind[i] != Kind::Dummy) {
        P_.rho[i] = rho_start[i] + dt * continuity_rate(rho_start[i], div_v_[i], g_dt, rc_[i]);
        P_.p[i] = equation_of_state(P_.rho[i], prm_.rho0, prm_.c, prm_.p0);
      }
  };

  v_n_ = P_.v;
  rho_n_ = P_.rho;
  p_n_ = P_.p;
  std::vector<Vec2>& gv0 = group_v0_;
  std::vector<real>& gw0 = group_w0_;
  gv0.resize(groups_.size());
  gw0.resize(groups_.size());
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    groups_[k].vel_n = gv0[k] = groups_[k].vel;
    groups_[k].omega_n = gw0[k] = groups_[k].omega;
  }

  // ---- predictor: V* = V^n + dt A(V^n, P^n); bodies from the loads of P^n, tau^n;
  //      rho* = rho^n + dt D(V*, P^n) (continuity uses the new velocity)
  compute_velocity_derivatives(P_.v);
  gradV_n_ = gradV_;
  compute_pressure_gradient(P_.p, P_.rho);
  rhie_chow_sweep(P_.p, P_.rho);
  group_loads();
  momentum_stage(v_n_);
  body_stage(dt, t_ + dt, gv0, gw0);
  set_boundary_kinematics();  // positions stay frozen during the stages
  compute_velocity_derivatives(P_.v);
  continuity_stage(rho_n_);
  boundary_pressure(P_.rho);

  // ---- corrector: V** = V* + dt A(V*, P*); bodies likewise; rho** = rho* + dt D(V**, P*)
  v_s_ = P_.v;
  rho_s_ = P_.rho;
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    gv0[k] = groups_[k].vel;
    gw0[k] = groups_[k].omega;
  }
  compute_pressure_gradient(P_.p, P_.rho);
  rhie_chow_sweep(P_.p, P_.rho);
  group_loads();
  momentum_stage(v_s_);
  body_stage(dt, t_ + dt, gv0, gw0);
  set_boundary_kinematics();
  compute_velocity_derivatives(P_.v);
  continuity_stage(rho_s_);
  boundary_pressure(P_.rho);

  // ---- update (P.28, P.32): averages of the stage-start and corrected values
  real vmax2 = 0;
#pragma omp parallel for schedule(static) reduction(max : vmax2)
  for (std::size_t i = 0; i < n; ++i) {
    if (i >= nb) {
      P_.v[i] = 0.5 * (P_.v[i] + v_n_[i]);
      P_.x[i] = domain_.wrap(P_.x[i] + dt * P_.v[i]);
    }
    if (i >= nb || prm_.single_layer || P_.kind[i] != Kind::Dummy) {
      P_.rho[i] = 0.5 * (P_.rho[i] + rho_n_[i]);
      P_.p[i] = 0.5 * (P_.p[i] + p_n_[i]);
    }
    vmax2 = std::max(vmax2, norm2(P_.v[i]));
  }
  if (!prm_.single_layer) boundary_pressure(P_.rho);  // dummies copy the averaged surface values
  t_ += dt;
  ++steps_;
  body_update(dt, t_);
  place_boundary(t_);

  // ---- particle shifting (P.33-P.36), with the step's geometry and the new fields
  if (prm_.shifting_beta > 0) {
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) gradV_[i] = 0.5 * (gradV_[i] + gradV_n_[i]);
    compute_pressure_gradient(P_.p, P_.rho);
    shift_particles(dt, std::sqrt(vmax2));
  }
  return check_health();
}

// ---------------------------------------------------------------------------------------------
// Rigid bodies

void Solver::body_stage(real dt, real t_stage_end, const std::vector<Vec2>& v0, const std::vector<real>& omega0) {
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    RigidGroup& g = groups_[k];
    if (g.motion == Motion::Free) {
      const Vec2 weight = body_weight(g.mass, g.area, prm_.rho0, prm_.gravity, prm_.gravity_in_fluid);
      const Vec2 force = g.force_pressure + g.force_viscous + g.force_collision + weight;
      free_body_stage(g, v0[k], omega0[k], force, g.torque, dt);
    } else if (g.motion == Motion::Prescribed && g.body >= 0) {
      const BodyParams& b = prm_.bodies[static_cast<std::size_t>(g.body)];
      const PrescribedState st = prescribed_state(b.schedule, b.velocity, b.omega, t_stage_end);
      g.vel = st.vel;
      g.omega = st.omega;
      g.acc = st.acc;
      g.alpha = st.alpha;
    }
  }
}

void Solver::body_update(real dt, real t_new) {
  for (auto& g : groups_) {
    if (g.motion == Motion::Free) {
      free_body_update(g, g.vel_n, g.omega_n, dt);
    } else if (g.motion == Motion::Prescribed) {
      Vec2 vel = g.vel;
      real omega = g.omega;
      const std::vector<MotionKnot>* knots = nullptr;
      if (g.body >= 0) {
        const BodyParams& b = prm_.bodies[static_cast<std::size_t>(g.body)];
        vel = b.velocity;
        omega = b.omega;
        knots = &b.schedule;
      }
      const PrescribedState st = prescribed_state(knots ? *knots : std::vector<MotionKnot>{}, vel, omega, t_new);
      g.pos = g.pos0 + st.displacement;
      g.angle = g.angle0 + st.rotation;
      g.vel = st.vel;
      g.omega = st.omega;
      g.acc = st.acc;
      g.alpha = st.alpha;
    }
  }
}

std::optional<Failure> Solver::collisions() {
  for (auto& g : groups_) g.force_collision = Vec2{};
  const real eps = prm_.collision_range > 0 ? prm_.collision_range : 3 * prm_.d0;
  const real k = prm_.collision_stiffness;
  const real overlap_limit = -0.25 * prm_.d0;  // interpenetration beyond sampling noise
  auto placed = [&](const RigidGroup& g) {
    const BodyParams& b = prm_.bodies[static_cast<std::size_t>(g.body)];
    return PlacedBody{&b.shape, &b.samples, g.pos, g.angle};
  };
  auto overlap = [&](const std::string& a, const std::string& b, real gap, Vec2 where) {
    Failure f;
    char buf[512];
    std::snprintf(buf, sizeof buf, "body '%s' overlaps %s by %.3g m (%.2f d0): the collision force did not keep them apart",
                  a.c_str(), b.c_str(), -gap, -gap / prm_.d0);
    f.what = buf;
    f.position = where;
    return f;
  };
  for (std::size_t a = 0; a < groups_.size(); ++a) {
    RigidGroup& ga = groups_[a];
    if (ga.is_wall) continue;
    const PlacedBody pa = placed(ga);
    const real Ra = prm_.bodies[static_cast<std::size_t>(ga.body)].shape.equivalent_radius();
    // bodies
    for (std::size_t b = a + 1; b < groups_.size(); ++b) {
      RigidGroup& gb = groups_[b];
      if (gb.is_wall) continue;
      const PlacedBody pb = placed(gb);
      if (norm(domain_.separation(ga.pos, gb.pos)) > pa.shape->bounding_radius() + pb.shape->bounding_radius() + eps)
        continue;
      const Contact c = body_contact(pa, pb, domain_);
      if (c.gap < overlap_limit) return overlap(prm_.bodies[ga.body].name, "body '" + prm_.bodies[gb.body].name + "'", c.gap, ga.pos);
      const real Rb = pb.shape->equivalent_radius();
      const Vec2 F = repulsive_force(c, Ra, Rb, k, eps);
      ga.force_collision += F;
      gb.force_collision -= F;
    }
    // walls, as the mirror image of the body (gap to the image = twice the gap to the wall)
    for (const auto& w : prm_.walls) {
      Contact c = wall_contact(pa, w.from, w.to, w.normal);
      if (c.gap > 1e299) continue;
      if (c.gap < overlap_limit && ga.motion == Motion::Free)
        return overlap(prm_.bodies[ga.body].name, "a wall", c.gap, ga.pos);
      c.gap *= 2;
      ga.force_collision += repulsive_force(c, Ra, Ra, k, eps);
    }
  }
  return std::nullopt;
}

void Solver::shift_particles(real dt, real vmax) {
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  const real scale = prm_.shifting_beta * vmax * dt;
  if (!(scale > 0)) return;
#pragma omp parallel for schedule(static)
  for (std::size_t i = nb; i < n; ++i) {
    const real rbar2 = rbar_[i] * rbar_[i];
    Vec2 sum;
    for (auto k = nl_.start[i]; k < nl_.start[i + 1]; ++k) sum += shifting_pair(rbar2, nl_.r[k], nl_.rij[k]);
    const Vec2 dr = scale * sum;
    P_.x[i] = domain_.wrap(P_.x[i] + dr);
    P_.v[i] += dr * gradV_[i];                 // P.34
    const real dp = P_.rho[i] * dot(dr, G_[i]);  // P.35: rho dr . <grad P / rho>
    P_.p[i] += dp;
    P_.rho[i] += dp / (prm_.c * prm_.c);       // P.36
  }
}

void Solver::reorder_fluid() {
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  if (n == nb) return;
  std::vector<std::uint32_t> key(n - nb);
  for (std::size_t i = nb; i < n; ++i) key[i - nb] = static_cast<std::uint32_t>(grid_.cell_index(P_.x[i]));
  std::vector<std::size_t> order(n - nb);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  auto permute = [&](auto& vec) {
    auto copy = vec;
    for (std::size_t k = 0; k < order.size(); ++k) vec[nb + k] = copy[nb + order[k]];
  };
  permute(P_.x);
  permute(P_.v);
  permute(P_.rho);
  permute(P_.p);
  permute(P_.m);
  permute(P_.kind);
  permute(P_.group);
  permute(P_.id);
}

std::optional<Failure> Solver::check_health() const {
  const std::size_t n = P_.size();
  const real lo = prm_.rho_min_ratio * prm_.rho0, hi = prm_.rho_max_ratio * prm_.rho0;
  const real h = prm_.h;
  std::int64_t worst = std::numeric_limits<std::int64_t>::max();
#pragma omp parallel for schedule(static) reduction(min : worst)
  for (std::size_t i = 0; i < n; ++i) {
    const bool finite = std::isfinite(P_.x[i].x) && std::isfinite(P_.x[i].y) && std::isfinite(P_.v[i].x) &&
                        std::isfinite(P_.v[i].y) && std::isfinite(P_.rho[i]) && std::isfinite(P_.p[i]);
    bool bad = !finite;
    if (!bad && P_.is_fluid(i)) {
      bad = P_.rho[i] < lo || P_.rho[i] > hi;
      const Vec2 x = P_.x[i];
      if (!domain_.periodic_x && (x.x < domain_.lo.x - h || x.x > domain_.hi.x + h)) bad = true;
      if (!domain_.periodic_y && (x.y < domain_.lo.y - h || x.y > domain_.hi.y + h)) bad = true;
    }
    if (bad) worst = std::min(worst, P_.id[i]);
  }
  if (worst == std::numeric_limits<std::int64_t>::max()) return std::nullopt;
  std::size_t i = 0;
  while (P_.id[i] != worst) ++i;
  Failure f;
  f.particle_id = worst;
  f.position = P_.x[i];
  const char* kind = P_.is_fluid(i) ? "fluid" : "boundary";
  char buf[512];
  if (!(std::isfinite(P_.rho[i]) && std::isfinite(P_.p[i]) && std::isfinite(P_.v[i].x) && std::isfinite(P_.v[i].y)))
    std::snprintf(buf, sizeof buf, "non-finite value (NaN or Inf) at %s particle %lld", kind, static_cast<long long>(worst));
  else if (P_.rho[i] < lo || P_.rho[i] > hi)
    std::snprintf(buf, sizeof buf, "density %.6g kg/m^3 of %s particle %lld outside [%.4g, %.4g] (rho0 x [%g, %g])",
                  P_.rho[i], kind, static_cast<long long>(worst), lo, hi, prm_.rho_min_ratio, prm_.rho_max_ratio);
  else
    std::snprintf(buf, sizeof buf, "%s particle %lld left the closed domain", kind, static_cast<long long>(worst));
  f.what = buf;
  return f;
}

}  // namespace particula
