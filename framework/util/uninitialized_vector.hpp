#pragma once
// A std::vector whose resize() leaves new elements of trivial types uninitialized: for buffers that a kernel
// fills right after growing them (the narrow phase's batches), where zero-filling first costs a pass over memory.
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace ccdlab {

template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  /// `resize(n)` constructs with no arguments: default-initialize (no-op for trivial T) instead of zeroing.
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using UninitializedVector = std::vector<T, DefaultInitAllocator<T>>;

/// For arrays of trivially copyable values every element of which is assigned before it is read, where even
/// default-initializing runs a constructor (a k-DOP's writes an empty volume): `resize(n)` constructs nothing,
/// so the pages are first touched by the (parallel) pass that fills them, not by one thread beforehand.
template <class T>
struct UnconstructedAllocator : std::allocator<T> {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);
  template <class U>
  struct rebind {
    using other = UnconstructedAllocator<U>;
  };
  UnconstructedAllocator() = default;
  template <class U>
  UnconstructedAllocator(const UnconstructedAllocator<U>&) noexcept {}

  template <class U>
  void construct(U*) noexcept {}  // resize(n): the caller assigns every new element
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

}  // namespace ccdlab
