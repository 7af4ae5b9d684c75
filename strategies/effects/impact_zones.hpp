#pragma once
// Rigid impact zones (Provot 1997; Bridson, Fedkiw & Anderson 2002, §7.4): ccd_contact's last resort, after
// its impulse rounds and the inelastic projection (inelastic_projection.hpp); the built-in scenes rarely need it, but only it
// guarantees an end. The motion x → p of a sub-step is checked with
// zero thickness; the vertices of every contact found are merged into zones (union–find; zones only grow
// within a sub-step), and each zone then moves rigidly over the sub-step:
//   - a zone with no scripted vertex keeps its linear and angular momentum: p_i = c + dt·v_c + R(dt·ω)(x_i − c),
//     c the centre of mass, v_c its velocity, ω = I⁻¹L;
//   - a zone that holds scripted vertices (obstacles, pinned cloth, handles) moves with their rigid motion.
// Why this ends every crossing: the frame at t is crossing-free, and a rigid motion of a crossing-free set keeps
// it crossing-free, so the only contacts left involve two different zones (or a zone and a free vertex) — and
// the next round merges them. Zones only grow, so the rounds end; in the worst case everything in contact is one
// zone moving with the scripted motion it holds. When contacts keep cascading (a falling zone runs into more
// cloth, round after round), the rounds escalate: everything in contact merges into one zone at once, and
// zones without scripted vertices stop for the sub-step (an inelastic impact, still rigid) instead of carrying
// their momentum into more cloth; later still, the zone takes in the whole of every cloth body it touches (a
// sheet wound round a spinning ball turns with the ball for the sub-step: with one scripted motion, no contact
// can be left).
// The one case rigid motion cannot resolve: a zone holding scripted vertices whose motions differ (cloth that
// touches two obstacles moving differently: draped over a knee, or pinched in the crease of a joint). Such a
// zone is counted as `pinched`, and each of its free vertices follows, of the scripted vertices nearest first,
// the first whose motion keeps it outside every obstacle's exact shape; what this leaves (cloth truly squeezed
// between two bodies) is counted by the caller, never hidden.
#include <cstdint>
#include <vector>

#include "framework/primitive/contact.hpp"
#include "framework/sim/effect.hpp"

namespace ccdlab {

class CcdPipeline;

class ImpactZones {
 public:
  struct Outcome {
    std::size_t left = 0;      ///< contacts still found after the last round
    std::size_t handled = 0;   ///< contacts found, summed over the rounds
    int detections = 0;        ///< CCD steps run (one per round, and the final check)
  };
  /// The whole last resort for one sub-step: detect x → p with `crossing` (zero thickness), merge, move, until
  /// no contact is left, none can be merged, or `max_rounds` rounds ran. `found`: the contacts of the current
  /// motion when the caller has just detected them (the first detection is then skipped).
  Outcome resolve(CcdPipeline& crossing, const SimSetup& setup, SimState& s, double dt, int max_rounds,
                  const Contacts* found = nullptr);

  /// Forgets every zone (each sub-step starts with single vertices).
  void reset(std::size_t vertices);
  /// Merges the vertices of each contact into one zone (`into_one`: the vertices of all contacts into a single
  /// zone). Returns how many contacts joined different zones: 0 means every contact lies inside one rigidly
  /// moving zone already, and another round cannot help.
  std::size_t merge(const Contacts& contacts, bool into_one = false);
  /// Merges every vertex of each cloth body that a contact touches into the first contact's zone (the last
  /// escalation). Returns how many vertices joined.
  std::size_t merge_bodies(const SimSetup& setup, const Contacts& contacts);
  /// Moves every zone of two or more vertices rigidly over the sub-step (p and v of its free vertices).
  void move(const SimSetup& setup, SimState& s, double dt);

  /// The zone of a vertex (its smallest member's index); a vertex in no zone is its own.
  Index zone(Index v) { return find(v); }

  std::uint64_t zones_moved = 0;     ///< zone moves, summed over rounds and sub-steps
  std::uint64_t largest_zone = 0;    ///< vertices in the largest zone seen
  std::uint64_t most_rounds = 0;     ///< the most merge-and-move rounds one sub-step needed
  std::uint64_t escalated = 0;       ///< sub-steps that reached kEscalate rounds (all contacts into one zone)
  static constexpr int kEscalate = 8;
  std::uint64_t whole_bodies = 0;    ///< sub-steps that reached kWholeBodies rounds (whole cloth bodies join)
  static constexpr int kWholeBodies = 16;
  std::uint64_t pinched_zones = 0;   ///< zone moves whose scripted vertices disagree on their motion

 private:
  Index find(Index v);
  void refresh_members();  ///< touched_ from parent_
  std::vector<Index> parent_;
  bool inelastic_ = false;      ///< escalated: zones without scripted vertices stop instead of keeping momentum
  std::vector<Index> touched_;  ///< vertices merged at least once this sub-step (the zones' members)
};

}  // namespace ccdlab
