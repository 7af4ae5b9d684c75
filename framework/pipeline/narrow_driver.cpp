#include "framework/pipeline/narrow_driver.hpp"

#include <algorithm>
#include <chrono>

#include "framework/pipeline/phase_clock.hpp"

namespace ccdlab {
namespace {

using Clock = std::chrono::steady_clock;

// Chunk sizes: large enough to amortise a hand-out, a clock read and a batch's padding, small enough to balance
// (docs/pipeline.md). An orphan costs a few ns at stage 1, a candidate ~50 feature pairs: hence the ratio.
constexpr std::size_t kCandidateChunk = 512;
constexpr std::size_t kOrphanChunk = 128 * OrphanCertificates::kBlock;  // whole blocks (their certificates)

}  // namespace

template <class Gather>
void NarrowDriver::run_chunk(ThreadState& s, std::size_t candidates, Gather&& gather) const {
  if (watch_ && watch_->stopped()) return;  // past a limit: the pipeline throws once the threads are done
  const std::size_t contacts_before = s.contacts.size();
  FeatureBatch& batch = s.scratch.batch;
  batch.clear();
  const auto t = Clock::now();
  const std::uint64_t staged_before = s.counters.kdop_ns + s.counters.triangle_ns;
  gather(s.scratch, s.counters);
  // What a gather spent on stage 0 or stage 1 (gather_orphans) counts there, not twice.
  s.counters.gather_ns += std::uint64_t(ms_since(t) * 1e6) - (s.counters.kdop_ns + s.counters.triangle_ns - staged_before);
  if (record_tested_) {
    s.tested_vf.insert(s.tested_vf.end(), batch.vf.begin(), batch.vf.end());
    s.tested_ee.insert(s.tested_ee.end(), batch.ee.begin(), batch.ee.end());
  }
  narrow_.run(s.scratch, s.contacts, s.counters);
  if (watch_) watch_->advance(candidates, s.contacts.size() - contacts_before);
}

double NarrowDriver::merge(const std::vector<PerThread<ThreadState>>& local, StepResult& result) const {
  const auto t0 = Clock::now();
  for (const auto& per_thread : local) {
    const ThreadState& s = per_thread.value;
    result.counters += s.counters;
    result.tested_vf.insert(result.tested_vf.end(), s.tested_vf.begin(), s.tested_vf.end());
    result.tested_ee.insert(result.tested_ee.end(), s.tested_ee.begin(), s.tested_ee.end());
  }
  return ms_since(t0);
}

template <class Gather>
void NarrowDriver::in_parallel(std::size_t n, std::size_t chunk, bool candidates, const char* phase, double* timing,
                               StepResult& result, Gather&& gather) const {
  PhaseClock(result).parallel(phase, timing, [&](PhaseTrace& trace) {
    std::vector<PerThread<ThreadState>>& local = thread_states();
    parallel_chunks(n, chunk, threads_, trace, [&](std::size_t b, std::size_t e, int tid) {
      run_chunk(local[tid].value, candidates ? e - b : 0,
                [&](NarrowScratch& scratch, NarrowCounters& c) { gather(b, e, scratch, c); });
    });
    trace.serial_ms += merge(local, result);
  });
}

void NarrowDriver::begin_step() const {
  for (PerThread<ThreadState>& state : states_) state.value.contacts.clear();
}

void NarrowDriver::sort_contacts_into(Contacts& out, ContactSortScratch& scratch, PhaseTrace& trace) const {
  std::vector<std::span<const Contact>> parts;
  for (const PerThread<ThreadState>& state : states_) parts.emplace_back(state.value.contacts);
  const auto t0 = Clock::now();
  double parallel_ms = 0;
  // Each thread sorts its own list (static: part i on thread i); the merge that follows is serial.
  const PartRunner in_parallel = [&](std::size_t n, const std::function<void(std::size_t)>& task) {
    const auto t = Clock::now();
    parallel_tasks(n, threads_, Distribution::static_chunks, trace, [&](std::size_t i, int) { task(i); });
    parallel_ms += ms_since(t);
  };
  ccdlab::sort_contacts_into(parts, out, scratch, threads_ > 1 ? in_parallel : PartRunner{});
  trace.serial_ms += ms_since(t0) - parallel_ms;
}

std::vector<PerThread<NarrowDriver::ThreadState>>& NarrowDriver::thread_states() const {
  states_.resize(std::size_t(threads_));
  for (PerThread<ThreadState>& state : states_) {
    ThreadState& s = state.value;
    s.counters = {};
    s.tested_vf.clear();
    s.tested_ee.clear();
  }
  return states_;
}

NarrowDriver::InTraversal::InTraversal(const NarrowDriver& driver)
    : driver_(driver), local_(driver.thread_states()), taken_(driver.threads_) {}

void NarrowDriver::InTraversal::take(int tid, std::span<const FacePair> pairs) {
  const auto t = Clock::now();
  for (std::size_t b = 0; b < pairs.size(); b += kCandidateChunk) {
    const auto piece = pairs.subspan(b, std::min(kCandidateChunk, pairs.size() - b));
    driver_.run_chunk(local_[tid].value, piece.size(), [&](NarrowScratch& scratch, NarrowCounters& c) {
      driver_.narrow_.gather(piece, scratch, c, !driver_.record_tested_);
    });
  }
  taken_[tid].value.pairs += pairs.size();
  taken_[tid].value.ms += ms_since(t);
}

double NarrowDriver::InTraversal::finish(StepResult& result) {
  double ms = 0;  // the threads' mean: they ran at once
  for (const auto& tk : taken_) {
    result.counters.candidate_pairs += tk.value.pairs;
    ms += tk.value.ms / double(taken_.size());
  }
  result.timings.narrow_ms += ms;
  // A serial phase of its own: its tasks are the traversal's.
  PhaseClock(result).serial("narrow_in_traversal", &result.timings.narrow_ms, [&] { driver_.merge(local_, result); });
  return ms;
}

void NarrowDriver::test_candidates(const CandidateList& pairs, StepResult& result) const {
  result.counters.candidate_pairs += pairs.size();
  in_parallel(pairs.size(), kCandidateChunk, true, "narrow", &result.timings.narrow_ms, result,
              [&](std::size_t b, std::size_t e, NarrowScratch& scratch, NarrowCounters& c) {
                pairs.for_each_span(b, e, [&](std::span<const FacePair> s) { narrow_.gather(s, scratch, c, !record_tested_); });
              });
}

void NarrowDriver::test_orphans(const std::vector<Index>* face_patch, StepResult& result) const {
  StepCounters& c = result.counters;
  const std::uint64_t vf_before = c.vf_pairs, ee_before = c.ee_pairs, tests_before = c.vf_tests + c.ee_tests;
  const Representatives& reps = narrow_.representatives();
  const OrphanSet& orphans = narrow_.orphans_to_test();
  auto same_skipped_patch = [face_patch](Index f, Index g) {
    return (*face_patch)[f] >= 0 && (*face_patch)[f] == (*face_patch)[g];
  };
  const std::size_t nvf = orphans.vf.size(), n = nvf + orphans.ee.size();
  in_parallel(n, kOrphanChunk, false, "orphans", &result.timings.orphan_ms, result, [&](std::size_t b, std::size_t e, NarrowScratch& scratch, NarrowCounters& lc) {
    FeatureBatch& batch = scratch.batch;
    if (!face_patch) return narrow_.gather_orphans(b, e, batch, lc, !record_tested_);  // recorded: all of them
    for (std::size_t i = b; i < std::min(e, nvf); ++i) {
      const VertexFacePair& p = orphans.vf[i];
      if (same_skipped_patch(reps.face_of_vertex(p.v), p.f)) ++lc.orphans_culled;
      else batch.vf.push_back(p);
    }
    for (std::size_t i = std::max(b, nvf); i < e; ++i) {
      const EdgeEdgePair& p = orphans.ee[i - nvf];
      if (same_skipped_patch(reps.face_of_edge(p.a), reps.face_of_edge(p.b))) ++lc.orphans_culled;
      else batch.ee.push_back(p);
    }
  });
  c.orphan_vf = c.vf_pairs - vf_before;  // orphan pairs considered (culled ones counted apart)
  c.orphan_ee = c.ee_pairs - ee_before;
  c.orphan_tests = c.vf_tests + c.ee_tests - tests_before;
}

}  // namespace ccdlab
