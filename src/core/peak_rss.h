// The process's memory high-water mark, for the run statistics and the benchmarks.
#pragma once

#include <sys/resource.h>

#include <cstdint>

namespace sombra {

// The process's peak resident set size so far, in bytes.
inline std::uint64_t peak_rss_bytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u;  // Linux reports KiB
}

}  // namespace sombra
