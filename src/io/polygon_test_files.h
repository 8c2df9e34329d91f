// Test helpers for the OBJ and PLY loader tests: a temporary folder that
// cleans up after itself, and where the shared test data lives.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "core/vec3.h"

namespace sombra::testing {

// A fresh folder under the system's temporary folder, removed with its contents.
struct TempFolder {
    std::filesystem::path path;

    TempFolder() {
        static std::atomic<int> counter{0};
        const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
        path = std::filesystem::temp_directory_path() / ("sombra-loader-test-" + std::to_string(::getpid()) + "-" +
                                                         std::to_string(stamp) + "-" + std::to_string(counter++));
        std::filesystem::create_directories(path);
    }
    ~TempFolder() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;

    // Writes `bytes` to NAME in the folder and returns its path.
    std::filesystem::path write(const std::string& name, std::string_view bytes) const {
        std::filesystem::path file = path / name;
        std::ofstream out(file, std::ios::binary);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        return file;
    }
};

inline std::filesystem::path shared_dir() { return SOMBRA_SHARED_DIR; }

// Twice the signed area of triangle (a, b, c) projected along `normal`.
inline float twice_area_along(Vec3 a, Vec3 b, Vec3 c, Vec3 normal) { return dot(cross(b - a, c - a), normal); }

}  // namespace sombra::testing

// Skips the test when shared/ (models, objsuite) is absent.
#define SOMBRA_REQUIRE_SHARED(subfolder)                                                              \
    do {                                                                                              \
        if (!std::filesystem::exists(::sombra::testing::shared_dir() / (subfolder))) {                \
            GTEST_SKIP() << "shared/ not found at " << ::sombra::testing::shared_dir() / (subfolder); \
        }                                                                                             \
    } while (0)
