#pragma once
// Inelastic projection (Harmon, Vouga, Tamstorf & Grinspun 2008, "Robust treatment of simultaneous
// collisions", §4): ccd_contact's step between its impulse rounds and the rigid impact zones. The impulse rounds
// treat one contact at a time, so a vertex held by two contacts that push different ways (cloth over a knee,
// touching thigh and shin) is pushed back and forth; rigid zones cannot help either, because no rigid motion
// follows both. The projection treats every contact at once: it looks for the velocities closest to the current
// ones in kinetic energy,
//     minimise ½ Σ m_i |v_i − v̂_i|²   subject to   g_c(v) = n_c · Σ_k w_ck v_k ≥ b_c   for every contact c,
// one row per contact (ContactRow: its four vertices, weights w, normal n and the separation it must keep), and
// solves it by projected Gauss–Seidel on the multipliers λ_c ≥ 0 (each row's impulse only pushes apart, but a
// later row may take back what an earlier one pushed too far — unlike the impulse rounds, whose impulses only
// add up). Scripted vertices (inverse mass 0) do not move. Rows are kept for the whole sub-step: a contact found
// in an earlier round stays a constraint, so a round cannot undo what an earlier one fixed (Harmon et al. keep
// them for the same reason). The motion is checked again with CCD after each solve; what the rows' linearisation
// misses (the normal is taken at the time of contact) shows up as a new contact in the next round.
#include <array>
#include <vector>

#include "framework/primitive/contact.hpp"
#include "framework/sim/effect.hpp"

namespace ccdlab {

class CcdPipeline;

/// One contact as a linear constraint on the velocities of its four vertices over the sub-step.
struct ContactRow {
  std::array<std::size_t, 4> vertices{};
  std::array<double, 4> w{};  ///< VF: vertex − face point; EE: point on edge a − point on edge b
  Vec3 n = Vec3::Zero();      ///< unit normal at the time of contact, oriented so the separation at t is ≥ 0
  double target = 0;          ///< the normal relative velocity b that ends the sub-step `gap` apart
  double mass = 0;            ///< Σ w_k² / m_k: 0 when no vertex is free
  double lambda = 0;          ///< accumulated impulse (projection only)

  /// n · Σ w_k v_k: the relative normal velocity of the features.
  [[nodiscard]] double normal_velocity(const Positions& v) const;
  /// Adds the impulse j along n to the free vertices' velocities.
  void apply(const SimSetup& setup, Positions& v, double j) const;
};

/// The row of a contact of the motion s.x → s.p: the features must end the sub-step at least `gap` apart along
/// the contact's normal, velocities taken as constant. Returns a row with n = 0 where the normal is undefined
/// (degenerate face, parallel edges at the time of contact).
ContactRow contact_row(const Contact& c, const SimSetup& setup, const SimState& s, double dt, double gap);

class InelasticProjection {
 public:
  struct Outcome {
    Contacts left;  ///< contacts still found after the last round (for the impact zones)
    int detections = 0;         ///< CCD steps run
  };
  /// Detects x → p with `crossing` (zero thickness), adds a row per contact found, projects, updates p, until no
  /// contact is left or `max_rounds` solves ran. Rows end each sub-step `gap` apart.
  Outcome resolve(CcdPipeline& crossing, const SimSetup& setup, SimState& s, double dt, double gap, int max_rounds);

  std::uint64_t rows = 0;          ///< constraint rows, summed over sub-steps
  std::uint64_t solves = 0;        ///< projections solved (one per round)
  std::uint64_t sweeps = 0;        ///< Gauss–Seidel sweeps, summed
  std::uint64_t unconverged = 0;   ///< solves that ended at kMaxSweeps (the next detection decides)
  std::uint64_t resolved = 0;      ///< sub-steps with contacts that the projection left free of contacts
  static constexpr int kMaxSweeps = 200;

 private:
  /// Projected Gauss–Seidel over every row, until no row's normal velocity changes by more than `tolerance`
  /// in a sweep or kMaxSweeps ran (counted in `unconverged`).
  void solve(const SimSetup& setup, SimState& s, double tolerance);
  std::vector<ContactRow> rows_;  ///< every contact found this sub-step, one row per round it was found in
};

}  // namespace ccdlab
