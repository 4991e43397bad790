// GLSL program building shared by the depth and the shaded renderer.
#include "gl_program.h"

#include <fmt/format.h>

#include "roving/core/error.h"

namespace roving::gl {
namespace {

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
    throw Error(fmt::format("gl ({}): the {} {} shader does not compile: {}", backend, name,
                            type == GL_VERTEX_SHADER ? "vertex" : "fragment", log));
  }
  return shader;
}

}  // namespace

GLuint link_program(const Api& gl, const std::string& backend, const char* name, const char* vertex_source,
                    const char* fragment_source) {
  const GLuint vertex = compile(gl, backend, GL_VERTEX_SHADER, vertex_source, name);
  const GLuint fragment = compile(gl, backend, GL_FRAGMENT_SHADER, fragment_source, name);
  const GLuint program = gl.CreateProgram();
  gl.AttachShader(program, vertex);
  gl.AttachShader(program, fragment);
  gl.LinkProgram(program);
  gl.DeleteShader(vertex);
  gl.DeleteShader(fragment);
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

void check_error(const Api& gl, const std::string& backend, const char* what) {
  const GLenum code = gl.GetError();
  if (code != GL_NO_ERROR)
    throw Error(fmt::format("gl ({}): {} failed with GL error 0x{:x}", backend, what, code));
}

}  // namespace roving::gl
