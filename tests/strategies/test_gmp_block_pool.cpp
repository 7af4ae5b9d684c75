// GMP's block pool (gmp_block_pool.hpp): recycled blocks never alias a live number, blocks cross threads and
// plain malloc/free in both directions, and a thread's lists are freed when it ends (the sanitizer build's leak
// check sees a block left behind).
#include <gmp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "strategies/testers/gmp_block_pool.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

/// 3ⁿ by repeated multiplication, as a decimal string: every step allocates, grows and frees limbs.
std::string power_of_three(unsigned n) {
  mpz_t x, y;
  mpz_init_set_ui(x, 1);
  mpz_init(y);
  for (unsigned i = 0; i < n; ++i) {
    mpz_mul_ui(y, x, 3);
    mpz_swap(x, y);
  }
  char* s = mpz_get_str(nullptr, 10, x);
  std::string out(s);
  std::free(s);  // GMP's string freed with plain free: the pool's blocks are malloc's
  mpz_clear(x);
  mpz_clear(y);
  return out;
}

/// 3ⁿ in one call (GMP's own power), the reference.
std::string power_of_three_direct(unsigned n) {
  mpz_t x;
  mpz_init(x);
  mpz_ui_pow_ui(x, 3, n);
  std::string out(mpz_sizeinbase(x, 10) + 2, '\0');
  mpz_get_str(out.data(), 10, x);
  out.resize(std::strlen(out.c_str()));
  mpz_clear(x);
  return out;
}

TEST(GmpBlockPool, RecycledBlocksKeepEveryNumberIntactAcrossThreads) {
  ASSERT_TRUE(recycle_gmp_blocks()) << "GMP's own allocator was not recognised: the pool is not installed";
  ASSERT_TRUE(recycle_gmp_blocks());  // once per process: the second call changes nothing
  // Numbers made on one thread and freed on another, while both threads keep computing.
  std::vector<__mpz_struct> made(64);
  for (std::size_t i = 0; i < made.size(); ++i) {
    mpz_init(&made[i]);
    mpz_ui_pow_ui(&made[i], 7, 50 + 37 * i);  // 3 … 35 limbs
  }
  std::vector<std::string> results(4);
  std::vector<std::thread> threads;
  for (unsigned t = 0; t < results.size(); ++t)
    threads.emplace_back([&, t] {
      std::string all;
      for (unsigned n = 1; n < 1200; n += 7 + t) all += power_of_three(n) + ",";
      if (t == 0)
        for (auto& m : made) mpz_clear(&m);
      results[t] = all;
    });
  for (auto& th : threads) th.join();
  for (unsigned t = 0; t < results.size(); ++t) {
    std::string expected;
    for (unsigned n = 1; n < 1200; n += 7 + t) expected += power_of_three_direct(n) + ",";
    EXPECT_EQ(results[t], expected) << "thread " << t;
  }
}

TEST(GmpBlockPool, BlocksMoveBetweenThePoolAndMallocBothWays) {
  ASSERT_TRUE(recycle_gmp_blocks());
  void* (*allocate)(std::size_t) = nullptr;
  void* (*reallocate)(void*, std::size_t, std::size_t) = nullptr;
  void (*release)(void*, std::size_t) = nullptr;
  mp_get_memory_functions(&allocate, &reallocate, &release);
  // A malloc'd block handed to GMP's free, then served for a request of the same size and freed by plain free.
  for (int round = 0; round < 3; ++round) {
    std::vector<void*> blocks;
    for (int i = 0; i < 100; ++i) blocks.push_back(std::malloc(24));
    for (void* b : blocks) release(b, 24);
    blocks.clear();
    for (int i = 0; i < 100; ++i) {
      auto* b = static_cast<unsigned char*>(allocate(24));
      std::memset(b, 0xab, 24);  // the whole requested size is writable (the sanitizer build checks)
      blocks.push_back(b);
    }
    for (void* b : blocks) std::free(b);
  }
  // Growing and shrinking keeps the contents, inside and outside the recycled sizes.
  const std::size_t sizes[] = {16, 64, 4096, 8192, 40, 8};
  auto* p = static_cast<unsigned char*>(allocate(sizes[0]));
  for (int i = 0; i < 16; ++i) p[i] = static_cast<unsigned char>(i);
  for (std::size_t k = 1; k < std::size(sizes); ++k) {
    p = static_cast<unsigned char*>(reallocate(p, sizes[k - 1], sizes[k]));
    for (std::size_t i = 0; i < std::min<std::size_t>(sizes[k], 16); ++i) ASSERT_EQ(p[i], i) << "resized to " << sizes[k];
  }
  release(p, sizes[std::size(sizes) - 1]);
}

}  // namespace
}  // namespace ccdlab
