// A PLY file's header read into a schema (ply_reader.cpp reads the body by it): the encoding,
// each element with its count and properties, and the role the reader gives each property.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace roving::ply {

enum class Encoding { Ascii, BinaryLittle, BinaryBig };

enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

// What the reader does with a property's values.
enum class Role { Skip, X, Y, Z, NX, NY, NZ, Corners, Red, Green, Blue };

struct Property {
  std::string name;
  Scalar type = Scalar::Float32;
  bool is_list = false;
  Scalar count_type = Scalar::UInt8;
  Role role = Role::Skip;
};

struct Element {
  std::string name;
  unsigned long long count = 0;
  std::vector<Property> properties;
  std::size_t header_line = 0;
};

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;  // first byte after "end_header\n"
  std::size_t lines = 0;        // header lines, for ASCII body line numbers
};

// The bytes of one value of type `s`.
std::size_t size_of(Scalar s);

inline bool is_integral(Scalar s) { return s != Scalar::Float32 && s != Scalar::Float64; }

// The header of `bytes` (the file `path`), its properties' roles given: throws naming the file
// and line on a malformed header, on properties no mesh or point cloud can be read from.
Header parse_header(const std::string& path, std::string_view bytes);
void assign_roles(const std::string& path, Header& header);

// parse_header and assign_roles, and every declared count checked against the bytes left and
// against the memory a mesh of that size would take, before anything is allocated.
Header checked_header(const std::string& path, std::string_view bytes);

}  // namespace roving::ply
