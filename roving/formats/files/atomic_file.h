// Output files that appear whole or not at all: written to a temporary file in the same folder
// and renamed into place by commit(). A failed or abandoned write leaves an existing file
// untouched and no partial file behind.
#pragma once

#include <cstdio>
#include <string>

namespace roving {

class AtomicFile {
 public:
  // Creates the temporary file beside `path`; throws roving::Error naming `path` when the
  // folder is not writable.
  explicit AtomicFile(std::string path);
  ~AtomicFile();  // removes the temporary file unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::FILE* stream() const { return stream_; }
  // A temporary path ending in the final name's extension, for writers that take a path
  // (and choose the format by its extension); close_stream() first.
  const std::string& temporary_path() const { return temporary_; }
  void close_stream();
  // Flushes, checks every write, syncs and renames into place; throws roving::Error naming the
  // final path on failure (a full disk, say), leaving nothing behind.
  void commit();

 private:
  std::string path_, temporary_;
  std::FILE* stream_ = nullptr;
  int lock_fd_ = -1;  // holds an flock on the temporary file while this object lives
  bool committed_ = false;
};

// Whether `name` (a file name, no folder) has the form of an AtomicFile's temporary file,
// ".NAME.XXXXXX.ext".
bool is_temporary_name(const std::string& name);

// Removes `path`, a temporary file left by AtomicFile, if no live process holds it (its writer
// died: killed, or the machine stopped); returns whether it was removed. A temporary file being
// written by another process (a concurrent shard) is left alone: its writer holds an flock on it.
bool remove_if_abandoned(const std::string& path);

// On SIGINT, SIGTERM or SIGHUP, removes the temporary files of every AtomicFile alive and exits
// 128 + the signal's number (130 for SIGINT, 143 for SIGTERM). For programs, not libraries.
void remove_temporaries_on_signals();

// Writes `text` to standard output and flushes; throws roving::Error when it cannot (a full
// disk or a closed pipe), so that a run never exits 0 with its report lost.
void write_stdout(const std::string& text);

}  // namespace roving
