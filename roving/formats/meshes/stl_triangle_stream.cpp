// Binary STL triangles a block at a time (stl_triangle_stream.h).
#include "roving/formats/meshes/stl_triangle_stream.h"

#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <new>
#include <stdexcept>

#include "roving/core/error.h"
#include "roving/core/memory_budget.h"

namespace roving {

std::optional<std::size_t> binary_stl_facets(const std::string& path) {
  struct stat info {};
  if (stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode) || info.st_size < 84) return std::nullopt;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  unsigned char header[84];
  if (!file || std::fread(header, 1, sizeof header, file.get()) != sizeof header) return std::nullopt;
  std::uint32_t count = 0;
  std::memcpy(&count, header + 80, sizeof count);  // little-endian
  if (84 + 50ull * count != static_cast<unsigned long long>(info.st_size)) return std::nullopt;
  return count;
}

// The distinct corners seen, by their bits (as read_stl's merge keys them: float bits, so 0 and -0
// differ), each marked where a kept face uses it. Open addressing with linear probing, 12 bytes a
// slot (an empty slot holds a NaN, which no corner is) and a bit for the mark, at most 80% full;
// in two tables that a bit of the hash splits between them, so that both cores fill one each.
class StlTriangleStream::CornerSet {
 public:
  using Key = std::array<std::uint32_t, 3>;
  // Written out: std::array's == called memcmp here, a tenth of the set's time.
  static bool same(const Key& a, const Key& b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

  CornerSet(const std::string& path, std::size_t expected_vertices) : path_(path) {
    for (Table& table : tables_) table.grow(path, std::max<std::size_t>(1024, expected_vertices * 3 / 4));
  }

  // Adds `count` corners, marking those with `used` set.
  void add(const Key* keys, const unsigned char* used, std::size_t count) {
    hashes_.resize(count);
    for (std::size_t i = 0; i < count; ++i) hashes_[i] = hash(keys[i]);
    tbb::parallel_for(std::size_t{0}, std::size_t{2}, [&](std::size_t part) {
      tables_[part].add(path_, keys, hashes_.data(), used, count, part);
    });
  }

  std::size_t size() const { return tables_[0].size + tables_[1].size; }
  std::size_t unmarked() const { return tables_[0].unmarked() + tables_[1].unmarked(); }

 private:
  static constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;  // a NaN's bits

  static std::uint64_t hash(const Key& k) {
    std::uint64_t h = (std::uint64_t{k[0]} << 32 | k[1]) * 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 29) ^ k[2]) * 0xBF58476D1CE4E5B9ull;
    return h ^ (h >> 32);
  }

  // Empty slots, in 2 MiB pages where the kernel gives them: a probe lands anywhere in hundreds of
  // megabytes, and with 4 KiB pages nearly every one missed the TLB as well as the caches.
  struct Free {
    void operator()(Key* slots) const { std::free(slots); }
  };
  using Slots = std::unique_ptr<Key[], Free>;
  static Slots allocate(std::size_t capacity) {
    constexpr std::size_t kHugePage = std::size_t{2} << 20;
    const std::size_t bytes = (capacity * sizeof(Key) + kHugePage - 1) / kHugePage * kHugePage;
    Slots slots(static_cast<Key*>(std::aligned_alloc(kHugePage, bytes)));
    if (!slots) throw std::bad_alloc();
    madvise(slots.get(), bytes, MADV_HUGEPAGE);  // advice: where refused, 4 KiB pages serve as well
    std::fill(slots.get(), slots.get() + capacity, Key{kEmpty, kEmpty, kEmpty});
    return slots;
  }

  struct Table {
    Slots slots;
    std::vector<bool> marked;
    std::size_t capacity = 0, size = 0;

    // The slot a hash starts from: its high bits (the low one chose the table).
    std::size_t home(std::uint64_t h) const {
      return static_cast<std::size_t>((static_cast<unsigned __int128>(h) * capacity) >> 64);
    }

    // The corners whose hash's low bit is `part`; the slots a few corners ahead are fetched while
    // one is placed (the table is far larger than the caches).
    void add(const std::string& path, const Key* keys, const std::uint64_t* hashes, const unsigned char* used,
             std::size_t count, std::size_t part) {
      constexpr std::size_t kAhead = 16;
      for (std::size_t i = 0; i < count; ++i) {
        if (i + kAhead < count && (hashes[i + kAhead] & 1) == part) __builtin_prefetch(&slots[home(hashes[i + kAhead])]);
        if ((hashes[i] & 1) != part) continue;
        if (size + 1 > capacity / 5 * 4) grow(path, 2 * capacity);
        std::size_t at = home(hashes[i]);
        while (!same(slots[at], keys[i]) && slots[at][0] != kEmpty) at = at + 1 == capacity ? 0 : at + 1;
        if (slots[at][0] == kEmpty) {
          slots[at] = keys[i];
          ++size;
        }
        if (used[i]) marked[at] = true;
      }
    }

    std::size_t unmarked() const {
      std::size_t count = 0;
      for (std::size_t at = 0; at < capacity; ++at) count += slots[at][0] != kEmpty && !marked[at];
      return count;
    }

    void grow(const std::string& path, std::size_t new_capacity) {
      require_memory(fmt::format("{}: counting its vertices", path), 12.125 * new_capacity,
                     fmt::format("a set of {} corners", new_capacity));
      Slots old_slots = allocate(new_capacity);  // fresh until swapped with the table's
      std::vector<bool> old_marked(new_capacity, false);
      std::swap(old_slots, slots);
      old_marked.swap(marked);
      const std::size_t old_capacity = capacity;
      capacity = new_capacity;
      for (std::size_t from = 0; from < old_capacity; ++from) {
        if (old_slots[from][0] == kEmpty) continue;
        std::size_t at = home(hash(old_slots[from]));
        while (slots[at][0] != kEmpty) at = at + 1 == capacity ? 0 : at + 1;
        slots[at] = old_slots[from];
        marked[at] = old_marked[from];
      }
    }
  };

  const std::string& path_;
  Table tables_[2];
  std::vector<std::uint64_t> hashes_;
};

StlTriangleStream::StlTriangleStream(const std::string& path, std::size_t facets)
    : TriangleStream(path, facets), file_(std::fopen(path.c_str(), "rb")) {
  if (!file_) throw Error(fmt::format("{}: cannot open the file", path));
  seen_ = std::make_unique<CornerSet>(path, facets / 2);  // a closed mesh has half as many vertices
}

StlTriangleStream::~StlTriangleStream() = default;

bool StlTriangleStream::next(std::size_t count, std::vector<Triangle>& triangles) {
  triangles.clear();
  corners_.clear();
  if (next_face_ >= face_count_) {
    if (!census_) {
      census_ = VertexCensus{seen_->size(), seen_->unmarked(), referenced_box_};
      seen_.reset();
    }
    return false;
  }
  // A block's corners are numbered 0 to 3 count - 1: a triangle's numbers must fit an int.
  count = std::min({count, face_count_ - next_face_, std::size_t{std::numeric_limits<int>::max() / 3}});
  buffer_.resize(50 * count);
  const std::uint64_t offset = 84 + 50ull * next_face_;
  if (fseeko(file_.get(), static_cast<off_t>(offset), SEEK_SET) != 0 ||
      std::fread(buffer_.data(), 1, buffer_.size(), file_.get()) != buffer_.size()) {
    throw Error(fmt::format("{}: could not read {} bytes at byte {}; the file changed or cannot be read", path_,
                            buffer_.size(), offset));
  }
  std::vector<CornerSet::Key> keys;
  std::vector<unsigned char> used;  // not vector<bool>: add() reads it as an array
  if (!census_) {
    keys.resize(3 * count);
    used.resize(3 * count);
  }
  triangles.reserve(count);
  corners_.reserve(3 * count);
  for (std::size_t i = 0; i < count; ++i) {
    const char* record = buffer_.data() + 50 * i + 12;  // after the facet normal
    CornerSet::Key bits[3];
    std::memcpy(bits, record, sizeof bits);
    float xyz[3][3];
    std::memcpy(xyz, record, sizeof xyz);
    for (int c = 0; c < 3; ++c) {
      if (!(std::isfinite(xyz[c][0]) && std::isfinite(xyz[c][1]) && std::isfinite(xyz[c][2]))) {
        throw Error(fmt::format("{}: facet {} corner {} has a non-finite coordinate ({}, {}, {}); expected finite "
                                "numbers",
                                path_, next_face_ + i, c, xyz[c][0], xyz[c][1], xyz[c][2]));
      }
    }
    const bool repeats = CornerSet::same(bits[0], bits[1]) || CornerSet::same(bits[1], bits[2]) ||
                         CornerSet::same(bits[0], bits[2]);
    if (!census_) {
      std::copy(bits, bits + 3, &keys[3 * i]);
      std::fill(&used[3 * i], &used[3 * i] + 3, !repeats);
    }
    if (repeats) {
      ++dropped_;
      continue;
    }
    const int first = static_cast<int>(corners_.size());
    for (int c = 0; c < 3; ++c) {
      corners_.emplace_back(xyz[c][0], xyz[c][1], xyz[c][2]);
      if (!census_) referenced_box_.extend(corners_.back());
    }
    triangles.push_back({first, first + 1, first + 2});
  }
  if (!census_) seen_->add(keys.data(), used.data(), keys.size());
  next_face_ += count;
  return true;
}

VertexCensus StlTriangleStream::census() const {
  if (!census_) throw std::logic_error("StlTriangleStream::census before a whole pass");
  return *census_;
}

}  // namespace roving
