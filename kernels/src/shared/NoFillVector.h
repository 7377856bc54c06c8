// A std::vector whose resize() leaves trivially constructible elements unwritten.
#pragma once

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace linkgi
{
/// std::allocator, except that constructing an element without a value default-initialises
/// it (nothing, for numbers) instead of value-initialising it (zero). A large buffer that
/// is written in full right after resize() then costs no fill pass, and its pages first
/// become resident in the threads that write them, not in one thread's zero fill.
template <typename T>
struct NoFillAllocator : std::allocator<T>
{
  template <typename U>
  struct rebind
  {
    using other = NoFillAllocator<U>;
  };
  NoFillAllocator() = default;
  template <typename U>
  NoFillAllocator(const NoFillAllocator<U>&) noexcept
  {
  }
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <typename T>
using NoFillVector = std::vector<T, NoFillAllocator<T>>;
}
