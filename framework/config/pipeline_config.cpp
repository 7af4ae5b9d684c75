#include "framework/config/pipeline_config.hpp"

namespace ccdlab {

PipelineStrategies make_strategies(const PipelineConfig& c, const BuilderRegistry& builders,
                                   const SchedulerRegistry& schedulers, const TesterRegistry& testers,
                                   const SettingName& name) {
  PipelineStrategies s;
  static_cast<PipelineSettings&>(s) = c;
  s.builder = builders.make(c.hierarchy);
  s.scheduler = schedulers.make(c.scheduler);
  s.tester = testers.make(c.tester);
  s.validate(name);
  return s;
}

}  // namespace ccdlab
