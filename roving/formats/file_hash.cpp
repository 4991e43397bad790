// sha256 by OpenSSL over the memory-mapped file.
#include "roving/formats/file_hash.h"

#include <fmt/format.h>
#include <openssl/evp.h>

#include "roving/core/error.h"
#include "roving/formats/file_bytes.h"

namespace roving {

std::string file_sha256(const std::string& path) {
  const FileBytes file(path, "a file to hash");
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (!EVP_Digest(file.bytes().data(), file.size(), digest, &length, EVP_sha256(), nullptr)) {
    throw Error(fmt::format("{}: computing its sha256 failed", path));
  }
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

}  // namespace roving
