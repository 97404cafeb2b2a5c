#include "octrace/io/AtomicFile.h"

#include "octrace/util/Error.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <fcntl.h>
#include <signal.h>
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

}  // namespace

void checkOutputFolder(const std::string& path) {
    std::error_code ec;
    const auto st = std::filesystem::status(folderOf(path), ec);
    if (!std::filesystem::is_directory(st)) fail(path, describeCreateFailure(path, ENOENT));
}

namespace {

std::string temporaryNameFor(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

// The temporaries being written, for the signal handler: fixed slots, each holding a name and
// a sequence number that is odd while the name changes (a seqlock), so that the handler reads
// complete names only, without locks or allocation.
constexpr std::size_t kSlots = 16, kMaxName = 4096;
struct Slot {
    std::atomic<bool> claimed{false};  // owned by a writer
    std::atomic<bool> live{false};     // `name` may exist on disk: remove it on a signal
    std::atomic<unsigned> sequence{0};
    char name[kMaxName];
};
Slot gSlots[kSlots];
std::atomic<bool> gHandlersInstalled{false};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<unsigned>::is_always_lock_free,
              "the signal handler needs lock-free atomics");

// Registers a temporary (before it is created) for the signal handler, and unregisters it
// when the write is over, whichever way it ends.
class TemporaryRegistration {
public:
    explicit TemporaryRegistration(const std::string& tmp) {
        if (!gHandlersInstalled.load() || tmp.size() >= kMaxName) return;
        for (Slot& s : gSlots) {
            bool expected = false;
            if (!s.claimed.compare_exchange_strong(expected, true)) continue;
            s.sequence.fetch_add(1);  // odd: changing
            std::memcpy(s.name, tmp.c_str(), tmp.size() + 1);
            s.sequence.fetch_add(1);  // even: complete
            s.live.store(true);
            slot_ = &s;
            return;
        }
    }
    ~TemporaryRegistration() {
        if (!slot_) return;
        slot_->live.store(false);
        slot_->claimed.store(false);
    }
    TemporaryRegistration(const TemporaryRegistration&) = delete;
    TemporaryRegistration& operator=(const TemporaryRegistration&) = delete;

private:
    Slot* slot_ = nullptr;
};

// Async-signal-safe: atomics, a copy into the stack, unlink(), raise().
extern "C" void removeTemporariesAndDie(int sig) {
    for (Slot& s : gSlots) {
        if (!s.live.load()) continue;
        const unsigned before = s.sequence.load();
        if (before % 2 != 0) continue;
        char name[kMaxName];
        std::memcpy(name, s.name, kMaxName);
        name[kMaxName - 1] = '\0';
        // A name that changed while it was copied belongs to a later write, which registered
        // it before creating the file: skipping it leaves nothing behind that exists now.
        if (s.sequence.load() != before || !s.live.load()) continue;
        ::unlink(name);
    }
    // SA_RESETHAND restored the default action and SA_NODEFER leaves the signal unblocked:
    // the process ends here, as if the handler had never been installed.
    ::raise(sig);
}

}  // namespace

void removeTemporariesOnSignals() {
    gHandlersInstalled.store(true);
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
        struct sigaction old {};
        if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        struct sigaction sa {};
        sa.sa_handler = removeTemporariesAndDie;
        sigemptyset(&sa.sa_mask);
        sa.sa_flags = SA_RESETHAND | SA_NODEFER;
        ::sigaction(sig, &sa, nullptr);
    }
}

void writeFileAtomically(const std::string& path, std::span<const std::uint8_t> bytes) {
    if (path.empty()) fail(path, "empty file name");
    const std::string tmp = temporaryNameFor(path);
    const TemporaryRegistration registration(tmp);

    // O_EXCL: never write through a stale temporary or a symlink planted under that name.
    // Mode 0666 (less the umask), as any other program's output; mkstemp would give 0600.
    int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) fail(path, describeCreateFailure(path, errno));
    // Test hook (tests/cli/SignalTest.cpp): stop with the temporary created and nothing written,
    // so that the test's signal arrives while the temporary exists, whatever the timing.
    if (const char* hook = std::getenv("OCTRACE_TEST_STOP_WHILE_WRITING"); hook && std::strcmp(hook, "1") == 0) ::raise(SIGSTOP);

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
