// All-or-nothing file replacement: the bytes go to a temporary file in the
// target's folder (same file system, so the final rename is atomic), and only
// a complete file is renamed over the target.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace sombra {

// Calls `fill(temp)` to write the whole file at `temp`, a fresh, empty file
// ".NAME.tmp-<pid>-<n>" beside `target`, then renames it over `target`.
// `fill` reports failure by throwing. On any failure the temporary file is
// removed, `target` keeps its earlier content, and
// Error(target, "cannot write: <reason>") is thrown.
void write_file_atomically(const std::filesystem::path& target,
                           const std::function<void(const std::filesystem::path& temp)>& fill);

// The OS's message for an errno value, starting lower-case ("no such file or directory").
std::string errno_message(int error_number);

}  // namespace sombra
