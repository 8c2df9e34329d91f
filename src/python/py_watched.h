// Long work from Python (a render, a denoise): run on a thread of its own
// with the GIL released, while the caller's thread, holding the GIL only
// briefly, watches for Ctrl-C and reports progress.
#pragma once

#include <pybind11/pybind11.h>

#include <chrono>
#include <cstdint>
#include <future>
#include <utility>

#include "render/render.h"

namespace sombra::python {

// How often the waiting thread looks for Ctrl-C: well within the second
// spec §19 allows, and rare enough to cost nothing.
inline constexpr std::chrono::milliseconds kPollInterval{50};

// Runs `work` on its own thread with the GIL released; every kPollInterval
// takes the GIL to check for signals and call `progress` (unless None) with
// (watched.samples_done, total). A KeyboardInterrupt (or an exception from
// `progress`) sets watched.cancel, waits for the work to stop, and
// propagates; so does the work's own exception.
template <class Work>
void run_watched(Work&& work, RenderProgress& watched, std::uint64_t total, const pybind11::object& progress) {
    bool python_error = false;
    std::future<void> done;
    {
        pybind11::gil_scoped_release release;
        done = std::async(std::launch::async, std::forward<Work>(work));
        while (done.wait_for(kPollInterval) != std::future_status::ready) {
            const pybind11::gil_scoped_acquire gil;
            if (PyErr_CheckSignals() != 0) {
                python_error = true;  // the error stays set in this thread until raised below
            } else if (!progress.is_none()) {
                try {
                    progress(watched.samples_done.load(), total);
                } catch (pybind11::error_already_set& e) {
                    e.restore();
                    python_error = true;
                }
            }
            if (python_error) {
                watched.cancel = true;
                break;
            }
        }
        done.wait();
    }
    if (python_error) throw pybind11::error_already_set();
    done.get();  // the work's own exception, if any
    // The last word: a bar ends where the work did, not at its last poll.
    if (!progress.is_none()) progress(watched.samples_done.load(), total);
}

}  // namespace sombra::python
