#include "framework/pipeline/end_box_rule.hpp"

#include <algorithm>

namespace ccdlab {

bool EndBoxRule::runs(bool kept, std::size_t faces) const {
  if (!kept) return false;
  if (mode_ == EndBoxMode::on) return true;
  const double f = double(faces);
  const bool may_pay = double(without_) >= kDropPerFace * f;
  switch (steps_ % kRemeasure) {
    case 0: return false;    // measures the candidates without
    case 1: return may_pay;  // measures them with
    default:
      return may_pay && double(with_) <= kKeepAtMost * double(without_) &&
             double(without_ - std::min(with_, without_)) >= kDropPerFace * f;
  }
}

void EndBoxRule::record(bool ran, std::uint64_t candidates) {
  (ran ? with_ : without_) = candidates;
  ++steps_;
}

}  // namespace ccdlab
