#include <gtest/gtest.h>

#include "framework/pipeline/schedule_sim.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

TEST(ScheduleSim, DynamicListScheduling) {
  PhaseTrace t{"p", Distribution::dynamic, 1.0, {4, 1, 1, 1, 1}, {}};
  EXPECT_DOUBLE_EQ(simulate_phase(t, 1), 9.0);
  EXPECT_DOUBLE_EQ(simulate_phase(t, 2), 5.0);   // 4 | 1+1+1+1
  EXPECT_DOUBLE_EQ(simulate_phase(t, 8), 5.0);   // the longest task bounds it
  PhaseTrace late_big{"p", Distribution::dynamic, 0, {1, 1, 1, 1, 4}, {}};
  EXPECT_DOUBLE_EQ(simulate_phase(late_big, 2), 6.0);  // order matters: the big task starts at 2
}

TEST(ScheduleSim, StaticChunksDoNotRebalance) {
  PhaseTrace t{"p", Distribution::static_chunks, 0, {4, 4, 1, 1}, {}};
  EXPECT_DOUBLE_EQ(simulate_phase(t, 2), 8.0);  // chunks {4, 4} and {1, 1}
  t.distribution = Distribution::dynamic;
  EXPECT_DOUBLE_EQ(simulate_phase(t, 2), 5.0);  // 4+1 | 4+1
}

TEST(ScheduleSim, StaticBalancedAssignsLargestFirstToTheLeastLoadedCore) {
  // 7 -> core 0; 5 -> core 1; 1 -> core 1 (5 < 7); 1 -> core 1 (6 < 7): loads 7 | 7.
  EXPECT_EQ(assign_largest_first({5, 1, 7, 1}, 2), (std::vector<int>{1, 1, 0, 1}));
  EXPECT_EQ(assign_largest_first({3, 3, 3}, 1), (std::vector<int>{0, 0, 0}));
  PhaseTrace t{"p", Distribution::static_balanced, 0.5, {5, 1, 7, 1}, {}};
  EXPECT_DOUBLE_EQ(simulate_phase(t, 2), 7.5);
  t.distribution = Distribution::static_chunks;
  EXPECT_DOUBLE_EQ(simulate_phase(t, 2), 8.5);  // chunks {5, 1} and {7, 1}
}

TEST(ScheduleSim, StepSumsPhasesAndSerialPartsStaySerial) {
  std::vector<PhaseTrace> step{{"a", Distribution::dynamic, 2.0, {}, {}},
                               {"b", Distribution::dynamic, 0.5, std::vector<double>(64, 1.0), {}}};
  EXPECT_DOUBLE_EQ(simulate_step(step, 1), 66.5);
  EXPECT_DOUBLE_EQ(simulate_step(step, 64), 3.5);
  EXPECT_DOUBLE_EQ(imbalance({"x", Distribution::dynamic, 0, {}, {3.0, 1.0}}), 1.5);
}

TEST(ScheduleSim, RegionsOfAPhaseEndAtABarrier) {
  PhaseTrace t{"p", Distribution::dynamic, 0, {2, 2}, {}};
  EXPECT_DOUBLE_EQ(simulate_phase(t, 2), 2.0);  // one region: side by side
  t.region_begin = {0, 1};
  EXPECT_DOUBLE_EQ(simulate_phase(t, 2), 4.0);  // two regions: one after the other
  EXPECT_DOUBLE_EQ(simulate_phase(t, 1), 4.0);
}

TEST(ScheduleSim, TheMachineAddsForkJoinPerRegionAndInflatesTasksOnMoreThanOneCore) {
  const MachineModel m{{0.1, 0.3}, {{"p", 1.5}}};
  PhaseTrace t{"p", Distribution::dynamic, 1.0, {2, 2}, {}, {0, 1}};
  EXPECT_DOUBLE_EQ(simulate_phase(t, 1, &m), 5.0);                    // what one thread recorded
  EXPECT_DOUBLE_EQ(simulate_phase(t, 2, &m), 1.0 + 2 * (2 * 1.5) + 2 * 0.2);
  EXPECT_DOUBLE_EQ(simulate_phase(t, 8, &m), simulate_phase(t, 2, &m));  // beyond the probe: its last values
  t.phase = std::string("q");  // no inflation measured: none (a temporary: GCC 12 -Wrestrict misfires on = "q")
  EXPECT_DOUBLE_EQ(simulate_phase(t, 2, &m), 1.0 + 2 * 2 + 2 * 0.2);
  EXPECT_DOUBLE_EQ(MachineModel{}.inflation("p", 4), 1.0);
  EXPECT_DOUBLE_EQ(MachineModel{}.fork_join(4), 0.0);
}

TEST(ScheduleSim, TaskInflationIsTheRatioOfTaskTimePerPhase) {
  const std::vector<std::vector<PhaseTrace>> alone{{{"a", Distribution::dynamic, 0, {1, 1}, {}}, {"s", Distribution::dynamic, 3, {}, {}}},
                                                   {{"a", Distribution::dynamic, 0, {2}, {}}}};
  const std::vector<std::vector<PhaseTrace>> parallel{{{"a", Distribution::dynamic, 0, {2, 2}, {}}, {"s", Distribution::dynamic, 2, {}, {}}},
                                                      {{"a", Distribution::dynamic, 0, {2}, {}}}};
  const auto inflation = measure_task_inflation(alone, parallel);
  EXPECT_EQ(inflation.size(), 1u);  // a phase without tasks has none
  EXPECT_DOUBLE_EQ(inflation.at("a"), 6.0 / 4.0);
}

TEST(ScheduleSim, TimeOutsideEveryPhaseIsSerial) {
  const std::vector<PhaseTrace> traces{{"a", Distribution::dynamic, 1.0, {2, 3}, {5.0}},
                                       {"b", Distribution::dynamic, 0.5, {4, 4}, {}}};
  const PhaseTrace rest = untraced_time(traces, 20.0);
  EXPECT_EQ(rest.phase, "untraced");
  EXPECT_DOUBLE_EQ(rest.serial_ms, 20.0 - (1.0 + 5.0) - (0.5 + 8.0));
  EXPECT_TRUE(rest.task_ms.empty());
  EXPECT_DOUBLE_EQ(untraced_time(traces, 1.0).serial_ms, 0.0);  // never negative
}

TEST(ScheduleSim, TheProbeMeasuresEveryThreadCount) {
  const MachineModel m = probe_machine(2);
  ASSERT_EQ(m.fork_join_ms.size(), 2u);
  for (double f : m.fork_join_ms) EXPECT_GT(f, 0.0);
  EXPECT_TRUE(m.task_inflation.empty());
}

}  // namespace
}  // namespace ccdlab
