// The table of distance methods by name.
#include "roving/registry/method_registry.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <functional>
#include <utility>

#include "roving/reference_cgal/cgal_reference.h"
#include "roving/reference_embree/embree_reference.h"
#include "roving/core/error.h"

namespace roving {
namespace {

using Factory = std::function<std::unique_ptr<DistanceMethod>(const GlMethodOptions&)>;

const std::vector<std::pair<std::string, Factory>>& registry() {
  static const std::vector<std::pair<std::string, Factory>> methods = {
      {"embree", [](const GlMethodOptions&) { return make_embree_reference(); }},
      {"cgal", [](const GlMethodOptions&) { return make_cgal_reference(); }},
      {"v2v-naive", [](const GlMethodOptions&) { return make_vertex_to_vertex(Search::Naive); }},
      {"v2v-kdtree", [](const GlMethodOptions&) { return make_vertex_to_vertex(Search::Accelerated); }},
      {"v2p-naive", [](const GlMethodOptions&) { return make_vertex_to_plane(Search::Naive); }},
      {"v2p-aabb", [](const GlMethodOptions&) { return make_vertex_to_plane(Search::Accelerated); }},
      {"roving", [](const GlMethodOptions& gl) { return make_surface_roving(gl); }},
      {"viewpoint", [](const GlMethodOptions& gl) { return make_viewpoint_sampling(gl); }},
      {"cooperative", [](const GlMethodOptions& gl) { return make_cooperative(gl); }},
  };
  return methods;
}

}  // namespace

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : registry()) names.push_back(name);
  return names;
}

bool is_gl_method(const std::string& name) {
  return name == "roving" || name == "viewpoint" || name == "cooperative";
}

std::unique_ptr<DistanceMethod> make_method(const std::string& name, const GlMethodOptions& gl) {
  for (const auto& [known, factory] : registry()) {
    if (known == name) return factory(gl);
  }
  throw Error(fmt::format("--method: expected one of {}, found '{}'", fmt::join(method_names(), ", "), name));
}

}  // namespace roving
