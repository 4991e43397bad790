// GLSL program building shared by the depth and the shaded renderer.
#include "gl_program.h"

#include <fmt/format.h>

#include <initializer_list>
#include <utility>

#include "roving/core/error.h"

namespace roving::gl {
namespace {

const char* stage_name(GLenum type) {
  return type == GL_VERTEX_SHADER ? "vertex" : type == GL_FRAGMENT_SHADER ? "fragment" : "compute";
}

GLuint compile(const Api& gl, const std::string& backend, GLenum type, const char* source, const char* name) {
  const GLuint shader = gl.CreateShader(type);
  gl.ShaderSource(shader, 1, &source, nullptr);
  gl.CompileShader(shader);
  GLint ok = 0;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    gl.GetShaderInfoLog(shader, sizeof log, nullptr, log);
    gl.DeleteShader(shader);
    throw Error(
        fmt::format("gl ({}): the {} {} shader does not compile: {}", backend, name, stage_name(type), log));
  }
  return shader;
}

GLuint link(const Api& gl, const std::string& backend, const char* name,
            std::initializer_list<std::pair<GLenum, const char*>> stages) {
  const GLuint program = gl.CreateProgram();
  for (const auto& [type, source] : stages) {
    GLuint shader = 0;
    try {
      shader = compile(gl, backend, type, source, name);
    } catch (const Error&) {
      gl.DeleteProgram(program);
      throw;
    }
    gl.AttachShader(program, shader);
    gl.DeleteShader(shader);  // freed with the program
  }
  gl.LinkProgram(program);
  GLint ok = 0;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    gl.GetProgramInfoLog(program, sizeof log, nullptr, log);
    gl.DeleteProgram(program);
    throw Error(fmt::format("gl ({}): the {} program does not link: {}", backend, name, log));
  }
  return program;
}

}  // namespace

GLuint link_program(const Api& gl, const std::string& backend, const char* name, const char* vertex_source,
                    const char* fragment_source) {
  return link(gl, backend, name, {{GL_VERTEX_SHADER, vertex_source}, {GL_FRAGMENT_SHADER, fragment_source}});
}

GLuint link_compute_program(const Api& gl, const std::string& backend, const char* name, const char* source) {
  return link(gl, backend, name, {{GL_COMPUTE_SHADER, source}});
}

void check_error(const Api& gl, const std::string& backend, const char* what) {
  const GLenum code = gl.GetError();
  if (code != GL_NO_ERROR)
    throw Error(fmt::format("gl ({}): {} failed with GL error 0x{:x}", backend, what, code));
}

}  // namespace roving::gl
