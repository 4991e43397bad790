#include "roving/formats/matlab_file.h"

#include <fmt/format.h>
#include <matio.h>

#include <memory>
#include <mutex>

#include "roving/core/error.h"

namespace roving {
namespace {

// matio reports through a logger whose default prints, and aborts on some errors; ours keeps the
// last message for the error we throw. matio's logger is global, hence the lock around a read.
std::mutex matio_lock;
std::string matio_message;

void keep_message(int, char* message) { matio_message = message ? message : ""; }

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

template <typename T>
MatlabArray<T> read_array(const std::string& path, const std::string& name, T (*convert)(double)) {
  const std::lock_guard<std::mutex> lock(matio_lock);
  Mat_LogInitFunc("roving", keep_message);
  matio_message.clear();
  const auto detail = [] { return matio_message.empty() ? std::string() : " (" + matio_message + ")"; };
  std::unique_ptr<mat_t, int (*)(mat_t*)> file(Mat_Open(path.c_str(), MAT_ACC_RDONLY), Mat_Close);
  if (!file) throw Error(fmt::format("{}: not a MATLAB .mat file that can be read{}", path, detail()));
  // The header first: its size is checked before the data is read.
  std::unique_ptr<matvar_t, void (*)(matvar_t*)> info(Mat_VarReadInfo(file.get(), name.c_str()), Mat_VarFree);
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
  info.reset();
  std::unique_ptr<matvar_t, void (*)(matvar_t*)> variable(Mat_VarRead(file.get(), name.c_str()), Mat_VarFree);
  if (!variable || !variable->data || variable->class_type != class_type) {
    if (count == 0 && variable) return array;
    throw Error(fmt::format("{}: variable '{}' is truncated or malformed{}", path, name, detail()));
  }
  const std::size_t element_size = Mat_SizeOfClass(class_type);
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
