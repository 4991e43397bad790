// Memory-mapped input files and token helpers shared by the strict readers.
#include "roving/formats/files/file_bytes.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>

#include "roving/core/error.h"

namespace roving {

namespace {

const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a named pipe (FIFO)";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  return "not a regular file";
}

bool trusted_references = false;

}  // namespace

void require_regular_file(const std::string& path, const std::string& what) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    throw Error(fmt::format("{}: cannot open for reading ({})", path, std::strerror(errno)));
  }
  if (!S_ISREG(info.st_mode)) {
    throw Error(fmt::format("{}: is {}; expected a file holding {}", path, file_kind(info.st_mode), what));
  }
}

void references_may_leave_folder(bool allowed) {
  trusted_references = allowed;
}

std::string resolve_reference(const std::string& referrer, const std::string& reference, const std::string& what) {
  namespace fs = std::filesystem;
  const fs::path folder = fs::path(referrer).parent_path();
  const fs::path resolved = (folder / reference).lexically_normal();
  if (trusted_references) return resolved.string();
  const auto refuse = [&](const char* why) {
    return Error(fmt::format("{}: {} '{}' {}; references must stay in the model's folder (--trust-references "
                             "allows it for inputs you trust)",
                             referrer, what, reference, why));
  };
  if (fs::path(reference).is_absolute()) throw refuse("is an absolute path");
  const fs::path relative = resolved.lexically_relative(folder.empty() ? fs::path(".") : folder);
  if (relative.empty() || *relative.begin() == "..") throw refuse("leads out of the folder");
  std::error_code error;
  // Absolute first: of a relative path none of whose parts exists, weakly_canonical returns it
  // relative, and a missing file beside the model read as a link leading out of the folder.
  const fs::path real_folder = fs::weakly_canonical(fs::absolute(folder.empty() ? fs::path(".") : folder), error);
  const fs::path real = fs::weakly_canonical(fs::absolute(resolved), error);
  const fs::path inside = real.lexically_relative(real_folder);
  if (!error && (inside.empty() || *inside.begin() == "..")) throw refuse("is a symbolic link leading out of the folder");
  return resolved.string();
}

FileBytes::FileBytes(const std::string& path, const std::string& what) {
  require_regular_file(path, what);
  // O_NONBLOCK: should the path have become a FIFO since the check, open() still returns at once.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw Error(fmt::format("{}: cannot open for reading ({})", path, std::strerror(errno)));
  struct stat info {};
  if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    ::close(fd);
    throw Error(fmt::format("{}: is {}; expected a file holding {}", path, file_kind(info.st_mode), what));
  }
  size_ = static_cast<std::size_t>(info.st_size);
  if (size_ == 0) {
    ::close(fd);
    throw Error(fmt::format("{}: file is empty; expected {}", path, what));
  }
  void* mapped = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
  ::close(fd);
  if (mapped == MAP_FAILED)
    throw Error(fmt::format("{}: cannot map {} bytes ({})", path, size_, std::strerror(errno)));
  ::madvise(mapped, size_, MADV_SEQUENTIAL);
  data_ = static_cast<const char*>(mapped);
}

FileBytes::~FileBytes() {
  if (data_) ::munmap(const_cast<char*>(data_), size_);
}

bool LineCursor::next_line(std::string_view& line) {
  if (position_ >= text_.size()) return false;
  std::size_t end = text_.find('\n', position_);
  if (end == std::string_view::npos) end = text_.size();
  line = text_.substr(position_, end - position_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  position_ = end + 1;
  ++line_number_;
  return true;
}

namespace {
bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}
}  // namespace

std::string_view next_token(std::string_view& rest) {
  std::size_t begin = 0;
  while (begin < rest.size() && is_space(rest[begin])) ++begin;
  std::size_t end = begin;
  while (end < rest.size() && !is_space(rest[end])) ++end;
  const std::string_view token = rest.substr(begin, end - begin);
  rest.remove_prefix(end);
  return token;
}

std::string quoted(std::string_view token) {
  if (token.empty()) return "end of line";
  std::string text(token.substr(0, 40));
  for (char& c : text) {
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  }
  return fmt::format("'{}{}'", text, token.size() > 40 ? "..." : "");
}

bool parse_number(std::string_view token, double& value) {
  // from_chars does not take a leading '+', which some writers emit.
  if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return !token.empty() && error == std::errc() && end == token.data() + token.size();
}

bool parse_number(std::string_view token, long long& value) {
  if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return !token.empty() && error == std::errc() && end == token.data() + token.size();
}

}  // namespace roving
