// Internal: checks of PLY, OFF and STL headers before OpenMesh reads the body.
#pragma once

#include <string>

namespace roving {

// OpenMesh's readers trust their headers: a non-numeric PLY element count sends its reader into
// a minute-long loop, and an ASCII OFF vertex it cannot parse turns into garbage indices. This
// check refuses such files first, with a message naming the file, what was expected and what
// was found: unknown PLY format or property types, counts that are not integers, counts that
// the file's size cannot hold (truncation), and non-numeric or non-finite plain-OFF vertices.
void check_mesh_header(const std::string& path, const std::string& ext);

}  // namespace roving
