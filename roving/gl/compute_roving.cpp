// Exact surface roving's cameras in a compute pass: buffers, uniforms, dispatches, read-back.
#include "compute_roving.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "compute_roving_shader.h"
#include "gl_program.h"
#include "roving/core/error.h"
#include "roving/core/geometry.h"

namespace roving::gl {

// Samples per dispatch: 1,024 work groups of 64, far below any context's work group count,
// and a read-back of 1.5 MiB.
constexpr std::size_t kSamplesPerDispatch = 1 << 16;

ComputeRoving::ComputeRoving(const Api& gl, std::string backend) : gl_(gl), backend_(std::move(backend)) {
  gl_.GenBuffers(kBuffers, buffers_);
  GLint max_block = 0;
  gl_.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  max_block_ = max_block;
  check_error(gl_, backend_, "preparing the roving compute pass");
}

ComputeRoving::~ComputeRoving() {
  gl_.DeleteBuffers(kBuffers, buffers_);
  for (const GLuint program : programs_)
    if (program) gl_.DeleteProgram(program);
}

template <class T>
void ComputeRoving::upload(Buffer buffer, const std::vector<T>& data, const char* what) {
  const std::size_t bytes = std::max<std::size_t>(data.size() * sizeof(T), sizeof(T));
  if (max_block_ > 0 && bytes > static_cast<std::size_t>(max_block_)) {
    throw Error(
        fmt::format("gl ({}): the roving compute pass's {} take {} bytes, more than this context's "
                    "largest storage block ({} bytes); use --camera-geometry cpu or gpu",
                    backend_, what, bytes, max_block_));
  }
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[buffer]);
  gl_.BufferData(GL_SHADER_STORAGE_BUFFER, bytes, data.empty() ? nullptr : data.data(),
                 buffer == kOffsets || buffer == kEntries ? GL_STATIC_DRAW : GL_STREAM_DRAW);
}

void ComputeRoving::upload_grid(const GridBuckets& grid) {
  upload(kOffsets, *grid.offsets, "grid offsets");
  upload(kEntries, *grid.entries, "grid entries");
  grid_ = grid;
  grid_.offsets = grid_.entries = nullptr;  // uploaded: not held
  grid_ready_ = true;
  check_error(gl_, backend_, "uploading the triangle grid");
}

void ComputeRoving::run(GLuint positions, GLuint corners, const std::vector<double>& samples,
                        const RovingSetup& setup, std::vector<ComputedTile>& answers) {
  if (!grid_ready_) throw Error("gl: rove_samples() before upload_grid()");
  const std::size_t count = samples.size() / 6;
  answers.resize(count);
  if (count == 0) return;
  // The shader with or without the faces' choice, compiled when first asked.
  const bool faces = setup.face_window > 0;
  if (!programs_[faces]) {
    const std::string source = fmt::format("#version 450 core\n#define CHOOSE_FACES {}\n{}", int(faces),
                                           compute_shaders::kRovingComputeShader);
    programs_[faces] = link_compute_program(gl_, backend_, faces ? "roving cameras and faces" : "roving cameras",
                                            source.c_str());
  }
  const GLuint program = programs_[faces];
  gl_.UseProgram(program);
  const auto location = [&](const char* name) { return gl_.GetUniformLocation(program, name); };
  gl_.Uniform3d(location("grid_origin"), grid_.origin.x(), grid_.origin.y(), grid_.origin.z());
  gl_.Uniform1d(location("grid_cell"), grid_.cell);
  gl_.Uniform3i(location("grid_dims"), grid_.dims[0], grid_.dims[1], grid_.dims[2]);
  gl_.Uniform1d(location("half_width"), setup.half_width);
  gl_.Uniform1d(location("half_depth"), setup.half_depth);
  gl_.Uniform1d(location("max_error"), setup.max_error);
  gl_.Uniform1d(location("face_window"), setup.face_window);
  // normal_line.cpp's and geometry.h's constants, rounded as the CPU rounds them.
  gl_.Uniform1d(location("unit"), 0x1p-53);
  gl_.Uniform1d(location("slack9"), 1 + 1e-9);
  gl_.Uniform1d(location("slack12"), 1 + 1e-12);
  gl_.Uniform1d(location("allowed_per_coordinate"), closest_point_error_bound(1.0));
  gl_.Uniform1d(location("tiniest"), std::numeric_limits<double>::denorm_min());
  double ring[16];
  for (int i = 0; i < 8; ++i) {
    const double angle = 2 * M_PI * i / 8;  // as surface_roving.cpp's widen_edge()
    ring[2 * i] = std::cos(angle), ring[2 * i + 1] = std::sin(angle);
  }
  gl_.Uniform2dv(location("ring"), 8, ring);
  gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, positions);
  gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, corners);
  gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, buffers_[kOffsets]);
  gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, buffers_[kEntries]);
  const std::size_t chunk = std::min(count, kSamplesPerDispatch);
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[kAnswers]);
  gl_.BufferData(GL_SHADER_STORAGE_BUFFER, chunk * sizeof(ComputedTile), nullptr, GL_STREAM_READ);
  for (std::size_t first = 0; first < count; first += chunk) {
    const std::size_t n = std::min(chunk, count - first);
    gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[kSamples]);
    gl_.BufferData(GL_SHADER_STORAGE_BUFFER, 6 * n * sizeof(double), samples.data() + 6 * first,
                   GL_STREAM_DRAW);
    gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, buffers_[kSamples]);
    gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, buffers_[kAnswers]);
    gl_.Uniform1ui(location("sample_count"), GLuint(n));
    gl_.DispatchCompute(GLuint((n + 63) / 64), 1, 1);
    gl_.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[kAnswers]);
    const void* mapped =
        gl_.MapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, n * sizeof(ComputedTile), GL_MAP_READ_BIT);
    if (!mapped) {
      check_error(gl_, backend_, "mapping the roving compute pass's answers");
      throw Error(fmt::format("gl ({}): mapping the roving compute pass's answers failed", backend_));
    }
    std::memcpy(answers.data() + first, mapped, n * sizeof(ComputedTile));
    gl_.UnmapBuffer(GL_SHADER_STORAGE_BUFFER);
  }
  check_error(gl_, backend_, "the roving compute pass");
}

}  // namespace roving::gl
