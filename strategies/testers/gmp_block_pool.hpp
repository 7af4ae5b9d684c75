#pragma once
// GMP's limb blocks recycled per thread. The exact tester builds and drops many small integers per query (the
// coefficients of a query's polynomials, the algebraic kernel's temporaries); through malloc and free that
// costs about as much as the arithmetic. The pool keeps freed blocks on per-thread lists, one list per
// block size, and hands them back for a request of exactly that size.
//
// Contract: every block it hands out is a genuine malloc block of at least the requested size (a recycled block
// was malloc'd, or handed to GMP's free, with exactly that size), so a block may cross between the pool and
// plain malloc/free in either direction: installing it while GMP numbers already exist, a block freed on
// another thread, or code that frees GMP memory with std::free all stay correct. Each list is capped; a thread's
// lists are freed when it ends, and a block freed after that goes straight to free.
namespace ccdlab {

/// Installs the pool as GMP's allocator (mp_set_memory_functions), once per process, where GMP still has its
/// own (a process in which another library installed one keeps it). Call it while no other thread is inside GMP
/// (the exact tester does so when it is constructed, before any step runs). Whether the pool is GMP's allocator.
bool recycle_gmp_blocks();

}  // namespace ccdlab
