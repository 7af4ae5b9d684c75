#pragma once
// Memory of the running process, for the memory limit of a run (config `memory_limit`) and the peak resident
// memory reported per step. Linux: /proc/self/status (VmRSS, VmHWM) and /proc/self/clear_refs (writing 5
// resets the high-water mark, so each step's peak is its own); elsewhere the functions return 0 ("unknown").
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
/// some VMs one costs microseconds (docs/narrow-phase.md, "Memory touched once"), so a step reports its own.
std::uint64_t minor_page_faults();

/// "8GiB", "512MiB", "1.5G", "2000000000" (bytes) or "60%" (of available_memory_bytes()); "0" or "none" = no
/// limit (returns 0). Throws Error naming `what` on anything else.
std::uint64_t parse_memory_size(const std::string& text, const std::string& what);

/// "1.23 GiB", "45.6 MiB", "789 KiB" for messages.
std::string format_bytes(std::uint64_t bytes);

}  // namespace ccdlab
