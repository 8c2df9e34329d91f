#include "accel/huge_pages.h"

#include <sys/mman.h>

#include <cstdint>

namespace sombra {
namespace {

std::size_t round_up(std::size_t bytes) { return (bytes + kHugePageBytes - 1) & ~(kHugePageBytes - 1); }

}  // namespace

void* allocate_big_array(std::size_t bytes, std::size_t align) {
    if (bytes < kHugePageBytes) return ::operator new (bytes, std::align_val_t{align});
    // Map one huge page more than needed and trim both ends, so that what is
    // left starts on a 2 MiB boundary: only whole, aligned 2 MiB ranges can
    // be backed by huge pages.
    const std::size_t size = round_up(bytes);
    if (size < bytes || size + kHugePageBytes < size) throw std::bad_alloc();
    void* mapped = mmap(nullptr, size + kHugePageBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapped == MAP_FAILED) throw std::bad_alloc();
    // The pointers are offsets from `mapped` (not integers cast back), so
    // they keep its provenance.
    const auto start = reinterpret_cast<std::uintptr_t>(mapped);
    const std::size_t lead = round_up(start) - start;  // bytes before the first 2 MiB boundary
    char* const p = static_cast<char*>(mapped) + lead;
    if (lead > 0) munmap(mapped, lead);
    const std::size_t tail = kHugePageBytes - lead;  // what is left after size bytes from p
    if (tail > 0) munmap(p + size, tail);
#ifdef MADV_HUGEPAGE
    madvise(p, size, MADV_HUGEPAGE);  // a hint: without huge pages the array still works
#endif
    return p;
}

void release_big_array(void* p, std::size_t bytes, std::size_t align) noexcept {
    if (p == nullptr) return;
    if (bytes < kHugePageBytes) {
        ::operator delete (p, std::align_val_t{align});
        return;
    }
    munmap(p, round_up(bytes));
}

}  // namespace sombra
