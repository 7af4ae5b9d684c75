// append_candidates: the parallel merge of per-thread candidate lists must give exactly the serial
// concatenation, in list order, whatever the thread count, with lists that cross its copy chunks (2^16 pairs),
// empty lists, and entries already in the output.
#include <gtest/gtest.h>

#include "framework/traversal/candidates.hpp"

namespace ccdlab {
namespace {

FacePairs numbered(std::size_t n, Index tag) {
  FacePairs l;
  for (std::size_t i = 0; i < n; ++i) l.push_back({tag, Index(i)});
  return l;
}

TEST(AppendCandidates, IsTheSerialConcatenationOnAnyNumberOfThreads) {
  const std::vector<FacePairs> lists = {numbered(70000, 1), numbered(0, 2), numbered(131072, 3), numbered(5, 4),
                                        numbered(65536, 5)};
  FacePairs expected = numbered(3, 0);
  for (const FacePairs& l : lists) expected.insert(expected.end(), l.begin(), l.end());
  std::vector<const FacePairs*> ptrs;
  for (const FacePairs& l : lists) ptrs.push_back(&l);
  for (int threads : {1, 2, 3, 8}) {
    FacePairs out = numbered(3, 0);
    const PhaseTrace trace = append_candidates(out, ptrs, threads);
    EXPECT_EQ(out, expected) << threads << " threads";
    EXPECT_EQ(trace.phase, "merge_candidates");
    EXPECT_EQ(trace.task_ms.size(), (expected.size() - 3 + 65535) / 65536) << "one task per 2^16 pairs copied";
  }
  FacePairs out;
  append_candidates(out, {}, 2);
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace ccdlab
