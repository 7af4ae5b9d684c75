#pragma once
// The work of the narrow phase, counted per stage (design.md: gather → cull → test → scatter). One home for the
// merge of per-thread counters: operator+=.
#include <cstdint>

namespace ccdlab {

struct NarrowCounters {
  std::uint64_t vf_pairs = 0;        ///< vertex–face feature pairs gathered (candidates' representatives + orphans)
  std::uint64_t ee_pairs = 0;        ///< edge–edge feature pairs gathered
  std::uint64_t orphan_vf = 0;       ///< of which from the orphan set
  std::uint64_t orphan_ee = 0;
  std::uint64_t orphans_culled = 0;  ///< orphan pairs inside a patch skipped by normal-cone culling
  std::uint64_t orphans_unmoved = 0;  ///< orphan pairs skipped: their block moved too little since its last test (OrphanCertificates)
  std::uint64_t orphans_carried = 0;  ///< orphan pairs gathered with a candidate that carries them (not in orphan_vf/ee)
  std::uint64_t candidates_gathered = 0;  ///< candidate face pairs whose feature pairs were gathered (after stage 0)
  std::uint64_t triangle_tested = 0;  ///< candidate face pairs stage 0 ran on (batched only, steps where it pays)
  std::uint64_t triangle_culled = 0;  ///< of which proven apart before their gather
  std::uint64_t triangle_fine = 0;    ///< of the tested, those left for its second pass (axes 4–13, normals) by x, y, z
  std::uint64_t kdop_culled = 0;     ///< pairs whose swept feature 26-DOPs are disjoint (stage 1, every mode)
  std::uint64_t plane_culled = 0;    ///< pairs proven to stay off each other's plane/line (stage 2, batched only)
  std::uint64_t split_culled = 0;    ///< pairs proven apart on every half or sixteenth of the step (stage 3, batched only)
  std::uint64_t sixteenths_tested = 0;  ///< of stage 3's, the pairs its sixteenths received (0 in steps where they do not run)
  std::uint64_t sixteenths_culled = 0;  ///< of which proven apart on every sixteenth
  std::uint64_t proximity_tested = 0;  ///< pairs stage 4 received (batched only; 0 in steps where it does not run)
  std::uint64_t proximity_culled = 0;  ///< of which proven apart on the windows stage 3 left open
  std::uint64_t vf_tests = 0;        ///< elementary VF tests run (survivors of the culling stages)
  std::uint64_t ee_tests = 0;        ///< elementary EE tests run
  std::uint64_t orphan_tests = 0;    ///< of the VF + EE tests, those from the orphan set
  std::uint64_t tests_filtered = 0;  ///< elementary tests decided by the tester's own certified filter (TestRoute)
  std::uint64_t tests_fallback = 0;  ///< elementary tests the tester could not decide itself (`conservative`)
  std::uint64_t contacts_vf = 0;
  std::uint64_t contacts_ee = 0;
  // Thread-time per stage, nanoseconds summed over threads (batched mode; scalar mode interleaves them and
  // reports all of it as test_ns).
  std::uint64_t triangle_ns = 0;  ///< stage 0
  std::uint64_t gather_ns = 0;  ///< feature pairs of candidate face pairs (representative rule)
  std::uint64_t kdop_ns = 0;    ///< stage 1
  std::uint64_t plane_ns = 0;   ///< stage 2 (staging the coordinates included)
  std::uint64_t split_ns = 0;   ///< stage 3's halves and its compactions
  std::uint64_t sixteenths_ns = 0;  ///< stage 3's sixteenths (their input's compaction included)
  std::uint64_t proximity_ns = 0;  ///< stage 4's own test
  std::uint64_t orphan_motion_ns = 0;  ///< the orphan certificates' motion pass (serial, before the orphan loop)
  std::uint64_t test_ns = 0;    ///< elementary tests and contact records

  NarrowCounters& operator+=(const NarrowCounters& o) {
    vf_pairs += o.vf_pairs, ee_pairs += o.ee_pairs, orphan_vf += o.orphan_vf, orphan_ee += o.orphan_ee;
    orphans_culled += o.orphans_culled, orphans_unmoved += o.orphans_unmoved, orphans_carried += o.orphans_carried, candidates_gathered += o.candidates_gathered;
    triangle_tested += o.triangle_tested, triangle_culled += o.triangle_culled, triangle_fine += o.triangle_fine, triangle_ns += o.triangle_ns;
    kdop_culled += o.kdop_culled, plane_culled += o.plane_culled;
    split_culled += o.split_culled, split_ns += o.split_ns, sixteenths_ns += o.sixteenths_ns;
    orphan_motion_ns += o.orphan_motion_ns;
    sixteenths_tested += o.sixteenths_tested, sixteenths_culled += o.sixteenths_culled;
    proximity_tested += o.proximity_tested, proximity_culled += o.proximity_culled;
    proximity_ns += o.proximity_ns;
    vf_tests += o.vf_tests, ee_tests += o.ee_tests, orphan_tests += o.orphan_tests;
    tests_filtered += o.tests_filtered, tests_fallback += o.tests_fallback;
    contacts_vf += o.contacts_vf, contacts_ee += o.contacts_ee;
    gather_ns += o.gather_ns, kdop_ns += o.kdop_ns, plane_ns += o.plane_ns, test_ns += o.test_ns;
    return *this;
  }
};

}  // namespace ccdlab
