// Stage 3 (split_filter.hpp): halves and sixteenths of the step, every SIMD target against the plain version,
// and the sixteenths culling at least what the halves cull.
#include <gtest/gtest.h>

#include <random>

#include "framework/narrow/split_filter.hpp"
#include "framework/util/error.hpp"
#include "support/narrow_batches.hpp"
#include "support/simd_targets.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::near_contact_rows;

using test::for_each_simd_target;

TEST(SplitFilter, EverySimdTargetAgreesWithThePlainVersion) {
  // Pairs near contact (stage 2 keeps many of them), at thickness 0 and > 0: stage 3's SIMD kernel against its
  // plain version, VF rows then EE rows as the narrow phase lays them out.
  const std::size_t n = 4001, nvf = 1777;
  PlaneBatch b = near_contact_rows(n, 21);
  for (CullReach reach : {CullReach{0, 2e-9}, CullReach{0.02, 2e-9}}) {
    std::vector<std::uint8_t> stage2(n);
    plane_filter(b, reach, stage2.data());
    for (const int levels : {kSplitCoarseLevels, kSplitLevels}) {
      std::vector<std::uint8_t> expect(n);
      std::vector<std::uint16_t> expect_open(n);
      std::size_t culled = 0, partly_open = 0;
      for (std::size_t i = 0; i < n; ++i) {
        expect_open[i] = split_filter_open(b, i, i < nvf, levels);
        culled += !(expect[i] = split_filter_keeps(b, i, i < nvf, levels));
        EXPECT_EQ(expect[i], expect_open[i] != 0);
        partly_open += expect_open[i] != 0 && expect_open[i] != (1u << (1 << levels)) - 1;
      }
      EXPECT_GT(culled, n / 10);
      EXPECT_GT(partly_open, n / 20);  // the masks mean something: many rows have some windows proven, not all
      for_each_simd_target([&](const char* target) {
        std::vector<std::uint8_t> keep(n, 1);
        std::vector<std::uint16_t> open(n, 0xABCD);
        split_filter(b, 0, nvf, true, keep.data(), levels, open.data());
        split_filter(b, nvf, n, false, keep.data(), levels, open.data());
        EXPECT_EQ(keep, expect) << target << " levels " << levels;
        EXPECT_EQ(open, expect_open) << target << " levels " << levels;
      });
    }
  }
}


TEST(SplitFilter, SixteenthsWithinTheOpenHalvesAgreeWithThePlainVersion) {
  // The sixteenths given the halves pass's open bits, as the narrow phase runs them (the bits read in place):
  // every row's windows within its open halves as the plain version finds them, the other half closed. Rows
  // are mostly one open half, in runs (whole vectors take the eight-window path) and mixed with rows where
  // both are open (their vectors take the sixteen-window path), on every target, at thickness 0 and > 0.
  const std::size_t n = 4001, nvf = 1777;
  PlaneBatch b = near_contact_rows(n, 22);
  std::mt19937 rng(5);
  std::vector<std::uint16_t> halves(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool mixed = (i / 64) % 2 == 1;  // runs of 64 rows: one open half each, then any of 1, 2, 3
    halves[i] = std::uint16_t(mixed ? 1 + rng() % 3 : 1 + rng() % 2);
  }
  for (CullReach reach : {CullReach{0, 2e-9}, CullReach{0.02, 2e-9}}) {
    std::vector<std::uint8_t> stage2(n);
    plane_filter(b, reach, stage2.data());
    std::vector<std::uint8_t> expect(n);
    std::vector<std::uint16_t> expect_open(n);
    std::size_t kept_by_other_half = 0;
    for (std::size_t i = 0; i < n; ++i) {
      expect_open[i] = split_filter_open(b, i, i < nvf, kSplitLevels, halves[i]);
      expect[i] = expect_open[i] != 0;
      const std::uint16_t all = split_filter_open(b, i, i < nvf, kSplitLevels);
      EXPECT_EQ(expect_open[i] & ~all, 0) << "row " << i;  // never opens a window the full pass closes
      kept_by_other_half += all != 0 && expect_open[i] == 0;
    }
    EXPECT_GT(kept_by_other_half, n / 20);  // the closed half matters: rows it alone drops are common
    for_each_simd_target([&](const char* target) {
      std::vector<std::uint8_t> keep(n, 1);
      std::vector<std::uint16_t> open = halves;
      split_filter(b, 0, nvf, true, keep.data(), kSplitLevels, open.data(), open.data());
      split_filter(b, nvf, n, false, keep.data(), kSplitLevels, open.data(), open.data());
      EXPECT_EQ(keep, expect) << target;
      EXPECT_EQ(open, expect_open) << target;
    });
  }
  std::vector<std::uint8_t> keep(1, 1);
  std::uint16_t open = 1;
  EXPECT_THROW(split_filter(b, 0, 1, true, keep.data(), kSplitCoarseLevels, &open, &open), Error);
}


TEST(SplitFilter, SixteenthsCullEveryPairTheHalvesCull) {
  // Running halves before sixteenths must only save work: a pair the halves drop, the sixteenths drop too.
  const std::size_t n = 20000;
  PlaneBatch b = near_contact_rows(n, 22);
  for (CullReach reach : {CullReach{0, 2e-9}, CullReach{0.02, 2e-9}}) {
    std::vector<std::uint8_t> stage2(n);
    plane_filter(b, reach, stage2.data());
    std::size_t halves_culled = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const bool vf = i % 2 == 0;
      if (split_filter_keeps(b, i, vf, kSplitCoarseLevels)) continue;
      ++halves_culled;
      EXPECT_FALSE(split_filter_keeps(b, i, vf, kSplitLevels)) << "row " << i;
    }
    EXPECT_GT(halves_culled, n / 10);
  }
}

}  // namespace CCDLAB_UNITY_ID
}  // namespace ccdlab
