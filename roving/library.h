// The version of the libroving a program runs against ("0.1.0").
#pragma once

namespace roving {

const char* library_version();

}  // namespace roving
