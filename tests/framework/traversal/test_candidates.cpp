// CandidateList: the parts are the candidate list in part order, read in place (for_each_span cuts any range
// of the concatenation at part boundaries, empty parts included); clear keeps memory, release returns it;
// reserve makes room ahead without writing a pair.
#include <gtest/gtest.h>

#include "framework/traversal/candidates.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

FacePairs numbered(std::size_t n, Index tag) {
  FacePairs l;
  for (std::size_t i = 0; i < n; ++i) l.push_back({tag, Index(i)});
  return l;
}

CandidateList parts_of(const std::vector<FacePairs>& lists) {
  CandidateList c;
  c.use_parts(int(lists.size()));
  for (std::size_t i = 0; i < lists.size(); ++i) c.part(int(i)) = lists[i];
  return c;
}

TEST(CandidateList, IsItsPartsInPartOrder) {
  const std::vector<FacePairs> lists = {numbered(700, 1), numbered(0, 2), numbered(1300, 3), numbered(5, 4),
                                        numbered(0, 5)};
  const CandidateList c = parts_of(lists);
  FacePairs expected;
  for (const FacePairs& l : lists) expected.insert(expected.end(), l.begin(), l.end());
  EXPECT_EQ(c.num_parts(), 5);
  EXPECT_EQ(c.size(), expected.size());
  EXPECT_EQ(c.flatten(), expected);
  // Every range, in chunks of several sizes (crossing part ends, empty parts, the last pair alone).
  for (std::size_t chunk : {std::size_t(1), std::size_t(7), std::size_t(512), std::size_t(700), expected.size()}) {
    FacePairs read;
    std::size_t calls = 0;
    for (std::size_t b = 0; b < expected.size(); b += chunk)
      c.for_each_span(b, std::min(expected.size(), b + chunk), [&](std::span<const FacePair> s) {
        EXPECT_FALSE(s.empty()) << "no call for an empty piece";
        read.insert(read.end(), s.begin(), s.end());
        ++calls;
      });
    EXPECT_EQ(read, expected) << "chunk " << chunk;
    EXPECT_GE(calls, (expected.size() + chunk - 1) / chunk);
  }
  int calls = 0;
  c.for_each_span(700, 700, [&](std::span<const FacePair>) { ++calls; });
  c.for_each_span(2005, 2005, [&](std::span<const FacePair>) { ++calls; });
  EXPECT_EQ(calls, 0) << "empty ranges";
}

TEST(CandidateList, ClearKeepsMemoryReleaseReturnsIt) {
  CandidateList c;
  EXPECT_EQ(c.num_parts(), 1) << "part 0 always exists";
  EXPECT_TRUE(c.empty());
  c.use_parts(3);
  c.part(2) = numbered(100, 2);
  c.use_parts(2);  // never shrinks
  EXPECT_EQ(c.num_parts(), 3);
  EXPECT_EQ(c.size(), 100u);
  c.clear();
  EXPECT_TRUE(c.empty());
  EXPECT_GE(c.part(2).capacity(), 100u);
  c.release();
  EXPECT_EQ(c.part(2).capacity(), 0u);
  EXPECT_EQ(c.num_parts(), 3);
}

TEST(CandidateList, ReserveMakesRoomInEachPartWithoutAddingPairs) {
  CandidateList c;
  c.part(0) = numbered(10, 0);
  c.reserve(4, 5000);
  EXPECT_EQ(c.num_parts(), 4);
  EXPECT_EQ(c.size(), 10u);
  EXPECT_GE(c.part(0).capacity(), 5010u) << "room beyond what the part holds";
  for (int i = 1; i < 4; ++i) EXPECT_GE(c.part(i).capacity(), 5000u);
  const FacePair* before = c.part(1).data();
  for (int i = 0; i < 5000; ++i) c.part(1).push_back({1, i});
  EXPECT_EQ(c.part(1).data(), before) << "filling the reserved room does not reallocate";
  EXPECT_LE(c.part(3).capacity(), CandidateList::kMaxReservedPairs);
}

}  // namespace
}  // namespace ccdlab
