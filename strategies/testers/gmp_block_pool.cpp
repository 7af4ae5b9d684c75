#include "strategies/testers/gmp_block_pool.hpp"

#include <gmp.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <utility>

// GMP's own allocator: exported by libgmp, declared only in its internal header (gmp-impl.h). The pool replaces
// it and nothing else: blocks of an allocator someone else installed need not be malloc's.
extern "C" {
void* __gmp_default_allocate(std::size_t);
void* __gmp_default_reallocate(void*, std::size_t, std::size_t);
void __gmp_default_free(void*, std::size_t);
}

namespace ccdlab {
namespace {

// Recycled: blocks of 1 … kLimbs limbs (GMP sizes its integers in whole limbs); other sizes go to malloc.
constexpr std::size_t kLimbBytes = sizeof(mp_limb_t);
constexpr std::size_t kLimbs = 32;
constexpr std::uint32_t kMaxPerList = 512;  // at most 512 · (1 + … + 32) limbs = 2.1 MiB held per thread

struct FreeBlock {
  FreeBlock* next;
};

// Trivially destructible, so it can be read until the thread is gone; `Drain` below empties it at thread exit.
struct Lists {
  std::array<FreeBlock*, kLimbs + 1> head;
  std::array<std::uint32_t, kLimbs + 1> count;
  bool draining;   // the thread is ending: blocks go straight to free
  bool will_drain;  // Drain is registered for this thread
};
thread_local Lists lists{};

struct Drain {
  ~Drain() {
    lists.draining = true;
    for (FreeBlock*& h : lists.head)
      while (h != nullptr) std::free(std::exchange(h, h->next));
  }
};
thread_local Drain drain;

/// The list for a block of `bytes`, or 0 when blocks of that size are not recycled.
std::size_t list_of(std::size_t bytes) {
  return bytes % kLimbBytes == 0 && bytes <= kLimbs * kLimbBytes ? bytes / kLimbBytes : 0;
}

/// GMP cannot unwind from a failed allocation (it is C): like its own allocator, say so and abort.
void* checked(void* p) {
  if (p == nullptr) {
    std::fputs("ccdlab: out of memory in GMP (exact arithmetic)\n", stderr);
    std::abort();
  }
  return p;
}

void* allocate(std::size_t bytes) {
  if (const std::size_t i = list_of(bytes); i != 0 && lists.head[i] != nullptr) {
    FreeBlock* b = lists.head[i];
    lists.head[i] = b->next;
    --lists.count[i];
    return b;
  }
  return checked(std::malloc(bytes));
}

void release(void* p, std::size_t bytes) {
  const std::size_t i = list_of(bytes);
  if (i == 0 || lists.draining || lists.count[i] == kMaxPerList) return std::free(p);
  if (!lists.will_drain) {
    lists.will_drain = true;
    (void)&drain;  // first use on this thread: registers its destructor
  }
  auto* b = static_cast<FreeBlock*>(p);
  b->next = lists.head[i];
  lists.head[i] = b;
  ++lists.count[i];
}

void* reallocate(void* p, std::size_t old_bytes, std::size_t new_bytes) {
  if (list_of(old_bytes) == 0 && list_of(new_bytes) == 0) return checked(std::realloc(p, new_bytes));
  void* q = allocate(new_bytes);
  std::memcpy(q, p, old_bytes < new_bytes ? old_bytes : new_bytes);
  release(p, old_bytes);
  return q;
}

}  // namespace

bool recycle_gmp_blocks() {
  static std::once_flag once;
  std::call_once(once, [] {
    void* (*a)(std::size_t) = nullptr;
    void* (*r)(void*, std::size_t, std::size_t) = nullptr;
    void (*f)(void*, std::size_t) = nullptr;
    mp_get_memory_functions(&a, &r, &f);
    if (a == __gmp_default_allocate && r == __gmp_default_reallocate && f == __gmp_default_free)
      mp_set_memory_functions(allocate, reallocate, release);
  });
  void* (*a)(std::size_t) = nullptr;
  mp_get_memory_functions(&a, nullptr, nullptr);
  return a == allocate;
}

}  // namespace ccdlab
