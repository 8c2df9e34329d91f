// An allocator base for the build's big arrays: resize() and emplace_back()
// with no value leave new elements unset instead of zeroed. The element
// types are aggregates of floats and integers (implicit-lifetime types, so
// the memory holds them without a constructor call), and every element read
// is written first. Zeroing them would make one thread fault in every page,
// gigabytes at 100 M triangles, before the parallel pass that fills them.
// Internal to src/accel.
#pragma once

#include <new>
#include <utility>

namespace sombra {

struct LeavesNewElementsUnset {
    template <class U>
    void construct(U*) noexcept {}
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

}  // namespace sombra
