#include "roving/formats/images_and_matlab/matlab_file.h"

#include <fmt/format.h>
#include <matio.h>
#include <zlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>

#include "roving/core/error.h"
#include "roving/core/run_time_library.h"

namespace roving {
namespace {

// matio reports through a logger whose default prints, and aborts on some errors; ours keeps the
// last message for the error we throw. matio's logger is global, hence the lock around a read.
std::mutex matio_lock;
std::string matio_message;

void keep_message(int, char* message) { matio_message = message ? message : ""; }

// libmatio is opened when a .mat file is first read, not linked: through HDF5 it pulls in curl,
// GnuTLS, Kerberos and LDAP, whose loading cost every run of the command 13 ms at start (of 44),
// for the DTU protocol alone to use. ROVING_MATIO_LIBRARY: its soname, from the build.
struct MatioLibrary {
  decltype(&Mat_LogInitFunc) log_init = nullptr;
  decltype(&Mat_Open) open = nullptr;
  decltype(&Mat_Close) close = nullptr;
  decltype(&Mat_VarReadInfo) read_info = nullptr;
  decltype(&Mat_VarRead) read = nullptr;
  decltype(&Mat_VarFree) free = nullptr;
  decltype(&Mat_SizeOfClass) size_of_class = nullptr;
};

const MatioLibrary& matio() {
  static const MatioLibrary library = [] {
    const RunTimeLibrary matio(ROVING_MATIO_LIBRARY, "reading .mat files", "install Debian's libmatio11");
    MatioLibrary l;
    matio.load(l.log_init, "Mat_LogInitFunc");
    matio.load(l.open, "Mat_Open");
    matio.load(l.close, "Mat_Close");
    matio.load(l.read_info, "Mat_VarReadInfo");
    matio.load(l.read, "Mat_VarRead");
    matio.load(l.free, "Mat_VarFree");
    matio.load(l.size_of_class, "Mat_SizeOfClass");
    return l;
  }();
  return library;
}

const char* class_name(matio_classes class_type) {
  switch (class_type) {
    case MAT_C_CELL: return "cell";
    case MAT_C_STRUCT: return "struct";
    case MAT_C_CHAR: return "char";
    case MAT_C_SPARSE: return "sparse";
    case MAT_C_OBJECT: return "object";
    case MAT_C_FUNCTION: return "function handle";
    default: return "non-numeric";
  }
}

constexpr std::size_t kMaxElements = 1000000000;

// The structure of a level 5 file, checked before matio reads it: matio trusts the sizes in its
// tags, and the fuzzer (tests/fuzz's fuzz_mat) found a 480-byte file whose dimensions tag declared
// 5.8 GB, which matio then allocated, and a MATLAB 4 file on which matio's reader spent minutes
// clearing a buffer of a size it declared. So: a level 5 header (128 bytes ending in the endian
// mark "IM" or "MI", version 0x0100; MATLAB 4 and 7.3 (HDF5) files are refused), then every
// element's size within what holds it, into matrices and through compressed elements (inflated
// here, to at most kMaxInflation times their size: deflate's own limit is 1032), and every
// matrix's element count within what the file could hold (matio allocates a cell array's
// elements by its dimensions before reading any: fuzz_mat found 10^13 declared in 600 bytes).
constexpr std::size_t kMaxInflation = 1100;
constexpr int kMaxDepth = 16;
constexpr std::uint32_t kMatrix = 14, kCompressed = 15;

class Level5Check {
 public:
  Level5Check(std::string path, bool swap, std::size_t file_bytes)
      : path_(std::move(path)), swap_(swap), most_elements_(kMaxInflation * file_bytes + 4096) {}

  // The elements of [data, data + size), each whole; `depth` counts the matrices and compressed
  // elements around them.
  void elements(const std::uint8_t* data, std::size_t size, int depth) const {
    if (depth > kMaxDepth) fail(fmt::format("elements nested more than {} deep", kMaxDepth));
    for (std::size_t at = 0; at < size;) {
      if (size - at < 8) {
        if (depth == 0) return;  // padding at the end of the file
        fail("an element's 8-byte tag is cut off");
      }
      std::uint32_t type = word(data + at), bytes = word(data + at + 4);
      if (type >> 16) {  // the small element format: 1 to 4 bytes of data within the tag
        if ((type >> 16) > 4) fail(fmt::format("a small element declares {} bytes (at most 4)", type >> 16));
        at += 8;
        continue;
      }
      if (bytes > size - at - 8) {
        fail(fmt::format("an element at byte {} declares {} bytes; {} remain", at, bytes, size - at - 8));
      }
      const std::uint8_t* body = data + at + 8;
      if (type == kMatrix) {
        dimensions(body, bytes);
        elements(body, bytes, depth + 1);
      }
      if (type == kCompressed) {
        const std::vector<std::uint8_t> inflated = inflate(body, bytes);
        elements(inflated.data(), inflated.size(), depth + 1);
      }
      // Elements are padded to 8 bytes, but for compressed ones (and the last may lack it).
      const std::size_t padded = type == kCompressed ? bytes : (std::size_t(bytes) + 7) / 8 * 8;
      at += 8 + std::min(padded, size - at - 8);
    }
  }

 private:
  // A matrix's dimensions (its second element, after the array flags' 16 bytes): each >= 0, their
  // product at most most_elements_. matio reads them at that place whatever size the flags
  // element declares, and allocates by their byte count (fuzz_mat: flags of 17 bytes, which
  // elements() steps over, hid a dimensions tag of 3.2 GB, a 6.4 GB allocation), so their tag is
  // checked here, not only as elements() walks the matrix.
  void dimensions(const std::uint8_t* matrix, std::size_t size) const {
    if (size < 24 || (word(matrix + 16) >> 16)) return;  // none, or one small element: nothing large
    const std::uint32_t bytes = word(matrix + 20);
    if (bytes > size - 24) {
      fail(fmt::format("a matrix's dimensions declare {} bytes; {} remain", bytes, size - 24));
    }
    std::size_t product = 1;
    for (std::uint32_t i = 0; i + 4 <= bytes; i += 4) {
      const auto d = static_cast<std::int32_t>(word(matrix + 24 + i));
      if (d < 0) fail(fmt::format("a matrix has dimension {}", d));
      if (d != 0 && product > most_elements_ / std::size_t(d)) {
        fail(fmt::format("a matrix declares more than {} elements", most_elements_));
      }
      product *= std::size_t(d);
    }
  }

  std::uint32_t word(const std::uint8_t* p) const {
    std::uint32_t v = std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
                      std::uint32_t(p[3]) << 24;
    return swap_ ? __builtin_bswap32(v) : v;
  }

  std::vector<std::uint8_t> inflate(const std::uint8_t* data, std::size_t size) const {
    const std::size_t limit = kMaxInflation * size + 4096;
    z_stream stream{};
    if (inflateInit(&stream) != Z_OK) fail("zlib could not start");
    std::vector<std::uint8_t> out;
    stream.next_in = const_cast<Bytef*>(data);
    stream.avail_in = static_cast<uInt>(size);
    int status = Z_OK;
    while (status == Z_OK) {
      if (out.size() >= limit) {
        inflateEnd(&stream);
        fail(fmt::format("a compressed element of {} bytes inflates to more than {}", size, limit));
      }
      const std::size_t had = out.size();
      out.resize(std::min(limit, had + std::max<std::size_t>(65536, had)));
      stream.next_out = out.data() + had;
      stream.avail_out = static_cast<uInt>(out.size() - had);
      status = ::inflate(&stream, Z_NO_FLUSH);
      out.resize(out.size() - stream.avail_out);
    }
    inflateEnd(&stream);
    if (status != Z_STREAM_END) fail("a compressed element is not a whole zlib stream");
    return out;
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(fmt::format("{}: a malformed MATLAB .mat file ({})", path_, what));
  }

  std::string path_;
  bool swap_;
  std::size_t most_elements_;
};

void require_level_5(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(fmt::format("{}: cannot be opened", path));
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::string mark = bytes.size() >= 128 ? std::string(bytes.begin() + 126, bytes.begin() + 128) : "";
  if (mark != "IM" && mark != "MI") {
    throw Error(fmt::format("{}: not a MATLAB level 5 .mat file ({}; MATLAB 4 files are not read: save with -v7)",
                            path,
                            bytes.size() < 128 ? fmt::format("{} bytes, shorter than the 128-byte header", bytes.size())
                                               : "its 128-byte header does not end in 'IM' or 'MI'"));
  }
  const bool swap = mark == "MI";
  const unsigned version = swap ? bytes[124] << 8 | bytes[125] : bytes[125] << 8 | bytes[124];
  if (version != 0x0100) {
    throw Error(fmt::format("{}: a MATLAB .mat file of version 0x{:04x}{}; expected level 5 (0x0100): save with -v7",
                            path, version, version == 0x0200 ? " (7.3, HDF5)" : ""));
  }
  Level5Check(path, swap, bytes.size()).elements(bytes.data() + 128, bytes.size() - 128, 0);
}

template <typename T>
MatlabArray<T> read_array(const std::string& path, const std::string& name, T (*convert)(double)) {
  require_level_5(path);
  const std::lock_guard<std::mutex> lock(matio_lock);
  const MatioLibrary& mat = matio();
  mat.log_init("roving", keep_message);
  matio_message.clear();
  const auto detail = [] { return matio_message.empty() ? std::string() : " (" + matio_message + ")"; };
  std::unique_ptr<mat_t, int (*)(mat_t*)> file(mat.open(path.c_str(), MAT_ACC_RDONLY), mat.close);
  if (!file) throw Error(fmt::format("{}: not a MATLAB .mat file that can be read{}", path, detail()));
  // The header first: its size is checked before the data is read.
  std::unique_ptr<matvar_t, void (*)(matvar_t*)> info(mat.read_info(file.get(), name.c_str()), mat.free);
  if (!info) throw Error(fmt::format("{}: no variable '{}'{}", path, name, detail()));
  if (info->isComplex) throw Error(fmt::format("{}: variable '{}' is complex; expected real numbers", path, name));
  const matio_classes class_type = info->class_type;
  const bool numeric = class_type == MAT_C_DOUBLE || class_type == MAT_C_SINGLE ||
                       (class_type >= MAT_C_INT8 && class_type <= MAT_C_UINT64);
  if (!numeric) {
    throw Error(fmt::format("{}: variable '{}' is a {} array; expected a numeric or logical one", path, name,
                            class_name(class_type)));
  }
  MatlabArray<T> array;
  std::size_t count = 1;
  for (int i = 0; i < info->rank; ++i) {
    array.dims.push_back(info->dims[i]);
    if (info->dims[i] != 0 && count > kMaxElements / info->dims[i]) {
      throw Error(fmt::format("{}: variable '{}' declares more than {} elements", path, name, kMaxElements));
    }
    count *= info->dims[i];
  }
  // Its values come from the file, compressed at most kMaxInflation to 1: more is a lie matio
  // would allocate for before finding the data short.
  const std::size_t file_bytes = std::filesystem::file_size(path);
  if (count * mat.size_of_class(class_type) > kMaxInflation * file_bytes + 4096) {
    throw Error(fmt::format("{}: variable '{}' declares {} elements, more than its {}-byte file can hold", path, name,
                            count, file_bytes));
  }
  info.reset();
  std::unique_ptr<matvar_t, void (*)(matvar_t*)> variable(mat.read(file.get(), name.c_str()), mat.free);
  if (!variable || !variable->data || variable->class_type != class_type) {
    if (count == 0 && variable) return array;
    throw Error(fmt::format("{}: variable '{}' is truncated or malformed{}", path, name, detail()));
  }
  const std::size_t element_size = mat.size_of_class(class_type);
  if (element_size == 0 || variable->nbytes < count * element_size) {
    throw Error(fmt::format("{}: variable '{}' holds {} bytes; its {} elements need {}", path, name,
                            variable->nbytes, count, count * element_size));
  }
  array.values.resize(count);
  const void* data = variable->data;
  const auto fill = [&](auto* typed) {
    for (std::size_t i = 0; i < count; ++i) array.values[i] = convert(static_cast<double>(typed[i]));
  };
  switch (class_type) {
    case MAT_C_DOUBLE: fill(static_cast<const double*>(data)); break;
    case MAT_C_SINGLE: fill(static_cast<const float*>(data)); break;
    case MAT_C_INT8: fill(static_cast<const std::int8_t*>(data)); break;
    case MAT_C_UINT8: fill(static_cast<const std::uint8_t*>(data)); break;
    case MAT_C_INT16: fill(static_cast<const std::int16_t*>(data)); break;
    case MAT_C_UINT16: fill(static_cast<const std::uint16_t*>(data)); break;
    case MAT_C_INT32: fill(static_cast<const std::int32_t*>(data)); break;
    case MAT_C_UINT32: fill(static_cast<const std::uint32_t*>(data)); break;
    case MAT_C_INT64: fill(static_cast<const std::int64_t*>(data)); break;
    case MAT_C_UINT64: fill(static_cast<const std::uint64_t*>(data)); break;
    default: break;
  }
  return array;
}

}  // namespace

MatlabArray<double> read_matlab_numbers(const std::string& path, const std::string& name) {
  return read_array<double>(path, name, [](double v) { return v; });
}

MatlabArray<std::uint8_t> read_matlab_mask(const std::string& path, const std::string& name) {
  return read_array<std::uint8_t>(path, name, [](double v) { return static_cast<std::uint8_t>(v != 0); });
}

}  // namespace roving
