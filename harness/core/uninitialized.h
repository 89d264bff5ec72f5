#pragma once
// A vector whose new elements are left unwritten (default-, not value-initialised) for buffers
// that the cores then write whole in parallel: each page is first touched by the core that
// fills it, rather than all of them zeroed by one core beforehand. On the project's 2-core
// machines a fresh 4 KB page costs about 2.7 us to touch (results/precompute-times/README.md).
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace rl {

template <typename T>
struct DefaultInitAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  template <typename U>
  void construct(U* p) {
    ::new (static_cast<void*>(p)) U;  // no value: left as the memory was
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// Elements appended by resize() hold no value until written.
template <typename T>
using UninitializedVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace rl
