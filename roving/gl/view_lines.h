// Internal to roving/gl: viewpoint sampling's lookup of each sample's normal line in the view
// just drawn, in a compute pass (view_lines_shader.h); the GL side of
// DepthRenderer::read_view_lines().
#pragma once

#include <string>
#include <vector>

#include "gl_api.h"
#include "roving/gl/depth_renderer.h"

namespace roving::gl {

class ViewLines {
 public:
  ViewLines(const Api& gl, std::string backend);
  ~ViewLines();
  ViewLines(const ViewLines&) = delete;
  ViewLines& operator=(const ViewLines&) = delete;

  // Copies the drawn rectangle of the bound framebuffer's depth into a storage buffer on the GPU
  // (no read-back), then one dispatch per chunk of samples, one mapped read-back each.
  void run(const ViewLineSetup& setup, const std::vector<double>& samples,
           std::vector<ViewLineAnswer>& answers);

 private:
  enum Buffer { kDepth, kSamples, kAnswers, kBuffers };
  const Api& gl_;
  std::string backend_;
  GLuint program_ = 0;
  GLuint buffers_[kBuffers] = {};
};

}  // namespace roving::gl
