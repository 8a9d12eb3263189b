// Which of a geom pair's contact candidates share a triangle vertex: the adjacency the contact
// manifold grows its patches through (contact_manifold.h). Candidate i is the intersecting pair of
// geom1's triangle with welded vertex ids vertices_a[i] and geom2's with vertices_b[i]
// (mesh_features.h, weld_vertex_ids); two candidates are adjacent when their triangles share a
// vertex id on either geom.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "graspcd/core/mesh_features.h"

namespace graspcd {

// Each vertex, side << 31 | id (side 0: geom1, side 1: geom2), has a slot, which heads the list of
// the candidates' vertex entries on it: entry 6 * i + k is candidate i's corner k on geom1 (k < 3)
// or corner k - 3 on geom2. A list runs from the last entry added to the first. When every id is
// below kDirectIds (welded ids count a mesh's vertices), a vertex finds its slot in a table
// indexed by id, stamped with the build that last gave it one (no table is cleared between
// builds), and slots are numbered in the order their vertices are first met; beyond, in an
// open-addressing hash table (linear probing). The buffers are kept from one build to the next, so
// that a warm index allocates nothing.
class AdjacencyIndex {
 public:
  // Indexes the candidates' vertices, replacing what was indexed before. Preconditions:
  // vertices_a and vertices_b are of one length n, with 6 n below 2^32 (entries are 32-bit), and
  // every id is below 2^31 (the side takes the top bit).
  void build(const std::vector<FaceVertexIds>& vertices_a,
             const std::vector<FaceVertexIds>& vertices_b);

  // Ids below this index their slots directly (the table grows to the largest id met).
  static constexpr std::uint32_t kDirectIds = std::uint32_t{1} << 20;

  // The number of slots (the distinct vertices, or the hash table's size: a power of two, at
  // least 16 and at least 6 n); slots are 0 .. count - 1.
  std::size_t slot_count() const { return slots_; }

  // The slot of candidate i's vertex k (k < 3: geom1's corner k, else geom2's corner k - 3).
  std::uint32_t slot(std::size_t i, std::size_t k) const { return slot_of_[6 * i + k]; }

  // Calls visit(i) for the candidate i of every entry on the slot's vertex, the last entry added
  // first (a candidate with a degenerate triangle may come twice).
  template <typename Visit>
  void for_each_candidate(std::uint32_t slot, Visit&& visit) const {
    for (std::uint32_t e = head_[slot]; e != kNone; e = next_[e]) visit(std::size_t{e / 6});
  }

 private:
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};

  void add(std::uint32_t key, std::size_t entry);

  int bits_ = 4;                        // log2 of the hash table's slot count
  std::vector<std::uint32_t> key_;      // slot -> its vertex (meaningful where head_ is not kNone)
  std::size_t slots_ = 0;               // slot_count()
  std::vector<std::uint32_t> head_;     // slot -> its vertex's last entry, kNone: empty slot
  std::vector<std::uint32_t> slot_of_;  // entry -> its vertex's slot
  std::vector<std::uint32_t> next_;     // entry -> the previous entry on its vertex, or kNone
  // The direct tables, per side: id -> the stamp of the build that gave the vertex its slot, and
  // that slot.
  struct Seen {
    std::uint32_t stamp = 0;
    std::uint32_t slot = 0;
  };
  std::vector<Seen> seen_[2];
  std::uint32_t stamp_ = 0;  // this build's (0: never given)
};

}  // namespace graspcd
