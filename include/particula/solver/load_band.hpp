// The loads on solids from the fluid's momentum balance in a band round each solid
// (numerics.force = "momentum"; docs/method.md, "Forces on solids"; the per-entry formulas are
// the PARTICULA_HD functions of solver/momentum_loads.hpp). The band (phi_B and its gradient at
// each fluid particle near a solid, with its Voronoi cell) depends on positions only: it is built
// from the solids' signed distances, in particle order whatever the thread count, and with
// numerics.load_band_motion kept across steps until a solid or a particle has moved that far.
// The backend evaluates its entries each stage (Backend::band_levels, band_loads); their loads
// are summed per group in one fixed order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "particula/bodies/contact_pairs.hpp"
#include "particula/core/types.hpp"
#include "particula/neighbors/body_cells.hpp"
#include "particula/neighbors/domain.hpp"
#include "particula/neighbors/neighbor_list.hpp"
#include "particula/solver/momentum_loads.hpp"
#include "particula/solver/particles.hpp"
#include "particula/solver/physics_params.hpp"
#include "particula/solver/rigid_group.hpp"
#include "particula/solver/solids.hpp"

namespace particula {

class Backend;

/// Where the kept band of the momentum loads was last built (numerics.load_band_motion > 0):
/// every particle's position and every rigid group's position and angle then. Checkpoints carry
/// it, so that a resumed run rebuilds the band the uninterrupted run holds at that step
/// (LoadBand::restore). Empty while no band is kept.
struct LoadBandState {
  std::vector<Vec2> x;      // every particle (boundary block first), in the particle order of the build
  std::vector<Vec2> pos;    // every rigid group
  std::vector<real> angle;  // every rigid group
  bool held() const { return !x.empty(); }
};

/// What the band reads of the solver's state, frozen during a step.
struct BandScene {
  const PhysicsParams& prm;
  const Domain& domain;
  const Particles& particles;  // the host copy: block sizes, kinds, surface samples
  const std::vector<RigidGroup>& groups;
};

class LoadBand {
 public:
  /// The band of this step: built, or kept (numerics.load_band_motion) while nothing has moved
  /// too far; a reordering renumbers the particles and rebuilds it. The positions and their grid
  /// come from `backend`, which gets the entries of each build.
  void update(const BandScene& s, Backend& backend, bool reordered);
  /// The band momentum balance of every group for the current stage, its entries evaluated by
  /// `backend`: each group's pressure, viscous and damping loads and torque.
  void group_loads(const BandScene& s, Backend& backend, std::vector<RigidGroup>& groups);

  /// Where the kept band was built (checkpoints carry it); empty while none is kept.
  const LoadBandState& state() const { return built_; }
  /// Restores a checkpoint's kept band: the next update builds it again from the positions and
  /// poses it was built from (the same band, bitwise), then tests the motion since as always.
  void restore(const LoadBandState& s) {
    built_ = s;
    restore_ = s.held();
  }
  /// Builds of the band so far (a kept band is built less often than once a step).
  std::int64_t builds() const { return builds_; }
  /// The kept band's last build: each particle's motion limit, squared (m^2), and the solid it
  /// moves relative to (its closest, for a particle in the band; -1: its own motion counts).
  const std::vector<real>& limits2() const { return limit2_; }
  const std::vector<std::int32_t>& anchors() const { return anchor_; }

 private:
  /// The entries at positions x for the solids at the poses pos_, angle_, the Voronoi cells from
  /// the neighbours `nbrs` at x; handed to `backend`.
  void build(const BandScene& s, const std::vector<Vec2>& x, const HostNeighbors& nbrs, Backend& backend);
  /// One thread's entries for fluid particles [f0, f1) of the fluid block, in particle order.
  void build_entries(const BandScene& s, const std::vector<Vec2>& x, const HostNeighbors& nbrs,
                     std::size_t f0, std::size_t f1, std::vector<BandEntry>& part);
  /// Whether, since the kept band was built (positions x now), a solid surface has moved more
  /// than numerics.load_band_motion, two solids near each other have closed in by more than
  /// solids_closed_in allows, or a particle has moved more than its limit, relative to its
  /// closest solid for a particle in the band. Fills shift_, turn_reach_ and turn_cs_.
  bool moved(const BandScene& s, const std::vector<Vec2>& x);
  /// Whether a solid surface has moved more than numerics.load_band_motion (fills shift_,
  /// turn_reach_, turn_cs_); `largest` gets the largest surface motion.
  bool solid_moved(const BandScene& s, real& largest);
  /// Whether two solids whose gap g is below load_band_motion / kBandGapShare have moved
  /// relative to each other by more than kBandGapShare max(g, kBandGapFloor d0) since the build.
  bool solids_closed_in(const BandScene& s);
  /// Whether a particle has moved beyond its limit since the build.
  bool particle_moved(const BandScene& s, const std::vector<Vec2>& x) const;
  /// Each entry's slot among the groups of its block of kBandBlock entries, and each block's
  /// groups (block_first_, slot_group_).
  void assign_slots(std::size_t groups);
  /// The blocks' partial sums (per slot) added per group in block order into `total`.
  template <class T>
  void add_up(std::size_t groups, const std::vector<T>& partial, std::vector<T>& total) const;
  /// The solids within `reach` of x (walls, then the bodies of the cells round x): at most `max`.
  int near_solids(const BandScene& s, Vec2 x, real reach, NearSolid* out, int max) const;
  /// Solid k's distance and its gradient at x into `out` when x is within `reach` of it.
  bool offer_near_solid(const BandScene& s, Vec2 x, real reach, std::size_t k, NearSolid& out) const;
  /// The area that weighs fluid particle i's grad(phi) terms (positions x, neighbours `nbrs`): its
  /// Voronoi cell among the particles within h, or 0 (its volume m / rho) when a surface particle
  /// is within h or the cell is not closed.
  real cell_area(const BandScene& s, std::size_t i, const std::vector<Vec2>& x,
                 const HostNeighbors& nbrs) const;
  /// The walls at the band's poses and the bodies' cos / sin of their angles, once a build.
  void place_solids(const BandScene& s);
  /// The bodies binned into cells of (largest bounding radius + reach), once a build.
  void bin_bodies(const BandScene& s, real reach);
  /// The stage's constants as the per-entry functions read them (the backend adds its arrays).
  LoadArrays load_arrays(const BandScene& s) const;
  /// Pass 1 of the loads: each group's level K_B (group_level_).
  void sum_levels(const BandScene& s, const LoadArrays& a, Backend& backend);
  /// Pass 2: the loads of the entries summed per group (load_total_).
  void sum_loads(const BandScene& s, const LoadArrays& a, Backend& backend);
  /// The load of group k's smooth pressure P_h, added exactly: the segment integral for a wall,
  /// -rho_h g_h A for a body with fluid all round, else the surface sum.
  void smooth_pressure_load(const BandScene& s, const LoadArrays& a, std::size_t k, Vec2& force,
                            real& torque) const;

  // the entries of this band in particle order, and the groups of each block of entries
  std::vector<BandEntry> band_;
  std::vector<std::vector<BandEntry>> parts_;  // per thread: the entries of its range of particles
  std::vector<std::size_t> part_first_;        // where thread t's entries start in band_
  std::vector<std::size_t> block_first_;       // block b's groups: slot_group_[first[b]...]
  std::vector<std::int32_t> slot_group_;       // the group of each block's slot
  // the sums of a stage
  std::vector<Vec2> level_partial_, level_total_;  // (num, den) of K_B per block slot / group
  std::vector<BandLoadSum> load_partial_, load_total_;
  std::vector<std::uint8_t> group_circle_;  // group k is a circular body
  std::vector<Vec2> group_pos_;
  std::vector<real> group_level_;
  // the solids as the band was built
  BodyCells bodies_;  // the bodies binned once a build for near_solids
  std::vector<BodyCells::Item> body_items_;
  CellGrid grid_;                 // a restored band's positions binned for cell_area
  std::vector<WallPiece> walls_;  // wall group k at the band's build (walls come first)
  std::vector<Vec2> turn_;        // body group k: cos and sin of its angle at the band's build
  std::vector<Vec2> pos_;         // group k's position the band is built at
  std::vector<real> angle_;       // group k's angle the band is built at
  // the kept band (numerics.load_band_motion)
  LoadBandState built_;               // where the kept band was built
  bool restore_ = false;              // built_ came from a checkpoint: build the band from it
  std::vector<Vec2> shift_;           // group k's displacement since the band's build
  std::vector<real> turn_reach_;      // how far group k's turn since the build can move its surface
  std::vector<Vec2> turn_cs_;         // cos and sin of group k's turn since the band's build
  BodyList body_list_;                // the bodies, for solids_closed_in
  std::vector<BodyPair> pairs_;       // bodies near each other (solids_closed_in)
  std::vector<real> limit2_;          // each particle's kept-band motion limit, squared
  std::vector<std::int32_t> anchor_;  // the solid a particle next to one moves relative to, or -1
  std::int64_t builds_ = 0;
};

}  // namespace particula
