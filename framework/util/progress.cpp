#include "framework/util/progress.hpp"

#include <cstdio>

#include <unistd.h>

namespace ccdlab {

Progress::Progress(std::string label, long total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled && stderr_is_terminal()), start_(std::chrono::steady_clock::now()), last_(start_) {}

Progress::~Progress() {
  if (enabled_) std::fprintf(stderr, "\r\033[K");
}

bool Progress::stderr_is_terminal() { return isatty(STDERR_FILENO) != 0; }

void Progress::update(long done) {
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  if (done < total_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  double elapsed = std::chrono::duration<double>(now - start_).count();
  double eta = done > 0 ? elapsed * double(total_ - done) / double(done) : 0.0;
  std::fprintf(stderr, "\r\033[K%s %ld/%ld (%.0f%%) %.1fs elapsed, ~%.1fs left", label_.c_str(), done, total_,
               total_ > 0 ? 100.0 * double(done) / double(total_) : 100.0, elapsed, eta);
  std::fflush(stderr);
}

}  // namespace ccdlab
