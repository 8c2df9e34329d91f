// `mpirun -np K sombra render` (spec §21): every rank loads the scene and
// builds its structure; rank 0 hands out the image's 32 × 32 blocks one at a
// time (dynamic load balancing), renders blocks itself between, and writes
// the image once every block has arrived. Without a launcher (or built
// without MPI) nothing here calls MPI: MPI_Init alone costs ~0.3 s.
#pragma once

#include <optional>
#include <string>

#include "render/render.h"

struct SombraMpiApi;  // distributed/mpi_plugin.h

namespace sombra {

// This process's rank and the number of ranks, as the launcher's environment
// says (Open MPI's OMPI_COMM_WORLD_*, MPICH/Hydra's PMI_*): {0, 1} without one.
struct LaunchedRanks {
    int rank = 0;
    int size = 1;
};
LaunchedRanks launched_ranks();

// Whether this sombra can run as several MPI ranks: its MPI plugin
// (libsombra_mpi.so, mpi_plugin.h) is there and loads; if not, why not.
bool mpi_available(std::string* why_not = nullptr);

// MPI for one `sombra render`: initialised only when launched as one of
// several ranks, finalised at the end.
class MpiRun {
public:
    MpiRun();
    ~MpiRun();
    MpiRun(const MpiRun&) = delete;
    MpiRun& operator=(const MpiRun&) = delete;

    bool active() const { return mpi_ != nullptr && size_ > 1; }
    int rank() const { return rank_; }
    int size() const { return size_; }

    // Ends every rank with `status` (MPI_Abort), so that no rank writes an
    // image after another failed.
    [[noreturn]] void abort(int status) const;

    // The worker threads a rank uses for --threads `asked` (0 = all): the
    // machine's threads shared among the ranks on it.
    int threads_per_rank(int asked) const;

    // Renders the still `job` over all ranks. On rank 0: the whole image, its
    // AOVs, and counters summed over the ranks; on the others: only their
    // own counters. `cancelled` as render_image's.
    RenderOutput render(RenderJob job, RenderProgress& progress) const;

    // Each rank's counters summed on rank 0 (the others get their own back).
    RayCounters sum(const RayCounters& mine) const;

private:
    const SombraMpiApi* mpi_ = nullptr;  // the plugin's calls, under a launcher
    int rank_ = 0;
    int size_ = 1;
};

}  // namespace sombra
