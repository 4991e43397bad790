// MATLAB .mat files (level 5: MATLAB's -v7 and -v6, read by Debian's libmatio once their structure is
// checked here): one real numeric or logical array by name, as the DTU data set stores its observation
// masks and ground planes. MATLAB 4 and 7.3 (HDF5) files are refused with a message.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace roving {

// An array in MATLAB's order: the first index runs fastest.
template <typename T>
struct MatlabArray {
  std::vector<std::size_t> dims;
  std::vector<T> values;
};

// The variable `name` of `path` converted to double. Throws roving::Error naming the file and
// the variable when the file cannot be read, the variable is missing, complex, not numeric or
// logical (a cell, struct, string), or has more than 10^9 elements.
MatlabArray<double> read_matlab_numbers(const std::string& path, const std::string& name);

// The same, as a mask: 1 where the value is non-zero (logical arrays as MATLAB stores them, or any
// numeric class), one byte per element.
MatlabArray<std::uint8_t> read_matlab_mask(const std::string& path, const std::string& name);

}  // namespace roving
