#include "framework/util/memory.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <new>
#include <fstream>
#include <string_view>

#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include "framework/util/error.hpp"

namespace ccdlab {
namespace {

/// A "Key:   1234 kB" line of /proc/self/status, in bytes; 0 if absent.
std::uint64_t proc_status_kb(std::string_view key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.starts_with(key) && line.size() > key.size() && line[key.size()] == ':')
      return std::stoull(line.substr(key.size() + 1)) * 1024;
  return 0;
}

std::uint64_t read_number_file(const char* path) {
  std::ifstream in(path);
  std::string s;
  if (!(in >> s) || s.empty() || !std::isdigit(static_cast<unsigned char>(s[0]))) return 0;  // "max" = none
  return std::stoull(s);
}

}  // namespace

std::uint64_t available_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  std::uint64_t bytes = pages > 0 && page > 0 ? std::uint64_t(pages) * std::uint64_t(page) : 0;
  for (const char* cgroup : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"})
    if (const std::uint64_t limit = read_number_file(cgroup); limit > 0 && (bytes == 0 || limit < bytes)) bytes = limit;
  return bytes;
}

std::uint64_t current_rss_bytes() { return proc_status_kb("VmRSS"); }
std::uint64_t peak_rss_bytes() { return proc_status_kb("VmHWM"); }

std::uint64_t minor_page_faults() {
  rusage usage{};
  return getrusage(RUSAGE_SELF, &usage) == 0 ? std::uint64_t(usage.ru_minflt) : 0;
}

namespace {
constexpr std::size_t kHugePage = std::size_t(2) << 20;
bool huge_pages_wanted() {
  static const bool on = [] {
    const char* v = std::getenv("CCDLAB_HUGE_PAGES");
    return !(v && (std::string_view(v) == "off" || std::string_view(v) == "0"));
  }();
  return on;
}
}  // namespace

bool is_large_allocation(std::size_t bytes) { return bytes >= kLargeAllocation && huge_pages_wanted(); }

void* allocate_large(std::size_t bytes) {
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  (void)madvise(p, rounded, MADV_HUGEPAGE);  // advice only: without THP the pages stay 4 KiB
#endif
  return p;
}

void free_large(void* p) { std::free(p); }

void reset_peak_rss() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";  // resets VmHWM to the current RSS (Linux ≥ 4.0); harmless where it is not supported
}

std::uint64_t parse_memory_size(const std::string& text, const std::string& what) {
  auto bad = [&]() -> std::uint64_t {
    fail("{}: expected a size like 8GiB, 512MiB or 60% (of this machine's {}), or none, got '{}'", what,
         format_bytes(available_memory_bytes()), text);
  };
  if (text == "none" || text == "0") return 0;
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return bad();
  }
  if (!(value > 0) || !std::isfinite(value)) return bad();
  std::string unit = text.substr(used);
  while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
  double scale = 0;
  if (unit.empty() || unit == "B") scale = 1;
  else if (unit == "%") scale = double(available_memory_bytes()) / 100;
  else if (unit == "K" || unit == "KiB" || unit == "KB") scale = 1024.0;
  else if (unit == "M" || unit == "MiB" || unit == "MB") scale = 1024.0 * 1024;
  else if (unit == "G" || unit == "GiB" || unit == "GB") scale = 1024.0 * 1024 * 1024;
  else if (unit == "T" || unit == "TiB" || unit == "TB") scale = 1024.0 * 1024 * 1024 * 1024;
  else return bad();
  if (unit == "%" && value > 100) return bad();
  return std::uint64_t(value * scale);
}

std::string format_bytes(std::uint64_t bytes) {
  const double b = double(bytes);
  if (b >= 1024.0 * 1024 * 1024) return fmt::format("{:.2f} GiB", b / (1024.0 * 1024 * 1024));
  if (b >= 1024.0 * 1024) return fmt::format("{:.1f} MiB", b / (1024.0 * 1024));
  return fmt::format("{:.0f} KiB", b / 1024.0);
}

}  // namespace ccdlab
