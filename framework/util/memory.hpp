#pragma once
// Memory of the running process, for the memory limit of a run (config `memory_limit`) and the peak resident
// memory reported per step. Linux: /proc/self/status (VmRSS, VmHWM) and /proc/self/clear_refs (writing 5
// resets the high-water mark, so each step's peak is its own); elsewhere the functions return 0 ("unknown").
#include <cstddef>
#include <cstdint>
#include <string>

namespace ccdlab {

/// Bytes of memory this process may use: the machine's RAM, or the cgroup's limit when lower (containers).
std::uint64_t available_memory_bytes();

/// Resident memory now, and its peak since the last reset_peak_rss() (or since the start).
std::uint64_t current_rss_bytes();
std::uint64_t peak_rss_bytes();
void reset_peak_rss();

/// Minor page faults of this process so far (getrusage), all threads: each is a first touch of a new page. On
/// some VMs one costs microseconds (docs/appendix-narrow-phase.md, "Memory touched once"), so a step reports its own.
std::uint64_t minor_page_faults();

/// Large arrays (node volumes, BVH nodes, build items and boxes, feature bounds, candidate lists: every
/// UninitializedVector and UnconstructedVector, through GrowthAllocator) in transparent huge pages. A
/// fresh 4 KiB page costs a fault on first touch, microseconds on some VMs (docs/appendix-measurements.md), which
/// can dominate a pass that writes each element once. One 2 MiB page takes one fault. Allocations of
/// kLargeAllocation bytes or more (1 MiB: zeroing one 2 MiB page costs less than the 256 faults of 1 MiB in 4 KiB
/// pages) are 2 MiB-aligned and marked MADV_HUGEPAGE (Linux; the kernel's THP setting decides, "never" turns it off); CCDLAB_HUGE_PAGES=off in
/// the environment turns it off for the process (read once).
constexpr std::size_t kLargeAllocation = std::size_t(1) << 20;
/// True when an allocation of `bytes` goes through allocate_large (the same answer for the whole process).
bool is_large_allocation(std::size_t bytes);
/// 2 MiB-aligned memory for `bytes` (rounded up to whole huge pages), marked for huge pages; throws
/// std::bad_alloc. Free it with free_large.
void* allocate_large(std::size_t bytes);
void free_large(void* p);

/// "8GiB", "512MiB", "1.5G", "2000000000" (bytes) or "60%" (of available_memory_bytes()); "0" or "none" = no
/// limit (returns 0). Throws Error naming `what` on anything else.
std::uint64_t parse_memory_size(const std::string& text, const std::string& what);

/// "1.23 GiB", "45.6 MiB", "789 KiB" for messages.
std::string format_bytes(std::uint64_t bytes);

}  // namespace ccdlab
