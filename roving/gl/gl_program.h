// Compiling and linking the renderers' GLSL programs, with the driver's log in the error.
#pragma once

#include <string>

#include "gl_api.h"

namespace roving::gl {

// Links a program from two shader sources; throws roving::Error naming `name`, the backend and
// the driver's log when a shader does not compile or the program does not link.
GLuint link_program(const Api& gl, const std::string& backend, const char* name, const char* vertex_source,
                    const char* fragment_source);
// The same for a compute program.
GLuint link_compute_program(const Api& gl, const std::string& backend, const char* name, const char* source);

// glGetError after `what`; throws roving::Error naming it and the code.
void check_error(const Api& gl, const std::string& backend, const char* what);

}  // namespace roving::gl
