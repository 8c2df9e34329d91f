#include "image/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <exception>
#include <new>
#include <string>
#include <system_error>

#include "core/error.h"

namespace sombra {

namespace fs = std::filesystem;

std::string errno_message(int error_number) {
    std::string message = std::generic_category().message(error_number);
    if (!message.empty()) message[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(message[0])));
    return message;
}

namespace {

// Creates a fresh temporary file beside `target` and returns its path. O_EXCL
// makes the name ours alone, so concurrent writers (threads or processes) never
// share one, without a global counter. Mode 0666 lets the umask decide, as for
// any ordinary new file.
fs::path create_temp_beside(const fs::path& target) {
    const fs::path folder = target.parent_path();
    // Cut a long name so that the temporary one stays within NAME_MAX (255 bytes).
    std::string stem = ".";  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on "." + string
    stem += target.filename().string().substr(0, 200);
    stem += ".tmp-" + std::to_string(::getpid()) + "-";
    constexpr int max_attempts = 1000;
    for (int n = 0; n < max_attempts; ++n) {
        fs::path temp = folder / (stem + std::to_string(n));
        const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            return temp;
        }
        const int open_errno = errno;
        if (open_errno != EEXIST) {
            const std::string shown = folder.empty() ? std::string(".") : folder.string();
            throw Error(target.string(), "cannot write: cannot create a temporary file in '" + shown +
                                             "': " + errno_message(open_errno));
        }
    }
    throw Error(target.string(), "cannot write: no free temporary file name");
}

// Pushes the temporary file's bytes to the disk before the rename, so that a
// crash right after it cannot leave an empty target behind.
void sync_file(const fs::path& file) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw std::system_error(errno, std::generic_category());
    const int result = ::fsync(fd);
    const int sync_errno = errno;
    ::close(fd);
    if (result != 0) throw std::system_error(sync_errno, std::generic_category());
}

std::string reason_of(const std::exception& e) {
    if (const auto* error = dynamic_cast<const Error*>(&e)) return error->message();
    if (const auto* system = dynamic_cast<const std::system_error*>(&e)) return errno_message(system->code().value());
    if (dynamic_cast<const std::bad_alloc*>(&e)) return "out of memory";
    return e.what();
}

}  // namespace

void write_file_atomically(const fs::path& target, const std::function<void(const fs::path& temp)>& fill) {
    const fs::path temp = create_temp_beside(target);
    std::string reason;
    try {
        fill(temp);
        sync_file(temp);
        fs::rename(temp, target);
        return;
    } catch (const std::exception& e) {
        reason = reason_of(e);
    } catch (...) {
        reason = "unknown failure";
    }
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw Error(target.string(), "cannot write: " + reason);
}

}  // namespace sombra
