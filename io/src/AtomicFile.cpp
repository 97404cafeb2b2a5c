#include "octrace/io/AtomicFile.h"

#include "octrace/util/Error.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace octrace::io {
namespace {

std::string describeErrno(int err) {
    std::string s = std::error_code(err, std::generic_category()).message();
    if (!s.empty() && s[0] >= 'A' && s[0] <= 'Z') s[0] = char(s[0] - 'A' + 'a');
    return s;
}

std::string folderOf(const std::string& path) {
    std::filesystem::path parent = std::filesystem::path(path).parent_path();
    return parent.empty() ? std::string(".") : parent.string();
}

// Why creating a file next to `path` failed, in words a user can act on.
std::string describeCreateFailure(const std::string& path, int err) {
    std::string folder = folderOf(path);
    std::error_code ec;
    if (err == ENOENT || err == ENOTDIR) {
        auto st = std::filesystem::status(folder, ec);
        if (!std::filesystem::exists(st)) return "folder '" + folder + "' does not exist";
        if (!std::filesystem::is_directory(st)) return "'" + folder + "' is not a folder";
    }
    if (err == EACCES || err == EPERM || err == EROFS)
        return describeErrno(err) + " (cannot create a file in folder '" + folder + "')";
    return describeErrno(err);
}

[[noreturn]] void fail(const std::string& path, const std::string& reason) {
    throw OutputError("cannot write '" + path + "': " + reason);
}

std::string temporaryNameFor(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

}  // namespace

void writeFileAtomically(const std::string& path, std::span<const std::uint8_t> bytes) {
    if (path.empty()) fail(path, "empty file name");
    const std::string tmp = temporaryNameFor(path);

    // O_EXCL: never write through a stale temporary or a symlink planted under that name.
    // Mode 0666 (less the umask), as any other program's output; mkstemp would give 0600.
    int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) fail(path, describeCreateFailure(path, errno));

    auto abandon = [&](const std::string& reason) {
        ::close(fd);
        ::unlink(tmp.c_str());
        fail(path, reason);
    };

    const std::uint8_t* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
        ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            abandon(describeErrno(errno));
        }
        p += n;
        left -= std::size_t(n);
    }
    // Flush before the rename so that a crash right after it cannot leave an empty target.
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) abandon(describeErrno(errno));
    if (::close(fd) != 0) {
        int err = errno;
        ::unlink(tmp.c_str());
        fail(path, describeErrno(err));
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        int err = errno;
        ::unlink(tmp.c_str());
        if (err == EISDIR) fail(path, "it is a folder");
        fail(path, describeErrno(err));
    }
}

void writeFileAtomically(const std::string& path, std::string_view text) {
    writeFileAtomically(path, std::span<const std::uint8_t>(
                                  reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace octrace::io
