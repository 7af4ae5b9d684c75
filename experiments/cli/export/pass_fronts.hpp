#pragma once
// The BVTT front of every traversal pass of a pipeline that runs the `front` scheduler (what `ccdlab export`
// draws, as VTK files or in the teaching page).
#include <vector>

#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/schedulers/front_scheduler.hpp"

namespace ccdlab::cli {

using Fronts = std::vector<std::vector<FrontNode>>;  ///< per traversal pass

inline Fronts fronts_of(const CcdPipeline& pipeline) {
  const auto* front = dynamic_cast<const FrontScheduler*>(pipeline.strategies().scheduler.get());
  Fronts out;
  for (const TraversalPass& pass : pipeline.passes()) out.push_back(front->front(pass.id));
  return out;
}

}  // namespace ccdlab::cli
