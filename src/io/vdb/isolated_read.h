// Runs a DensityGrid reader in a child process (fork), so that what a
// hostile file does to the library behind it stays there: a crash, an
// allocation the file claims (the child's heap is limited), a leak, a hang
// (the parent waits a bounded time). The parent receives the grid through
// a pipe, checks its size before it allocates, and turns any failure into
// one sombra::Error naming the file.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "scene/density_grid.h"

namespace sombra {

// `read` in a child process; `name` names the file in errors, `file_bytes`
// sizes the child's memory limit and the time allowed. The result has no
// majorants (the parent builds them). Where fork is impossible, `read` runs
// here.
DensityGrid read_isolated(const std::string& name, std::uintmax_t file_bytes, const std::function<DensityGrid()>& read);

}  // namespace sombra
