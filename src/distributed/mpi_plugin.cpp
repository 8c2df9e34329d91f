// libsombra_mpi.so: the MPI calls of mpi_plugin.h over Open MPI's C API.
#include "distributed/mpi_plugin.h"

#include <mpi.h>

#include <cstdlib>

namespace {

void init(int* rank, int* size) {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, rank);
    MPI_Comm_size(MPI_COMM_WORLD, size);
}

void finalize() { MPI_Finalize(); }

[[noreturn]] void abort_all(int status) {
    MPI_Abort(MPI_COMM_WORLD, status);
    std::_Exit(status);  // not reached: MPI_Abort does not return
}

void send_floats(const float* values, int count, int to, int tag) {
    MPI_Send(values, count, MPI_FLOAT, to, tag, MPI_COMM_WORLD);
}

void send_int(int value, int to, int tag) { MPI_Send(&value, 1, MPI_INT, to, tag, MPI_COMM_WORLD); }

int receive_int(int from, int tag) {
    int value = 0;
    MPI_Recv(&value, 1, MPI_INT, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return value;
}

bool probe(int* from, int* tag, int* float_count) {
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
    if (!arrived) return false;
    MPI_Get_count(&status, MPI_FLOAT, float_count);
    *from = status.MPI_SOURCE;
    *tag = status.MPI_TAG;
    return true;
}

void receive_floats(float* values, int count, int from, int tag) {
    MPI_Recv(values, count, MPI_FLOAT, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
}

void sum_on_rank0(const std::uint64_t* mine, std::uint64_t* total, int count) {
    MPI_Reduce(mine, total, count, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
}

const SombraMpiApi kApi{sombra::kSombraMpiAbi, init,  finalize,       abort_all,   send_floats, send_int,
                        receive_int,           probe, receive_floats, sum_on_rank0};

}  // namespace

extern "C" __attribute__((visibility("default"))) const SombraMpiApi* sombra_mpi_api() { return &kApi; }
