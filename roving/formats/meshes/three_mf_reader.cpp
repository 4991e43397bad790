// 3MF through assimp, in a child process. Under fuzzing Debian's assimp aborts on a corrupt zip
// entry (an ai_assert in its ZipArchiveIOSystem) and its other importers overflowed buffers, so
// it runs where a crash, an abort, a hang or a runaway allocation cannot take the caller with
// it: the child sends back the triangles or assimp's error through a pipe, and anything else
// becomes a one-line error naming the file. Only the 3MF importer stays registered (assimp
// otherwise hands a file its importer refuses to every other one it has); its post-processing
// bakes every build item's transform into the vertices and splits polygons into triangles.
#include "roving/formats/meshes/three_mf_reader.h"

#include <assimp/BaseImporter.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <assimp/Importer.hpp>
#include <csignal>
#include <cstring>

#include "roving/core/error.h"
#include "roving/core/memory_budget.h"
#include "roving/formats/files/file_bytes.h"

#if defined(__SANITIZE_ADDRESS__)
#define ROVING_ADDRESS_SANITIZER
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ROVING_ADDRESS_SANITIZER
#endif
#endif

// Present in sanitizer builds only (weak): the fuzzer's hook, which must not run in the child.
extern "C" void __sanitizer_set_death_callback(void (*callback)()) __attribute__((weak));

namespace roving {
namespace {

// What the child sends: 'E' and assimp's message, or 'M', three counts (vertices, triangles,
// faces dropped for a repeated vertex) and the arrays.
std::string import_with_assimp(const std::string& path) {
  Assimp::Importer importer;
  const std::size_t keep = importer.GetImporterIndex(".3mf");
  std::vector<Assimp::BaseImporter*> others;
  for (std::size_t i = 0; i < importer.GetImporterCount(); ++i) {
    if (i != keep) others.push_back(importer.GetImporter(i));
  }
  for (Assimp::BaseImporter* other : others) importer.UnregisterLoader(other);
  // Nothing but geometry: no normals, materials, animations or cameras are made or kept.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                              aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
                                  aiComponent_TEXCOORDS | aiComponent_ANIMATIONS | aiComponent_LIGHTS |
                                  aiComponent_CAMERAS | aiComponent_MATERIALS);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(path, aiProcess_RemoveComponent | aiProcess_Triangulate |
                                                     aiProcess_SortByPType | aiProcess_PreTransformVertices);
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    return "E" + std::string(importer.GetErrorString());
  std::vector<double> positions;
  std::vector<std::int32_t> corners;
  std::uint64_t dropped = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    const std::size_t base = positions.size() / 3;
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      positions.insert(positions.end(), {mesh.mVertices[v].x, mesh.mVertices[v].y, mesh.mVertices[v].z});
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // left by a mesh of mixed primitives
      const unsigned* i = face.mIndices;
      if (i[0] >= mesh.mNumVertices || i[1] >= mesh.mNumVertices || i[2] >= mesh.mNumVertices) {
        return fmt::format("Emesh {} face {} refers to a vertex past its {}", m, f, mesh.mNumVertices);
      }
      if (i[0] == i[1] || i[1] == i[2] || i[0] == i[2]) {
        ++dropped;
        continue;
      }
      for (int c = 0; c < 3; ++c) corners.push_back(static_cast<std::int32_t>(base + i[c]));
    }
  }
  const std::uint64_t counts[3] = {positions.size() / 3, corners.size() / 3, dropped};
  std::string out = "M";
  out.append(reinterpret_cast<const char*>(counts), sizeof counts);
  out.append(reinterpret_cast<const char*>(positions.data()), positions.size() * sizeof(double));
  out.append(reinterpret_cast<const char*>(corners.data()), corners.size() * sizeof(std::int32_t));
  return out;
}

void write_all(int fd, const std::string& bytes) {
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

}  // namespace

LoadedMesh read_3mf(const std::string& path) {
  { const FileBytes bytes(path, "a 3MF mesh"); }  // the shared checks: missing, a directory, empty
  const auto fail = [&](const std::string& why) {
    return Error(fmt::format("{}: cannot read it as .3mf ({})", path, why));
  };
  int pipe_ends[2];
  if (::pipe(pipe_ends) != 0)
    throw fail(fmt::format("no pipe to a reader process: {}", std::strerror(errno)));
  const pid_t child = ::fork();
  if (child < 0) throw fail(fmt::format("no reader process: {}", std::strerror(errno)));
  if (child == 0) {
    ::close(pipe_ends[0]);
    // The child dies quietly of what it meets: default signal actions (not a fuzzer's or a
    // sanitizer's handlers, inherited from the parent), and assimp's own messages unseen.
    for (int signal : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) std::signal(signal, SIG_DFL);
    if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(nullptr);
    if (const int null = ::open("/dev/null", O_WRONLY); null >= 0) ::dup2(null, STDERR_FILENO);
    const rlimit cpu{60, 60};  // seconds: a hang ends here
    ::setrlimit(RLIMIT_CPU, &cpu);
#ifndef ROVING_ADDRESS_SANITIZER  // its allocator maps more data than any limit would allow
    const rlim_t memory = available_memory();
    const rlimit data{memory, memory};
    ::setrlimit(RLIMIT_DATA, &data);
#endif
    std::string reply;
    try {
      reply = import_with_assimp(path);
    } catch (const std::exception& e) {
      reply = std::string("E") + e.what();
    }
    write_all(pipe_ends[1], reply);
    ::_exit(0);  // no destructors or exit handlers of the parent's run in the child
  }
  ::close(pipe_ends[1]);
  std::string reply;
  char chunk[1 << 16];
  for (ssize_t n; (n = ::read(pipe_ends[0], chunk, sizeof chunk)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    reply.append(chunk, static_cast<std::size_t>(n));
  }
  ::close(pipe_ends[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    throw fail(fmt::format("assimp's importer died of signal {}, {}", WTERMSIG(status),
                           strsignal(WTERMSIG(status))));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || reply.empty()) {
    throw fail("assimp's importer ended without an answer");
  }
  if (reply[0] == 'E') {
    if (reply.find("No meshes remaining") != std::string::npos) {
      throw Error(fmt::format(
          "{}: no faces found (its meshes hold only points or lines); expected a triangle mesh", path));
    }
    throw fail(reply.substr(1));
  }
  std::uint64_t counts[3] = {0, 0, 0};
  if (reply.size() < 1 + sizeof counts) throw fail("a truncated answer from assimp's importer");
  std::memcpy(counts, reply.data() + 1, sizeof counts);
  const std::size_t expected =
      1 + sizeof counts + counts[0] * 3 * sizeof(double) + counts[1] * 3 * sizeof(std::int32_t);
  if (reply.size() != expected) throw fail("a truncated answer from assimp's importer");
  const char* at = reply.data() + 1 + sizeof counts;
  std::vector<Vec3> positions(counts[0]);
  for (Vec3& p : positions) {
    double xyz[3];
    std::memcpy(xyz, at, sizeof xyz);
    at += sizeof xyz;
    p = Vec3(xyz[0], xyz[1], xyz[2]);
  }
  std::vector<Triangle> triangles(counts[1]);
  for (Triangle& t : triangles) {
    std::memcpy(t.data(), at, 3 * sizeof(std::int32_t));
    at += 3 * sizeof(std::int32_t);
  }
  LoadedMesh loaded;
  loaded.path = path;
  loaded.dropped_repeated_vertex_faces = counts[2];
  loaded.mesh =
      TriangleMesh(std::move(positions), std::move(triangles), path);  // checks indices and coordinates
  return loaded;
}

}  // namespace roving
