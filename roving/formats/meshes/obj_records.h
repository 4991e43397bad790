// The records of a Wavefront OBJ that both its readers parse, the whole file's (obj_reader.h) and
// the block-at-a-time stream's (obj_triangle_stream.h), with the same checks and messages.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "roving/core/error.h"
#include "roving/core/triangle_mesh.h"
#include "roving/formats/files/file_bytes.h"

namespace roving::obj {

// The error for the current line: "PATH:LINE: what".
using Fail = std::function<Error(const std::string& what)>;
// That of `lines`' current line, numbered after `lines_before` lines (where the cursor began).
Fail line_error(const std::string& path, const LineCursor& lines, std::size_t lines_before = 0);

// 'v x y z [r g b | w]' after the keyword: the position, and true with `rgb` where three more
// numbers follow (a colour; one more is the homogeneous w, ignored).
bool parse_vertex(std::string_view rest, Vec3& position, double rgb[3], const Fail& fail);
// 'vt u v' after the keyword: two finite numbers.
void parse_texture_coordinate(std::string_view rest, double uv[2], const Fail& fail);
// 'f v[/vt[/vn]] ...' after the keyword, with `vertices` and `texture_coordinates` defined so far:
// each corner's 0-based vertex and texture coordinate (-1 where none is given); at least 3.
void parse_face(std::string_view rest, long long vertices, long long texture_coordinates, std::vector<int>& corners,
                std::vector<int>& corner_uv, const Fail& fail);
// Whether a face names a vertex twice (the readers drop it and count it).
bool repeats_a_vertex(const std::vector<int>& corners);

}  // namespace roving::obj
