// Temporary-file-and-rename output.
#include "roving/formats/files/atomic_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <regex>

#include "roving/core/error.h"

namespace roving {

namespace {

// The temporary files alive in this process, for the signal handler: slots of pointers to each
// AtomicFile's temporary_ (lock-free, so the handler may read them).
std::array<std::atomic<const char*>, 64> live_temporaries{};

void track(const char* temporary) {
  for (auto& slot : live_temporaries) {
    const char* empty = nullptr;
    if (slot.compare_exchange_strong(empty, temporary)) return;
  }  // more than 64 at once: the next run sweeps what a signal leaves
}

void untrack(const char* temporary) {
  for (auto& slot : live_temporaries) {
    const char* expected = temporary;
    if (slot.compare_exchange_strong(expected, nullptr)) return;
  }
}

extern "C" void remove_temporaries_and_exit(int signal) {
  for (auto& slot : live_temporaries) {
    if (const char* temporary = slot.load()) ::unlink(temporary);
  }
  ::_exit(128 + signal);
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  const auto slash = path_.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "" : path_.substr(0, slash + 1);
  const std::string name = path_.substr(folder.size());
  const auto dot = name.find_last_of('.');
  const std::string extension = dot == std::string::npos || dot == 0 ? "" : name.substr(dot);
  int fd = -1;
  for (int attempt = 0;; ++attempt) {
    // ".NAME.XXXXXX.ext": hidden, unique, and still ending in the extension.
    std::string pattern = folder + "." + name + ".XXXXXX" + extension;
    fd = ::mkstemps(pattern.data(), static_cast<int>(extension.size()));
    if (fd < 0) throw Error(fmt::format("{}: cannot open for writing ({})", path_, std::strerror(errno)));
    temporary_ = pattern;
    // The lock says "a live process writes this": remove_if_abandoned() leaves it alone. A second
    // descriptor keeps it until the rename, after the stream is closed.
    lock_fd_ = ::dup(fd);
    if (lock_fd_ >= 0) ::flock(lock_fd_, LOCK_EX);
    // A concurrent sweep (a batch shard starting) may have locked and removed the file in the
    // moment before our lock: then it is not ours by that name any more, and we start again.
    struct stat ours {}, named {};
    if (::fstat(fd, &ours) != 0 || ::stat(temporary_.c_str(), &named) != 0 || ours.st_ino != named.st_ino ||
        ours.st_dev != named.st_dev) {
      ::close(fd);
      if (lock_fd_ >= 0) ::close(lock_fd_);
      if (attempt < 100) continue;
      throw Error(fmt::format("{}: cannot open for writing (its temporary file kept being removed)", path_));
    }
    break;
  }
  track(temporary_.c_str());
  stream_ = ::fdopen(fd, "wb");
  if (!stream_) {
    ::close(fd);
    ::unlink(temporary_.c_str());
    untrack(temporary_.c_str());
    if (lock_fd_ >= 0) ::close(lock_fd_);
    throw Error(fmt::format("{}: cannot open for writing", path_));
  }
}

AtomicFile::~AtomicFile() {
  if (stream_) std::fclose(stream_);
  if (!committed_) ::unlink(temporary_.c_str());
  untrack(temporary_.c_str());
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

bool is_temporary_name(const std::string& name) {
  static const std::regex pattern(R"(\..+\.[A-Za-z0-9]{6}(\.[A-Za-z0-9]+)?)");
  return std::regex_match(name, pattern);
}

bool remove_if_abandoned(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) return false;
  struct stat info {};
  // A live writer holds LOCK_EX until its rename; the lock is released when a writer dies.
  const bool abandoned = ::fstat(fd, &info) == 0 && S_ISREG(info.st_mode) && ::flock(fd, LOCK_EX | LOCK_NB) == 0;
  const bool removed = abandoned && ::unlink(path.c_str()) == 0;
  ::close(fd);
  return removed;
}

void remove_temporaries_on_signals() {
  struct sigaction action {};
  action.sa_handler = remove_temporaries_and_exit;
  sigemptyset(&action.sa_mask);
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(signal, &action, nullptr);
}

void AtomicFile::close_stream() {
  if (!stream_) return;
  const bool failed =
      std::fflush(stream_) != 0 || std::ferror(stream_) != 0 || ::fsync(::fileno(stream_)) != 0;
  const int error = errno;
  const bool close_failed = std::fclose(stream_) != 0;
  stream_ = nullptr;
  if (failed || close_failed) {
    throw Error(fmt::format("{}: write failed ({}); the file was not changed", path_, std::strerror(error)));
  }
}

void AtomicFile::commit() {
  close_stream();
  // mkstemps creates the file 0600; outputs get the usual permissions.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::chmod(temporary_.c_str(), 0666 & ~mask);
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    throw Error(
        fmt::format("{}: cannot move the finished file into place ({})", path_, std::strerror(errno)));
  }
  committed_ = true;
  untrack(temporary_.c_str());
}

void write_stdout(const std::string& text) {
  const bool failed =
      std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0;
  if (failed) throw Error(fmt::format("standard output: write failed ({})", std::strerror(errno)));
}

}  // namespace roving
