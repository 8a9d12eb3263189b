#include "graspcd/core/adjacency_index.h"

namespace graspcd {

void AdjacencyIndex::build(const std::vector<FaceVertexIds>& vertices_a,
                           const std::vector<FaceVertexIds>& vertices_b) {
  const std::size_t n = vertices_a.size();
  const std::size_t entries = 6 * n;
  std::size_t table_size = 16;
  bits_ = 4;
  while (table_size < entries) {
    table_size <<= 1;
    ++bits_;
  }
  key_.resize(table_size);
  head_.assign(table_size, kNone);
  slot_of_.resize(entries);
  next_.resize(entries);
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
