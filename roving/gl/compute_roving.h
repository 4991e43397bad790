// Internal to roving/gl: exact surface roving's cameras in a compute pass (compute_roving_shader.h)
// over TEST's triangles and their grid, held in storage buffers; the GL side of
// DepthRenderer::rove_samples().
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gl_api.h"
#include "roving/gl/depth_renderer.h"

namespace roving::gl {

class ComputeRoving {
 public:
  ComputeRoving(const Api& gl, std::string backend);
  ~ComputeRoving();
  ComputeRoving(const ComputeRoving&) = delete;
  ComputeRoving& operator=(const ComputeRoving&) = delete;

  // Uploads the grid's buckets once. Throws roving::Error where a buffer is larger than the
  // context's largest storage block.
  void upload_grid(const GridBuckets& grid);
  // One dispatch per chunk of samples that the context's work group count allows, one mapped
  // read-back each; `positions` and `corners` are TEST's storage buffers (double positions,
  // three corners a triangle).
  void run(GLuint positions, GLuint corners, const std::vector<double>& samples, const RovingSetup& setup,
           std::vector<ComputedTile>& answers);

 private:
  enum Buffer { kOffsets, kEntries, kSamples, kAnswers, kBuffers };
  template <class T>
  void upload(Buffer buffer, const std::vector<T>& data, const char* what);

  const Api& gl_;
  std::string backend_;
  GLuint programs_[2] = {};  // without and with the faces' choice
  GLuint buffers_[kBuffers] = {};
  GridBuckets grid_;
  bool grid_ready_ = false;
  long long max_block_ = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
};

}  // namespace roving::gl
