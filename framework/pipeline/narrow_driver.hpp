#pragma once
// Stage 4 of a step (design.md): the narrow phase on every thread. NarrowPhase (framework/narrow/) culls and
// tests one batch; this driver cuts the work into chunks, keeps each thread's state (contacts, counters,
// batch memory), merges the threads' counters in thread order after each loop, and at the end of the step sorts
// the threads' contacts into the step's list (sort_contacts_into: one order whatever the schedule, each contact
// copied once). It takes candidates three ways:
//   InTraversal      on the traversal's own threads, as each thread hands its candidates over
//   test_candidates  a list of candidates left over (or streamed slice by slice), in parallel chunks
//   test_orphans     the orphan set (representatives.hpp), in parallel chunks
#include <span>
#include <vector>

#include "framework/narrow/narrow_phase.hpp"
#include "framework/pipeline/step_result.hpp"
#include "framework/pipeline/step_watch.hpp"

namespace ccdlab {

class NarrowDriver {
 public:
  NarrowDriver(const NarrowPhase& narrow, int threads) : narrow_(narrow), threads_(threads) {}

  /// Tests of the ownership rule: record every feature pair gathered into StepResult::tested_*.
  void record_tested(bool on) { record_tested_ = on; }
  /// The step's watch (time limit, room for contacts, progress): each chunk advances it, and once it has stopped
  /// the workers take no more chunks (the pipeline then throws). Null: none.
  void watch(StepWatch* watch) { watch_ = watch; }
  /// The contacts this step may hold under memory_limit (the memory plan's share for them; 0 = no limit).
  void limit_contacts(std::uint64_t n) const {
    if (watch_) watch_->set_max_contacts(n);
  }
  /// A step begins: the threads' contacts of the last one are dropped (their memory kept).
  void begin_step() const;
  /// The step's contacts, every thread's, sorted by feature identity into `out`: each thread sorts its own,
  /// then they are merged (the merge is `trace`'s serial part).
  void sort_contacts_into(Contacts& out, ContactSortScratch& scratch, PhaseTrace& trace) const;

  /// One thread's state over a parallel loop: what it found and counted, and its batch memory.
  struct ThreadState {
    Contacts contacts;
    NarrowCounters counters;
    NarrowScratch scratch;
    std::vector<VertexFacePair> tested_vf;
    std::vector<EdgeEdgePair> tested_ee;
  };

  /// The narrow phase inside the traversal: take() runs on the thread that found the pairs; finish() merges
  /// (adding the narrow phase's time to StepTimings::narrow_ms) and returns the threads' mean time in take()
  /// (they ran at once): the traversal's time leaves it out.
  class InTraversal {
   public:
    explicit InTraversal(const NarrowDriver& driver);
    void take(int tid, std::span<const FacePair> pairs);
    double finish(StepResult& result);

   private:
    struct Taken {
      std::uint64_t pairs = 0;
      double ms = 0;
    };
    const NarrowDriver& driver_;
    std::vector<PerThread<ThreadState>>& local_;  ///< the driver's, emptied (thread_states)
    std::vector<PerThread<Taken>> taken_;
  };

  /// Every candidate of `pairs` (phase "narrow", into StepTimings::narrow_ms); counts them as candidate pairs.
  void test_candidates(const CandidateList& pairs, StepResult& result) const;
  /// The orphan set (phase "orphans", into StepTimings::orphan_ms). With `face_patch` (normal cones: each face's skipped patch this step, or
  /// −1), a pair of two faces in one skipped patch is culled: the same height-field argument as for the
  /// candidates the traversal skipped.
  void test_orphans(const std::vector<Index>* face_patch, StepResult& result) const;

 private:
  /// One chunk of `candidates` candidate pairs (0 for orphans) on one thread: `gather(scratch, counters)` fills
  /// the scratch's batch, which is then culled and tested; nothing once the step's watch has stopped.
  template <class Gather>
  void run_chunk(ThreadState& state, std::size_t candidates, Gather&& gather) const;
  /// `n` items in chunks on every thread, as the phase `phase` (its ms added to `*timing`):
  /// `gather(begin, end, scratch, counters)` puts a chunk's feature pairs into the scratch's batch; the threads' results are
  /// merged into `result`.
  template <class Gather>
  void in_parallel(std::size_t n, std::size_t chunk, bool candidates, const char* phase, double* timing,
                   StepResult& result, Gather&& gather) const;
  /// Adds the threads' counters and recorded pairs to `result`, in thread order; returns its ms. Their contacts
  /// stay with them until the step's end (sort_contacts_into).
  double merge(const std::vector<PerThread<ThreadState>>& local, StepResult& result) const;
  /// One state per thread, its counters and recorded pairs emptied, its contacts those of the step so far; all
  /// keep their memory: a dense step's contacts would otherwise grow into fresh pages on every thread at every
  /// step (each zeroed by the kernel). A parallel loop or an InTraversal takes them and merges them before the
  /// next one takes them again (a step runs them one after another).
  std::vector<PerThread<ThreadState>>& thread_states() const;

  const NarrowPhase& narrow_;
  int threads_;
  bool record_tested_ = false;
  StepWatch* watch_ = nullptr;
  mutable std::vector<PerThread<ThreadState>> states_;
};

}  // namespace ccdlab
