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

}  // namespace ccdlab
