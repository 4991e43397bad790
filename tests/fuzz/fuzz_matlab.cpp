// libFuzzer harness for MATLAB .mat files: the bytes are written to a file and every variable the
// DTU protocol reads is read from it (ObsMask as a mask; BB, Res and P as numbers), as
// --dtu-obs-mask and --dtu-plane read them. A roving::Error is a clean refusal; a crash, a sanitizer
// report, a hang or an allocation over the limit is a finding (libmatio's own included).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "roving/core/error.h"
#include "roving/formats/images_and_matlab/matlab_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/roving-fuzz-" + std::to_string(::getpid()) + ".mat";
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) std::abort();
  std::fwrite(data, 1, size, file);
  std::fclose(file);
  try {
    (void)roving::read_matlab_mask(path, "ObsMask");
  } catch (const roving::Error&) {
  }
  for (const char* name : {"BB", "Res", "P"}) {
    try {
      (void)roving::read_matlab_numbers(path, name);
    } catch (const roving::Error&) {
    }
  }
  return 0;
}
