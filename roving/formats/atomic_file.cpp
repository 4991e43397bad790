// Temporary-file-and-rename output.
#include "roving/formats/atomic_file.h"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "roving/core/error.h"

namespace roving {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  const auto slash = path_.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "" : path_.substr(0, slash + 1);
  const std::string name = path_.substr(folder.size());
  const auto dot = name.find_last_of('.');
  const std::string extension = dot == std::string::npos || dot == 0 ? "" : name.substr(dot);
  // ".NAME.XXXXXX.ext": hidden, unique, and still ending in the extension.
  std::string pattern = folder + "." + name + ".XXXXXX" + extension;
  const int fd = ::mkstemps(pattern.data(), static_cast<int>(extension.size()));
  if (fd < 0) throw Error(fmt::format("{}: cannot open for writing ({})", path_, std::strerror(errno)));
  temporary_ = pattern;
  stream_ = ::fdopen(fd, "wb");
  if (!stream_) {
    ::close(fd);
    ::unlink(temporary_.c_str());
    throw Error(fmt::format("{}: cannot open for writing", path_));
  }
}

AtomicFile::~AtomicFile() {
  if (stream_) std::fclose(stream_);
  if (!committed_) ::unlink(temporary_.c_str());
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
}

void write_stdout(const std::string& text) {
  const bool failed =
      std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0;
  if (failed) throw Error(fmt::format("standard output: write failed ({})", std::strerror(errno)));
}

}  // namespace roving
