// Interval arithmetic must enclose the exact result of every operation (checked against GMP rationals),
// including cancellation, huge and tiny magnitudes, and products that underflow.
#include <gtest/gtest.h>

#include <gmp.h>

#include <random>

#include "framework/geometry/interval.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

struct Q {
  mpq_t v;
  Q() { mpq_init(v); }
  explicit Q(double d) { mpq_init(v); mpq_set_d(v, d); }
  ~Q() { mpq_clear(v); }
  Q(const Q&) = delete;
};

/// lo ≤ exact ≤ hi, in exact arithmetic.
bool encloses(const Interval& r, const Q& exact) {
  if (!(r.lo <= r.hi)) return false;
  Q lo(r.lo), hi(r.hi);
  return mpq_cmp(lo.v, exact.v) <= 0 && mpq_cmp(exact.v, hi.v) <= 0;
}

TEST(Interval, EveryOperationEnclosesTheExactResult) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> mant(-1, 1);
  std::uniform_int_distribution<int> expo(-1070, 60);
  for (int k = 0; k < 20000; ++k) {
    // Mix ordinary, tiny (subnormal-range) and nearly cancelling operands.
    const double a = std::ldexp(mant(rng), k % 3 == 0 ? expo(rng) : int(mant(rng) * 20));
    double b = std::ldexp(mant(rng), k % 3 == 1 ? expo(rng) : int(mant(rng) * 20));
    if (k % 7 == 0) b = -std::nextafter(a, 0.0);
    const Interval A(a), B(b);
    Q qa(a), qb(b), r;
    mpq_add(r.v, qa.v, qb.v);
    ASSERT_TRUE(encloses(A + B, r)) << a << " + " << b;
    mpq_sub(r.v, qa.v, qb.v);
    ASSERT_TRUE(encloses(A - B, r)) << a << " - " << b;
    mpq_mul(r.v, qa.v, qb.v);
    ASSERT_TRUE(encloses(A * B, r)) << a << " * " << b;
    // Wide operands: the product of intervals covers every product of their members.
    const Interval W = A + B, V = A - B;
    Q wl(W.lo), vh(V.hi);
    mpq_mul(r.v, wl.v, vh.v);
    ASSERT_TRUE(encloses(W * V, r));
  }
}

TEST(Interval, ExactZerosStayZeroAndUnderflowIsCovered) {
  const Interval z = Interval(0.0) * Interval(3.5);
  EXPECT_EQ(z.lo, 0.0);
  EXPECT_EQ(z.hi, 0.0);
  const Interval tiny = Interval(1e-200) * Interval(1e-200);  // rounds to 0, exact value is 1e-400 > 0
  EXPECT_LE(tiny.lo, 0.0);
  EXPECT_GT(tiny.hi, 0.0);
}

TEST(Interval, CertaintyIsFalseOnNaN) {
  const double inf = std::numeric_limits<double>::infinity();
  const Interval nan = Interval(inf) - Interval(inf);
  EXPECT_FALSE(nan.certainly_positive());
  EXPECT_FALSE(nan.certainly_negative());
}

}  // namespace
}  // namespace ccdlab
