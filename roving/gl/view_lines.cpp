// Viewpoint sampling's lookup in a compute pass: the view's depth copied on the GPU, uniforms,
// dispatches, read-back of the answers alone.
#include "view_lines.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "gl_program.h"
#include "roving/core/error.h"
#include "view_lines_shader.h"

namespace roving::gl {

constexpr std::size_t kSamplesPerDispatch = 1 << 16;  // 1,024 work groups of 64

ViewLines::ViewLines(const Api& gl, std::string backend) : gl_(gl), backend_(std::move(backend)) {
  program_ = link_compute_program(gl_, backend_, "view lines", compute_shaders::kViewLinesComputeShader);
  gl_.GenBuffers(kBuffers, buffers_);
  check_error(gl_, backend_, "preparing the views' compute pass");
}

ViewLines::~ViewLines() {
  gl_.DeleteBuffers(kBuffers, buffers_);
  gl_.DeleteProgram(program_);
}

void ViewLines::run(const ViewLineSetup& setup, const std::vector<double>& samples,
                    std::vector<ViewLineAnswer>& answers) {
  const std::size_t count = samples.size() / 6;
  answers.resize(count);
  if (count == 0) return;
  const PixelRect& r = setup.rect;
  // The drawn rectangle, row by row, into a buffer the pass reads: a copy on the GPU (a pixel
  // pack into a buffer object), not a read-back.
  const std::size_t pixels = r.empty() ? 1 : std::size_t(r.x1 - r.x0) * std::size_t(r.y1 - r.y0);
  gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, buffers_[kDepth]);
  gl_.BufferData(GL_PIXEL_PACK_BUFFER, pixels * sizeof(float), nullptr, GL_STREAM_COPY);
  if (!r.empty()) gl_.ReadPixels(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);

  gl_.UseProgram(program_);
  const auto location = [&](const char* name) { return gl_.GetUniformLocation(program_, name); };
  const auto vector = [&](const char* name, const Vec3& v) {
    gl_.Uniform3d(location(name), v.x(), v.y(), v.z());
  };
  const OrthoCamera& c = setup.camera;
  vector("centre", c.centre);
  vector("right", c.right);
  vector("up", c.up);
  vector("forward", c.forward);
  vector("half_extents", Vec3(c.half_width, c.half_height, c.half_depth));
  gl_.Uniform4i(location("rect"), r.x0, r.y0, r.empty() ? r.x0 : r.x1, r.empty() ? r.y0 : r.y1);
  gl_.Uniform1i(location("resolution"), setup.resolution);
  gl_.Uniform1d(location("h"), setup.h);
  gl_.Uniform1d(location("smooth_span"), setup.smooth_span);
  gl_.Uniform1d(location("depth_scale"), setup.depth_scale);
  gl_.Uniform1d(location("crease_limit"), setup.crease_limit);
  gl_.Uniform1d(location("min_distance"), setup.min_distance);
  gl_.Uniform1d(location("noise"), setup.noise);
  gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers_[kDepth]);
  const std::size_t chunk = std::min(count, kSamplesPerDispatch);
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[kAnswers]);
  gl_.BufferData(GL_SHADER_STORAGE_BUFFER, chunk * sizeof(ViewLineAnswer), nullptr, GL_STREAM_READ);
  for (std::size_t first = 0; first < count; first += chunk) {
    const std::size_t n = std::min(chunk, count - first);
    gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[kSamples]);
    gl_.BufferData(GL_SHADER_STORAGE_BUFFER, 6 * n * sizeof(double), samples.data() + 6 * first,
                   GL_STREAM_DRAW);
    gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers_[kSamples]);
    gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, buffers_[kAnswers]);
    gl_.Uniform1ui(location("sample_count"), GLuint(n));
    gl_.DispatchCompute(GLuint((n + 63) / 64), 1, 1);
    gl_.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[kAnswers]);
    const void* mapped =
        gl_.MapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, n * sizeof(ViewLineAnswer), GL_MAP_READ_BIT);
    if (!mapped) {
      check_error(gl_, backend_, "mapping the views' compute pass's answers");
      throw Error(fmt::format("gl ({}): mapping the views' compute pass's answers failed", backend_));
    }
    std::memcpy(answers.data() + first, mapped, n * sizeof(ViewLineAnswer));
    gl_.UnmapBuffer(GL_SHADER_STORAGE_BUFFER);
  }
  check_error(gl_, backend_, "the views' compute pass");
}

}  // namespace roving::gl
