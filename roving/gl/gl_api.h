// The GL entry points the renderer uses, loaded through the backend's GetProcAddress. Neither
// libGL nor libOpenGL is linked: OSMesa and EGL each bring their own GL, and loading through a
// table lets both backends live in one process.
#pragma once

#include <GL/glcorearb.h>

#include <functional>
#include <string>

namespace roving::gl {

#define ROVING_GL_FUNCTIONS(X)                                 \
  X(PFNGLGETSTRINGPROC, GetString)                             \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                         \
  X(PFNGLGETERRORPROC, GetError)                               \
  X(PFNGLVIEWPORTPROC, Viewport)                               \
  X(PFNGLSCISSORPROC, Scissor)                                 \
  X(PFNGLCLEARDEPTHPROC, ClearDepth)                           \
  X(PFNGLCLEARCOLORPROC, ClearColor)                           \
  X(PFNGLCLEARPROC, Clear)                                     \
  X(PFNGLENABLEPROC, Enable)                                   \
  X(PFNGLDISABLEPROC, Disable)                                 \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                             \
  X(PFNGLDRAWBUFFERPROC, DrawBuffer)                           \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                           \
  X(PFNGLREADPIXELSPROC, ReadPixels)                           \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                         \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                 \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                 \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer) \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)   \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)           \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)               \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)               \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)         \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)         \
  X(PFNGLCREATESHADERPROC, CreateShader)                       \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                       \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                     \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                         \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)               \
  X(PFNGLDELETESHADERPROC, DeleteShader)                       \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                     \
  X(PFNGLATTACHSHADERPROC, AttachShader)                       \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                         \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                       \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)             \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                           \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                     \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)           \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                             \
  X(PFNGLUNIFORM1UIPROC, Uniform1ui)                           \
  X(PFNGLUNIFORM2IPROC, Uniform2i)                             \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                             \
  X(PFNGLUNIFORM2DVPROC, Uniform2dv)                           \
  X(PFNGLUNIFORM1DPROC, Uniform1d)                             \
  X(PFNGLUNIFORM3DPROC, Uniform3d)                             \
  X(PFNGLUNIFORM3IPROC, Uniform3i)                             \
  X(PFNGLUNIFORM4IPROC, Uniform4i)                             \
  X(PFNGLMAPBUFFERRANGEPROC, MapBufferRange)                   \
  X(PFNGLUNMAPBUFFERPROC, UnmapBuffer)                         \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                 \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                 \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)           \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                           \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                           \
  X(PFNGLBUFFERDATAPROC, BufferData)                           \
  X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                     \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                   \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                     \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)         \
  X(PFNGLVERTEXATTRIBIPOINTERPROC, VertexAttribIPointer)       \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray) \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                           \
  X(PFNGLDRAWARRAYSINDIRECTPROC, DrawArraysIndirect)           \
  X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                 \
  X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                     \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                       \
  X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                         \
  X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                     \
  X(PFNGLCLEARBUFFERUIVPROC, ClearBufferuiv)                   \
  X(PFNGLGENTEXTURESPROC, GenTextures)                         \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                         \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                     \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                           \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                     \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                   \
  X(PFNGLUNIFORM1IPROC, Uniform1i)

struct Api {
#define ROVING_GL_DECLARE(type, name) type name = nullptr;
  ROVING_GL_FUNCTIONS(ROVING_GL_DECLARE)
#undef ROVING_GL_DECLARE

  // Loads every entry point; throws roving::Error naming the first one `get` cannot find.
  void load(const std::function<void*(const char*)>& get, const std::string& backend);
};

}  // namespace roving::gl
