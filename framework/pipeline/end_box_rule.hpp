#pragma once
// Whether a step's traversal tests end boxes (bv.end_boxes, framework/swept/end_boxes.hpp): always (`on`),
// never (`off`), or where they pay (`auto`). The rule object beside the narrow phase's TriangleStageRule, which
// decides stage 0 in the same way: from whole-step counts, so that every schedule decides alike.
//
// End boxes cost every step a pass over the nodes (their refit beside the k-DOPs) and 12 more compares per node
// pair the walk opens; they save the node pairs and the candidates they drop. Under `auto` they run in a step when
// the last step run with them kept at most kKeepAtMost of the candidates of the last step run without them, and
// dropped at least kDropPerFace candidates per face (docs/appendix-wide-bvh.md, "End boxes", gives the thresholds' margins
// on the real steps). Both counts are measured again every kRemeasure steps: one step without (step 0 mod 16), then
// one with (1 mod 16) when the step without had enough candidates to drop. Whole-step candidate counts are the
// same for every scheduler, width, thread count and slicing.
#include <cstddef>
#include <cstdint>

#include "framework/narrow/narrow_phase.hpp"
#include "framework/pipeline/pipeline_settings.hpp"

namespace ccdlab {

class EndBoxRule {
 public:
  static constexpr double kKeepAtMost = 0.5;
  static constexpr double kDropPerFace = 4;
  static constexpr std::uint64_t kRemeasure = 16;
  static_assert(kRemeasure == TriangleStageRule::kRemeasure,
                "stage 0 measures at 2 and 3 mod 16, after the end boxes' steps 0 and 1, on the same kind of candidates");

  explicit EndBoxRule(EndBoxMode mode) : mode_(mode) {}
  /// Whether the next step tests end boxes, when the hierarchies keep them (`kept`), over `faces` triangles.
  [[nodiscard]] bool runs(bool kept, std::size_t faces) const;
  /// A step's candidate count, and whether it tested end boxes.
  void record(bool ran, std::uint64_t candidates);

 private:
  EndBoxMode mode_;
  std::uint64_t steps_ = 0;
  std::uint64_t without_ = 0;  ///< candidates of the last step run without end boxes
  std::uint64_t with_ = 0;     ///< … and with them
};

}  // namespace ccdlab
