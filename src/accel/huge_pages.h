// An allocator for the BVH's two big arrays (Bvh::nodes, Bvh::blocks) that
// asks Linux for 2 MiB pages (transparent huge pages, madvise mode) once an
// array spans at least one. Incoherent rays read nodes and triangle blocks
// all over a structure of tens of MB; with 4 KiB pages nearly every such read
// also misses the TLB, and on a virtual machine each page walk is itself a
// chain of cache misses. Embree does the same for its own arrays (its
// "hugepages" option, on by default under Linux). Allocation happens at
// build time only, never per ray.
#pragma once

#include <cstddef>
#include <new>

#include "accel/unset_elements.h"

namespace sombra {

// 2 MiB: the x86-64 huge page. Arrays of at least this many bytes get
// memory aligned to it and advised MADV_HUGEPAGE; smaller ones come from
// operator new.
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

// `bytes` of memory aligned to `align` (a power of two, at most 4096), as
// above. Throws std::bad_alloc when none is to be had. Release with
// release_big_array(p, bytes, align), the same two numbers.
void* allocate_big_array(std::size_t bytes, std::size_t align);
void release_big_array(void* p, std::size_t bytes, std::size_t align) noexcept;

// Like std::allocator otherwise, new elements left unset (unset_elements.h):
// make_bvh writes every node and block.
template <class T>
struct HugePageAllocator : LeavesNewElementsUnset {
    using value_type = T;
    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) {
        if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T*>(allocate_big_array(n * sizeof(T), alignof(T)));
    }
    void deallocate(T* p, std::size_t n) noexcept { release_big_array(p, n * sizeof(T), alignof(T)); }
    friend bool operator==(const HugePageAllocator&, const HugePageAllocator&) { return true; }
};

}  // namespace sombra
