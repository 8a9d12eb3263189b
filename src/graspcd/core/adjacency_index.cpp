#include "graspcd/core/adjacency_index.h"

namespace graspcd {

void AdjacencyIndex::build(const std::vector<FaceVertexIds>& vertices_a,
                           const std::vector<FaceVertexIds>& vertices_b) {
  const std::size_t n = vertices_a.size();
  const std::size_t entries = 6 * n;
  slot_of_.resize(entries);
  next_.resize(entries);
  // Every id of a side is at most the OR of them all.
  std::uint32_t any[2] = {0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      any[0] |= vertices_a[i][k];
      any[1] |= vertices_b[i][k];
    }
  }
  if (any[0] < kDirectIds && any[1] < kDirectIds) {
    for (std::size_t side = 0; side < 2; ++side) {
      if (seen_[side].size() <= any[side]) seen_[side].resize(std::size_t{any[side]} + 1);
    }
    if (++stamp_ == 0) {  // the stamps wrapped: forget them all
      for (std::vector<Seen>& seen : seen_) seen.assign(seen.size(), Seen{});
      stamp_ = 1;
    }
    if (head_.size() < entries) head_.resize(entries);
    std::uint32_t* const head = head_.data();
    std::uint32_t* const next = next_.data();
    std::uint32_t* const slot_of = slot_of_.data();
    Seen* const seen_sides[2] = {seen_[0].data(), seen_[1].data()};
    const std::uint32_t stamp = stamp_;
    std::uint32_t slots = 0;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < 6; ++k) {
        const std::uint32_t id = k < 3 ? vertices_a[i][k] : vertices_b[i][k - 3];
        Seen& seen = seen_sides[k < 3 ? 0 : 1][id];
        if (seen.stamp != stamp) {
          seen.stamp = stamp;
          seen.slot = slots;
          head[slots++] = kNone;
        }
        const std::size_t entry = 6 * i + k;
        next[entry] = head[seen.slot];
        head[seen.slot] = static_cast<std::uint32_t>(entry);
        slot_of[entry] = seen.slot;
      }
    }
    slots_ = slots;
    return;
  }
  std::size_t table_size = 16;
  bits_ = 4;
  while (table_size < entries) {
    table_size <<= 1;
    ++bits_;
  }
  key_.resize(table_size);
  head_.assign(table_size, kNone);
  slots_ = table_size;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      add(vertices_a[i][k], 6 * i + k);
      add(std::uint32_t{1} << 31 | vertices_b[i][k], 6 * i + 3 + k);
    }
  }
}

// Fibonacci hashing (the key times 2^64 over the golden ratio, its top bits), then linear probing
// to the key's slot or the first empty one.
void AdjacencyIndex::add(std::uint32_t key, std::size_t entry) {
  const std::size_t mask = key_.size() - 1;
  std::size_t h = (std::uint64_t{key} * 0x9E3779B97F4A7C15ull) >> (64 - bits_);
  while (head_[h] != kNone && key_[h] != key) h = (h + 1) & mask;
  key_[h] = key;
  next_[entry] = head_[h];
  head_[h] = static_cast<std::uint32_t>(entry);
  slot_of_[entry] = static_cast<std::uint32_t>(h);
}

}  // namespace graspcd
