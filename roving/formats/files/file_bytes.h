// A file's bytes, memory-mapped read-only, with the errors every reader shares (missing,
// a directory, empty), and little helpers for bounded parsing.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace roving {

// Throws roving::Error naming `path` unless it is a regular file: a named pipe, socket or device
// could block a read forever or never end, a directory holds no model. Checked by stat(), without
// opening the file. `what` says what was expected ("a .ply mesh").
void require_regular_file(const std::string& path, const std::string& what);

// Throws roving::Error unless `reference`, a file that `referrer` names (a glTF buffer or image, an
// OBJ's mtllib, a texture), resolved relative to `referrer`'s folder, stays inside that folder:
// no absolute path, no '..' out of it, no symbolic link pointing out. Returns the resolved path.
// references_may_leave_folder(true) (the CLI's --trust-references) lifts the rule for trusted inputs.
std::string resolve_reference(const std::string& referrer, const std::string& reference, const std::string& what);
void references_may_leave_folder(bool allowed);

class FileBytes {
 public:
  // Throws roving::Error naming `path` when it cannot be opened, is not a regular file, or is
  // empty (`what` says what was expected: "a .ply mesh").
  FileBytes(const std::string& path, const std::string& what);
  ~FileBytes();
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;

  std::string_view bytes() const { return {data_, size_}; }
  std::size_t size() const { return size_; }

 private:
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

// Text cut into lines ('\n', with a trailing '\r' dropped), and lines into whitespace-separated
// tokens; nothing is copied.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text, std::size_t offset = 0) : text_(text), position_(offset) {}
  // The next line, or false at the end of the text; line_number() is then its 1-based number
  // (counted from `offset`).
  bool next_line(std::string_view& line);
  std::size_t line_number() const { return line_number_; }
  std::size_t offset() const { return std::min(position_, text_.size()); }
  bool at_end() const { return position_ >= text_.size(); }

 private:
  std::string_view text_;
  std::size_t position_;
  std::size_t line_number_ = 0;
};

// The next whitespace-separated token of `rest` (empty at its end), removed from `rest`.
std::string_view next_token(std::string_view& rest);
// The token for a message: 'text', or "end of line" for none; at most 40 characters.
std::string quoted(std::string_view token);
// Whole token as a number; false when it is empty, malformed or out of range.
bool parse_number(std::string_view token, double& value);
bool parse_number(std::string_view token, long long& value);

}  // namespace roving
