// The sha256 of a file, for provenance (reports, dataset manifests).
#pragma once

#include <string>

namespace roving {

// Lower-case hex sha256 of the file's bytes; throws roving::Error naming `path` when it cannot
// be read.
std::string file_sha256(const std::string& path);

}  // namespace roving
