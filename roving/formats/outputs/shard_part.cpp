// A shard's part: its layout, read and written (shard_part.h).
#include "roving/formats/outputs/shard_part.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "roving/core/error.h"

namespace roving {
namespace {

constexpr const char* kPartMagic = "roving shard part 1";
constexpr std::size_t kBytesPerSample = 17;       // d (float64), hit (uint8), weight (float64)
constexpr std::size_t kMaxHeaderBytes = 1 << 24;  // the JSON line: models' descriptions and warnings

static_assert(sizeof(double) == 8);

bool little_endian() {
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

static_assert(sizeof(Colour) == 3 * sizeof(float));

std::uint64_t bytes_of(const PartDirection& d) {
  return d.count * (kBytesPerSample + (d.agreement ? sizeof(double) : 0) + (d.colour ? 2 * sizeof(Colour) : 0));
}

void write_array(std::FILE* out, const void* data, std::size_t bytes) {
  if (bytes && std::fwrite(data, 1, bytes, out) != bytes) throw Error("writing the shard's part failed");
}

}  // namespace

void write_part(std::FILE* out, nlohmann::json description, const std::vector<PartColumns>& columns) {
  description["byte_order"] = little_endian() ? "little" : "big";
  const std::string lines = std::string(kPartMagic) + "\n" + description.dump() + "\n";
  write_array(out, lines.data(), lines.size());
  for (const PartColumns& a : columns) {
    const std::size_t count = a.signed_distance->size();
    write_array(out, a.signed_distance->data(), count * sizeof(double));
    write_array(out, a.hit->data(), count);
    write_array(out, a.weights->data(), count * sizeof(double));
    if (a.agreement) write_array(out, a.agreement->data(), a.agreement->size() * sizeof(double));
    for (const std::vector<Colour>* colours : {a.reference_colour, a.test_colour}) {
      if (colours) write_array(out, colours->data(), colours->size() * sizeof(Colour));
    }
  }
}

PartHeader read_part_header(const std::string& path) {
  PartHeader part;
  part.path = path;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("{}: cannot read the file", path));
  std::string magic;
  char c = 0;
  while (magic.size() <= 64 && in.get(c) && c != '\n') magic.push_back(c);
  if (magic != kPartMagic) {
    throw Error(fmt::format("{}: expected a shard's part (written by roving measure --shard-out, first line '{}'), "
                            "found something else",
                            path, kPartMagic));
  }
  std::string line;
  while (line.size() <= kMaxHeaderBytes && in.get(c) && c != '\n') line.push_back(c);
  if (c != '\n' || line.size() > kMaxHeaderBytes) {
    throw Error(fmt::format("{}: the part's description line is truncated or longer than {} bytes", path,
                            kMaxHeaderBytes));
  }
  part.arrays_at = static_cast<std::uint64_t>(in.tellg());
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  std::uintmax_t expected = part.arrays_at;
  try {
    part.description = nlohmann::json::parse(line);
    const nlohmann::json& directions = part.description.at("directions");
    if (!directions.is_array() || directions.empty() || directions.size() > 2) {
      throw Error("its directions are not one or two");
    }
    for (const nlohmann::json& d : directions) {
      const nlohmann::json& samples = d.at("samples");
      PartDirection& direction = part.directions.emplace_back();
      direction.count = samples.at("count").get<std::size_t>();
      direction.first = samples.at("first").get<std::size_t>();
      direction.agreement = d.at("normal_agreement").get<bool>();
      direction.colour = d.at("colour").get<bool>();
      if (direction.count > size / kBytesPerSample) break;  // the size check below says so
      expected += bytes_of(direction);
    }
    if (part.description.at("byte_order").get<std::string>() != "little" || !little_endian()) {
      throw Error("its arrays' byte order is not this machine's");
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("{}: the part's description is not what roving measure --shard-out writes: {}", path,
                            e.what()));
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", path, e.what()));
  }
  if (error || size != expected) {
    throw Error(fmt::format("{}: expected {} bytes (the description, then {} bytes per sample), found {}; the part "
                            "is truncated or damaged: run its shard again",
                            path, expected, kBytesPerSample, size));
  }
  return part;
}

void append_part_arrays(const PartHeader& part, const std::vector<PartArrays>& into) {
  std::ifstream in(part.path, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(part.arrays_at));
  const auto damaged = [&](const char* what, double value) {
    return Error(fmt::format("{}: the part holds {} {}; it is damaged: run its shard again", part.path, what, value));
  };
  for (std::size_t i = 0; i < part.directions.size() && i < into.size(); ++i) {
    const std::size_t count = part.directions[i].count;
    const auto read = [&](auto& values) {
      const std::size_t at = values.size();
      values.resize(at + count);
      if (!in.read(reinterpret_cast<char*>(values.data() + at), static_cast<std::streamsize>(count * sizeof(values[0])))) {
        throw Error(fmt::format("{}: the part ended before its {} samples", part.path, count));
      }
      return at;
    };
    const PartArrays& a = into[i];
    const PartDirection& direction = part.directions[i];
    if ((direction.agreement && !a.agreement) || (direction.colour && !(a.reference_colour && a.test_colour))) {
      throw Error(fmt::format("{}: the part carries per-sample values the other parts do not", part.path));
    }
    for (std::size_t k = read(*a.signed_distance); k < a.signed_distance->size(); ++k) {
      if (!std::isfinite((*a.signed_distance)[k])) throw damaged("the distance", (*a.signed_distance)[k]);
    }
    for (std::size_t k = read(*a.hit); k < a.hit->size(); ++k) {
      if ((*a.hit)[k] > 1) throw damaged("the hit flag", (*a.hit)[k]);
    }
    for (std::size_t k = read(*a.weights); k < a.weights->size(); ++k) {
      const double w = (*a.weights)[k];
      if (!(w >= 0 && std::isfinite(w))) throw damaged("the sample area", w);
    }
    if (direction.agreement) {
      for (std::size_t k = read(*a.agreement); k < a.agreement->size(); ++k) {
        const double value = (*a.agreement)[k];
        if (!(value >= 0 && value <= 1 + 1e-12)) throw damaged("the normal agreement", value);
      }
    }
    if (!direction.colour) continue;
    for (std::vector<Colour>* colours : {a.reference_colour, a.test_colour}) {
      for (std::size_t k = read(*colours); k < colours->size(); ++k) {
        for (const float value : (*colours)[k]) {
          if (!std::isnan(value) && !(value >= 0 && value <= 255)) throw damaged("the colour value", value);
        }
      }
    }
  }
}

}  // namespace roving
