// The process's memory high-water mark, for the run statistics and the benchmarks.
#pragma once

#include <sys/resource.h>

#include <cstdint>
#include <fstream>
#include <string>

namespace sombra {

// The process's peak resident set size so far, in bytes.
inline std::uint64_t peak_rss_bytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u;  // Linux reports KiB
}

// Starts a new high-water mark for peak_rss_since_reset_bytes(), so that one
// process can measure the peak of each of its phases (load, each build) in
// turn: Linux resets VmHWM to the current resident size when "5" is written
// to /proc/self/clear_refs (getrusage's peak is not reset). False where that
// file cannot be written.
inline bool reset_peak_rss() {
    std::ofstream clear_refs("/proc/self/clear_refs");
    clear_refs << "5";
    clear_refs.flush();
    return static_cast<bool>(clear_refs);
}

// The peak resident set size in bytes since the last reset_peak_rss() (or
// since the process started): VmHWM of /proc/self/status. 0 when unreadable.
inline std::uint64_t peak_rss_since_reset_bytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024u;  // "VmHWM:  1234 kB"
    }
    return 0;
}

}  // namespace sombra
