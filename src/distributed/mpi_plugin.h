// The MPI calls `mpirun -np K sombra render` makes (mpi_render.cpp), in a
// plugin of their own (mpi_plugin.cpp → libsombra_mpi.so) that sombra opens
// only under a launcher: the executable links no MPI library, so the .deb
// needs no Open MPI, and the sombra-mpi package adds it (docs/install.md).
// Plain C types only: the table is the plugin's whole interface.
#pragma once

#include <cstdint>

extern "C" {

struct SombraMpiApi {
    int abi;  // kSombraMpiAbi: a plugin of another sombra is refused
    // MPI_Init_thread (funneled: only the calling thread uses MPI), then
    // this process's rank and the number of ranks.
    void (*init)(int* rank, int* size);
    void (*finalize)();
    void (*abort)(int status);  // every rank ends with `status`; does not return
    void (*send_floats)(const float* values, int count, int to, int tag);
    void (*send_int)(int value, int to, int tag);
    int (*receive_int)(int from, int tag);
    // Whether a message from any rank waits (without receiving it): its
    // sender, tag and size in floats.
    bool (*probe)(int* from, int* tag, int* float_count);
    void (*receive_floats)(float* values, int count, int from, int tag);
    // Σ over the ranks of `count` values, element by element, on rank 0.
    void (*sum_on_rank0)(const std::uint64_t* mine, std::uint64_t* total, int count);
};

// The plugin's one exported function.
const SombraMpiApi* sombra_mpi_api();
using SombraMpiApiEntry = const SombraMpiApi* (*)();
}

namespace sombra {
inline constexpr int kSombraMpiAbi = 1;
inline constexpr const char* kSombraMpiEntry = "sombra_mpi_api";
}  // namespace sombra
