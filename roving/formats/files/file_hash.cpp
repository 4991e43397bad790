// sha256 by OpenSSL, read in 1 MiB blocks: a mapping of the whole file would count its pages in
// the process's resident memory (190 MiB for a 10 M-triangle model) while they are hashed.
#include "roving/formats/files/file_hash.h"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "roving/core/error.h"
#include "roving/formats/files/file_bytes.h"

namespace roving {

std::string file_sha256(const std::string& path) {
  { const FileBytes check(path, "a file to hash"); }  // the shared errors: missing, a directory, empty
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!file) throw Error(fmt::format("{}: cannot open for reading ({})", path, std::strerror(errno)));
  const std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> context(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  if (!context || !EVP_DigestInit_ex(context.get(), EVP_sha256(), nullptr)) {
    throw Error(fmt::format("{}: computing its sha256 failed", path));
  }
  std::vector<unsigned char> block(1 << 20);
  while (const std::size_t n = std::fread(block.data(), 1, block.size(), file.get())) {
    EVP_DigestUpdate(context.get(), block.data(), n);
  }
  if (std::ferror(file.get())) throw Error(fmt::format("{}: read failed while hashing it", path));
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_DigestFinal_ex(context.get(), digest, &length);
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

}  // namespace roving
