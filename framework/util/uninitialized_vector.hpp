#pragma once
// Vectors whose resize() does not value-initialize the new elements: for buffers that a kernel fills right
// after growing them (the narrow phase's batches, candidate lists, bounding volumes), where zero-filling or
// constructing first costs a pass over memory, on one thread. Large ones live in huge pages (memory.hpp).
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "framework/util/memory.hpp"

namespace ccdlab {

/// What `resize(n)` does to the new elements.
enum class Growth {
  default_init,   ///< default-initialize: nothing for trivial types, the default constructor otherwise
  unconstructed,  ///< nothing at all, even where a default constructor exists (trivially copyable types only)
};

template <class T, Growth G>
struct GrowthAllocator : std::allocator<T> {
  static_assert(G == Growth::default_init || (std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>));
  template <class U>
  struct rebind {
    using other = GrowthAllocator<U, G>;
  };
  GrowthAllocator() = default;
  template <class U>
  GrowthAllocator(const GrowthAllocator<U, G>&) noexcept {}

  /// `resize(n)` constructs with no arguments.
  template <class U>
  void construct(U* p) noexcept(G == Growth::unconstructed || std::is_nothrow_default_constructible_v<U>) {
    if constexpr (G == Growth::default_init) ::new (static_cast<void*>(p)) U;
  }
  /// Large arrays in huge pages (framework/util/memory.hpp).
  T* allocate(std::size_t n) {
    if (!is_large_allocation(n * sizeof(T))) return std::allocator<T>::allocate(n);
    return static_cast<T*>(allocate_large(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) {
    if (!is_large_allocation(n * sizeof(T))) return std::allocator<T>::deallocate(p, n);
    free_large(p);
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using UninitializedVector = std::vector<T, GrowthAllocator<T, Growth::default_init>>;

/// For arrays every element of which is assigned before it is read, where even default-initializing runs a
/// constructor (a k-DOP's writes an empty volume): the pages are first touched by the (parallel) pass that
/// fills them, not by one thread beforehand.
template <class T>
using UnconstructedVector = std::vector<T, GrowthAllocator<T, Growth::unconstructed>>;

}  // namespace ccdlab
