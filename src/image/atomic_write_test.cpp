// All-or-nothing writes and the early output-path check: whatever fails, the
// earlier file stays byte for byte and no temporary file is left behind.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"
#include "image/image_io.h"
#include "image/test_folder.h"

namespace sombra {
namespace {

namespace fs = std::filesystem;
using test::read_bytes;
using test::write_bytes;

using AtomicWriteTest = test::TestFolder;
using CheckOutputPathTest = test::TestFolder;

const std::string old_content = "the earlier, good image";

// Noise, so that no format can compress it below a few kilobytes.
std::vector<float> noise(int width, int height) {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    std::vector<float> rgb(static_cast<std::size_t>(width * height * 3));
    for (float& v : rgb) v = uniform(random);
    return rgb;
}

// Makes every write past `bytes` in any file fail (EFBIG): a full disk, even for root.
class FileSizeLimit {
public:
    explicit FileSizeLimit(rlim_t bytes) {
        ::getrlimit(RLIMIT_FSIZE, &saved_);
        saved_handler_ = std::signal(SIGXFSZ, SIG_IGN);
        rlimit limit = saved_;
        limit.rlim_cur = bytes;
        ::setrlimit(RLIMIT_FSIZE, &limit);
    }
    ~FileSizeLimit() {
        ::setrlimit(RLIMIT_FSIZE, &saved_);
        std::signal(SIGXFSZ, saved_handler_);
    }
    FileSizeLimit(const FileSizeLimit&) = delete;
    FileSizeLimit& operator=(const FileSizeLimit&) = delete;

private:
    rlimit saved_{};
    void (*saved_handler_)(int) = SIG_DFL;
};

// The message of the Error that `write` throws, after checking it names `path`.
template <class Write>
std::string error_of(const fs::path& path, Write write) {
    try {
        write();
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), path.string());
        return e.message();
    }
    ADD_FAILURE() << "no error for " << path;
    return {};
}

TEST_F(AtomicWriteTest, ReplacesAnExistingFileAndLeavesNoTemporaryFile) {
    for (const char* name : {"a.png", "a.pfm", "a.exr"}) {
        write_bytes(folder_ / name, old_content);
        const std::vector<float> rgb = noise(8, 4);
        write_image(folder_ / name, {8, 4, rgb.data()}, {});
        EXPECT_GT(read_bytes(folder_ / name).size(), 8u * 4u * 3u) << name;
    }
    EXPECT_EQ(entries(), (std::set<std::string>{"a.png", "a.pfm", "a.exr"}));
}

TEST_F(AtomicWriteTest, FailureToWriteMidwayKeepsTheEarlierFile) {
    const std::vector<float> rgb = noise(64, 64);  // at least 12 KB in every format
    for (const char* name : {"a.png", "a.pfm", "a.exr"}) {
        write_bytes(folder_ / name, old_content);
        std::string message;
        {
            const FileSizeLimit limit(4096);
            message = error_of(folder_ / name, [&] { write_image(folder_ / name, {64, 64, rgb.data()}, {}); });
        }
        EXPECT_EQ(message.rfind("cannot write: ", 0), 0u) << message;
        EXPECT_EQ(read_bytes(folder_ / name), std::vector<unsigned char>(old_content.begin(), old_content.end()));
    }
    EXPECT_EQ(entries(), (std::set<std::string>{"a.png", "a.pfm", "a.exr"}));
}

TEST_F(AtomicWriteTest, MissingFolderFailsAndCreatesNothing) {
    const std::vector<float> rgb = noise(2, 2);
    const fs::path path = folder_ / "missing" / "a.png";
    const std::string message = error_of(path, [&] { write_image(path, {2, 2, rgb.data()}, {}); });
    EXPECT_EQ(message.rfind("cannot write: ", 0), 0u) << message;
    EXPECT_NE(message.find("no such file or directory"), std::string::npos) << message;
    EXPECT_TRUE(entries().empty());
}

TEST_F(AtomicWriteTest, FolderInTheTargetsPlaceIsLeftAlone) {
    fs::create_directory(folder_ / "a.pfm");
    write_bytes(folder_ / "a.pfm" / "inside.txt", old_content);
    const std::vector<float> rgb = noise(2, 2);
    const std::string message = error_of(folder_ / "a.pfm", [&] {
        write_image(folder_ / "a.pfm", {2, 2, rgb.data()}, {});
    });
    EXPECT_EQ(message.rfind("cannot write: ", 0), 0u) << message;
    EXPECT_EQ(read_bytes(folder_ / "a.pfm" / "inside.txt"),
              std::vector<unsigned char>(old_content.begin(), old_content.end()));
    EXPECT_EQ(entries(), (std::set<std::string>{"a.pfm"}));
}

TEST_F(AtomicWriteTest, ReadOnlyFolderFailsAndKeepsTheEarlierFile) {
    if (::geteuid() == 0) GTEST_SKIP() << "root ignores folder permissions (FailureToWriteMidway covers this)";
    write_bytes(folder_ / "a.png", old_content);
    ::chmod(folder_.c_str(), 0555);
    const std::vector<float> rgb = noise(2, 2);
    const std::string message = error_of(folder_ / "a.png", [&] {
        write_image(folder_ / "a.png", {2, 2, rgb.data()}, {});
    });
    ::chmod(folder_.c_str(), 0755);
    EXPECT_EQ(message.rfind("cannot write: ", 0), 0u) << message;
    EXPECT_EQ(read_bytes(folder_ / "a.png"), std::vector<unsigned char>(old_content.begin(), old_content.end()));
    EXPECT_EQ(entries(), (std::set<std::string>{"a.png"}));
}

TEST_F(AtomicWriteTest, LongestFileNamesStillGetATemporaryFile) {
    const std::string name = std::string(251, 'n') + ".pfm";  // 255 bytes, the most a name may have
    const std::vector<float> rgb = {1, 2, 3};
    write_image(folder_ / name, {1, 1, rgb.data()}, {});
    EXPECT_EQ(read_bytes(folder_ / name).size(), 12u + 12u);
    EXPECT_EQ(entries(), (std::set<std::string>{name}));
}

TEST_F(AtomicWriteTest, ConcurrentWritersLeaveOneCompleteFile) {
    // Each thread writes a constant image of its own value; the survivor must be whole.
    constexpr int writers = 4;
    std::vector<std::thread> threads;
    for (int w = 0; w < writers; ++w) {
        threads.emplace_back([&, w] {
            const std::vector<float> rgb(16 * 16 * 3, static_cast<float>(w + 1));
            for (int round = 0; round < 10; ++round) write_image(folder_ / "a.pfm", {16, 16, rgb.data()}, {});
        });
    }
    for (std::thread& thread : threads) thread.join();
    const std::vector<unsigned char> bytes = read_bytes(folder_ / "a.pfm");
    ASSERT_EQ(bytes.size(), 14u + 16u * 16u * 12u);
    const std::vector<unsigned char> first_value(bytes.begin() + 14, bytes.begin() + 18);
    for (std::size_t at = 14; at < bytes.size(); at += 4)
        ASSERT_TRUE(std::equal(first_value.begin(), first_value.end(), bytes.begin() + static_cast<long>(at)));
    EXPECT_EQ(entries(), (std::set<std::string>{"a.pfm"}));
}

TEST_F(AtomicWriteTest, WritingThroughASymbolicLinkUpdatesTheLinkedFile) {
    write_bytes(folder_ / "real.pfm", old_content);
    fs::create_symlink("real.pfm", folder_ / "link.pfm");
    const std::vector<float> rgb = {1, 2, 3};
    write_image(folder_ / "link.pfm", {1, 1, rgb.data()}, {});
    EXPECT_TRUE(fs::is_symlink(folder_ / "link.pfm"));
    EXPECT_EQ(read_bytes(folder_ / "real.pfm").size(), 12u + 12u);
    EXPECT_EQ(entries(), (std::set<std::string>{"real.pfm", "link.pfm"}));
}

TEST_F(AtomicWriteTest, InvalidImagesAreRejectedBeforeAnyFileIsMade) {
    const std::vector<float> rgb(12, 0.5f);
    const fs::path path = folder_ / "a.png";
    EXPECT_NE(error_of(path, [&] { write_image(path, {0, 4, rgb.data()}, {}); }).find("0x4"), std::string::npos);
    EXPECT_NE(error_of(path, [&] { write_image(path, {4, -1, rgb.data()}, {}); }).find("4x-1"), std::string::npos);
    EXPECT_EQ(error_of(path, [&] { write_image(path, {2, 2, nullptr}, {}); }), "cannot write: no pixel data");
    const fs::path tif = folder_ / "a.tif";
    EXPECT_EQ(error_of(tif,
                       [&] {
                           write_image(tif, {2, 2, rgb.data()}, {});
                       }),
              "unsupported image format 'tif' (use .png, .jpg, .pfm or .exr)");
    EXPECT_TRUE(entries().empty());
}

TEST_F(CheckOutputPathTest, AcceptsANewOrExistingFileInAWritableFolder) {
    EXPECT_NO_THROW(check_output_path(folder_ / "new.png"));
    write_bytes(folder_ / "old.exr", old_content);
    EXPECT_NO_THROW(check_output_path(folder_ / "old.exr"));
    EXPECT_EQ(entries(), (std::set<std::string>{"old.exr"}));  // checking writes nothing
}

TEST_F(CheckOutputPathTest, EmptyParentMeansTheCurrentFolder) {
    const fs::path previous = fs::current_path();
    fs::current_path(folder_);
    EXPECT_NO_THROW(check_output_path("render.png"));
    fs::create_directory("render.pfm");
    EXPECT_THROW(check_output_path("render.pfm"), Error);
    EXPECT_EQ(error_of("nowhere/render.png", [] { check_output_path("nowhere/render.png"); }),
              "folder 'nowhere' does not exist");
    fs::current_path(previous);
}

TEST_F(CheckOutputPathTest, RejectsEachKindOfUnwritablePath) {
    const fs::path missing = folder_ / "missing" / "a.png";
    EXPECT_EQ(error_of(missing, [&] { check_output_path(missing); }),
              "folder '" + (folder_ / "missing").string() + "' does not exist");

    fs::create_directory(folder_ / "dir.exr");
    EXPECT_EQ(error_of(folder_ / "dir.exr", [&] { check_output_path(folder_ / "dir.exr"); }),
              "is a folder, not an image file");

    write_bytes(folder_ / "file", old_content);
    const fs::path under_file = folder_ / "file" / "a.pfm";
    EXPECT_EQ(error_of(under_file, [&] { check_output_path(under_file); }),
              "'" + (folder_ / "file").string() + "' is not a folder");

    const fs::path gif = folder_ / "a.gif";
    EXPECT_EQ(error_of(gif, [&] { check_output_path(gif); }),
              "unsupported image format 'gif' (use .png, .jpg, .pfm or .exr)");
}

TEST_F(CheckOutputPathTest, RejectsAReadOnlyFolder) {
    if (::geteuid() == 0) GTEST_SKIP() << "root ignores folder permissions";
    ::chmod(folder_.c_str(), 0555);
    const fs::path path = folder_ / "a.png";
    const std::string message = error_of(path, [&] { check_output_path(path); });
    EXPECT_EQ(message.rfind("folder '" + folder_.string() + "' is not writable", 0), 0u) << message;
}

}  // namespace
}  // namespace sombra
