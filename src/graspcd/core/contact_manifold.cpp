#include "graspcd/core/contact_manifold.h"

#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "graspcd/core/adjacency_index.h"
#include "graspcd/core/tolerances.h"

namespace graspcd {
namespace {

using Point2 = std::array<double, 2>;

double cross2(const Point2& o, const Point2& a, const Point2& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// The convex hull of `pts` into `hull`, counter-clockwise, each corner once (Andrew's monotone
// chain, 1979); collinear points give the segment's two ends. Sorts `pts` in place.
void convex_hull(std::vector<Point2>& pts, std::vector<Point2>& hull) {
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  hull.assign(2 * pts.size() + 1, Point2{});
  if (pts.size() < 3) {
    hull.assign(pts.begin(), pts.end());
    return;
  }
  std::size_t k = 0;
  for (const Point2& p : pts) {  // lower hull
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
    while (k >= lower && cross2(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
}

// The area of a convex polygon (shoelace); 0 for a point or a segment.
double polygon_area(const std::vector<Point2>& h) {
  double twice = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const Point2& a = h[i];
    const Point2& b = h[(i + 1) % h.size()];
    twice += a[0] * b[1] - b[0] * a[1];
  }
  return 0.5 * std::abs(twice);
}

// How much adding x enlarges the convex polygon h (counter-clockwise, or a segment taken as its
// two directed edges): the triangles from x to the edges it sees, which lie outside h. The edges
// come as HullEdge (hull_edges), each the start o and the difference to the next corner, so that
// the cross product (a - o) x (x - o) of cross2 reuses a - o.
struct HullEdge {
  Point2 o, d;
};

void hull_edges(const std::vector<Point2>& h, std::vector<HullEdge>& edges) {
  edges.clear();
  if (h.size() < 2) return;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const Point2& o = h[i];
    const Point2& a = h[i + 1 == h.size() ? 0 : i + 1];
    edges.push_back({o, {a[0] - o[0], a[1] - o[1]}});
  }
}

double hull_gain(const std::vector<HullEdge>& edges, const Point2& x) {
  double twice = 0;
  for (const HullEdge& e : edges) {
    const double c = e.d[0] * (x[1] - e.o[1]) - e.d[1] * (x[0] - e.o[0]);
    if (c < 0) twice -= c;
  }
  return 0.5 * twice;
}

double squared_distance(const Point2& a, const Point2& b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1];
  return dx * dx + dy * dy;
}

// The member not taken yet that most enlarges the convex hull `hull` of the chosen points (`edges`
// its edges, rebuilt here), or `count` when none enlarges it by more than tol::kManifoldFlatArea
// times `extent2` (collinear points). Members are deepest first, so the strict > keeps ties
// deepest.
std::size_t largest_hull_gain(const std::vector<Point2>& q, std::size_t count,
                              const std::vector<char>& taken, const std::vector<Point2>& hull,
                              double extent2, std::vector<HullEdge>& edges) {
  hull_edges(hull, edges);
  std::size_t best = count;
  double best_gain = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (taken[i]) continue;
    const double gain = hull_gain(edges, q[i]);
    if (gain > best_gain) {
      best_gain = gain;
      best = i;
    }
  }
  return best_gain <= tol::kManifoldFlatArea * extent2 ? count : best;
}

// The member not taken yet farthest from the chosen ones (the deeper on ties), or `count` when
// every other member sits on a chosen point.
std::size_t farthest_from_chosen(const std::vector<Point2>& q, std::size_t count,
                                 const std::vector<char>& taken,
                                 const std::vector<std::size_t>& chosen) {
  std::size_t best = count;
  double best_d2 = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (taken[i]) continue;
    double d2 = std::numeric_limits<double>::infinity();
    for (std::size_t c : chosen) d2 = std::min(d2, squared_distance(q[i], q[c]));
    if (d2 > best_d2) {
      best_d2 = d2;
      best = i;
    }
  }
  return best;
}

// Chooses at most `k` of a patch's `count` members (deepest first; q their positions in the patch
// plane) by the rule of build_contact_manifold, step 2: their positions in the members into
// `chosen`, in choice order, and the convex hull of the chosen points (convex_hull's) into `hull`.
void choose_patch_points(std::size_t count, const std::vector<Point2>& q, std::size_t k,
                         std::vector<std::size_t>& chosen, std::vector<Point2>& hull) {
  chosen.clear();
  hull.clear();
  if (count == 0 || k == 0) return;
  chosen.push_back(0);
  thread_local std::vector<char> taken;
  taken.assign(count, 0);
  taken[0] = 1;
  double extent2 = 0;  // squared largest distance from the deepest point: the patch's scale
  for (std::size_t i = 1; i < count; ++i) extent2 = std::max(extent2, squared_distance(q[i], q[0]));
  thread_local std::vector<Point2> sorted;
  thread_local std::vector<HullEdge> edges;
  hull.push_back(q[0]);
  while (chosen.size() < k) {
    // The largest hull-area gain; for the second point, or collinear points, the member farthest
    // from the chosen ones.
    std::size_t best =
        chosen.size() >= 2 ? largest_hull_gain(q, count, taken, hull, extent2, edges) : count;
    if (best == count) best = farthest_from_chosen(q, count, taken, chosen);
    if (best == count) break;  // every other member sits on a chosen point
    taken[best] = 1;
    chosen.push_back(best);
    sorted.clear();
    for (std::size_t c : chosen) sorted.push_back(q[c]);
    convex_hull(sorted, hull);
  }
}

// A key that orders doubles as < does (-0.0 and 0.0 alike), NaNs included (beyond the
// infinities), so that a sort by it is well defined whatever the values.
std::uint64_t order_key(double x) {
  x += 0.0;  // -0.0 -> 0.0
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return bits >> 63 ? ~bits : bits | std::uint64_t{1} << 63;
}

struct KeyIndex {
  std::uint64_t key;
  std::uint32_t index;
};

// The larger key first, ties by index: the order a stable sort by the value, descending, gives.
bool larger_key_first(const KeyIndex& a, const KeyIndex& b) {
  return a.key > b.key || (a.key == b.key && a.index < b.index);
}

// Sorts [first, last) by `before` keeping ties in order, as std::stable_sort does, without its
// buffer for the few elements it mostly gets (insertion sort; std::stable_sort beyond 16).
template <typename It, typename Before>
void small_stable_sort(It first, It last, Before before) {
  if (last - first > 16) {
    std::stable_sort(first, last, before);
    return;
  }
  for (It i = first; i != last; ++i) {
    for (It j = i; j != first && before(*j, *(j - 1)); --j) std::iter_swap(j, j - 1);
  }
}

// ---- The steps of build_contact_manifold_by_ids

// Throws std::invalid_argument, naming the lengths, unless `a` and `b` (named `name_a` and
// `name_b`, arguments of `function`) each hold one entry per candidate.
void check_one_per_candidate(const char* function, std::size_t candidates, const char* name_a,
                             std::size_t a, const char* name_b, std::size_t b) {
  if (a == candidates && b == candidates) return;
  throw std::invalid_argument(std::string(function) + ": " + std::to_string(a) + " " + name_a +
                              " and " + std::to_string(b) + " " + name_b + " for " +
                              std::to_string(candidates) + " candidates");
}

// Throws std::length_error for a vertex id of 2^31 or more (AdjacencyIndex's precondition).
void check_vertex_ids(const std::vector<FaceVertexIds>& vertices_a,
                      const std::vector<FaceVertexIds>& vertices_b) {
  std::uint32_t any = 0;  // the OR of every id: its top bit is set when any id's is
  for (std::size_t i = 0; i < vertices_a.size(); ++i) {
    for (std::size_t k = 0; k < 3; ++k) any |= vertices_a[i][k] | vertices_b[i][k];
  }
  if (any >> 31) throw std::length_error("build_contact_manifold_by_ids: a vertex id beyond 2^31");
}

// The candidates deepest first, ties in the given order: sorted by depth, then index, the order a
// stable sort by depth gives.
void sort_deepest_first(const std::vector<TriContact>& candidates, std::vector<KeyIndex>& order) {
  order.resize(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    order[i] = {order_key(candidates[i].depth), static_cast<std::uint32_t>(i)};
  }
  std::sort(order.begin(), order.end(), larger_key_first);
}

// Step 1: patches grown breadth-first through `adjacency`, each from the deepest unassigned
// candidate (`order`: deepest first), into `patches`, their members in the order found. (The
// patches depend on which candidates share a vertex, not on the order they are found in: a patch
// is the seed's connected component, and its members are sorted in step 2.)
void grow_patches(const std::vector<TriContact>& candidates, const std::vector<KeyIndex>& order,
                  const AdjacencyIndex& adjacency, double patch_cosine,
                  std::vector<ContactPatch>& patches) {
  std::size_t count = 0;  // patches grown: patches[0 .. count - 1], the rest an earlier build's
  thread_local std::vector<int> patch_of;
  patch_of.assign(candidates.size(), -1);
  thread_local std::vector<std::size_t> queue;
  thread_local std::vector<int> slot_scanned;  // the last patch that scanned the vertex's list
  slot_scanned.assign(adjacency.slot_count(), -1);
  for (const KeyIndex& by_depth : order) {
    const std::size_t seed = by_depth.index;
    if (patch_of[seed] >= 0) continue;
    const int id = static_cast<int>(count);
    const Vec3& seed_normal = candidates[seed].normal;
    patch_of[seed] = id;
    queue.assign(1, seed);
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::size_t i = queue[head];
      for (std::size_t k = 0; k < 6; ++k) {
        // A vertex scanned once for this patch needs no second scan: whom it admits depends only
        // on the seed's normal.
        const std::uint32_t h = adjacency.slot(i, k);
        if (slot_scanned[h] == id) continue;
        slot_scanned[h] = id;
        adjacency.for_each_candidate(h, [&](std::size_t j) {
          if (patch_of[j] >= 0 || candidates[j].normal.dot(seed_normal) < patch_cosine) return;
          patch_of[j] = id;
          queue.push_back(j);
        });
      }
    }
    // A patch of an earlier build keeps its buffers.
    if (static_cast<std::size_t>(id) == patches.size()) patches.emplace_back();
    ContactPatch& patch = patches[static_cast<std::size_t>(id)];
    patch.members.assign(queue.begin(), queue.end());
    patch.selected.clear();
    patch.depth = 0;
    patch.area = 0;
    // The patch normal: the seed's, the penetration direction at the deepest point. (A mean over
    // the members mixes in the edge directions of the patch's rim; on a cube resting on a cube
    // their tilt of 0.1 degree made the cube creep 7 mm in 1.5 s.)
    patch.normal = seed_normal;
    ++count;
  }
  patches.resize(count);
}

// Two unit axes spanning the plane across the unit `normal`: u across normal and the coordinate
// axis least aligned with it, w = normal x u.
struct PlaneAxes {
  Vec3 u, w;
};

PlaneAxes plane_axes(const Vec3& nrm) {
  Vec3 axis = Vec3::Zero();
  axis[std::abs(nrm[0]) <= std::abs(nrm[1]) ? (std::abs(nrm[0]) <= std::abs(nrm[2]) ? 0 : 2)
                                            : (std::abs(nrm[1]) <= std::abs(nrm[2]) ? 1 : 2)] = 1;
  const Vec3 u = nrm.cross(axis).normalized();
  const Vec3 w = nrm.cross(u);
  return {u, w};
}

// Step 2 for one patch: its members' depths along its normal into `along` (indexed by candidate),
// the members sorted by that depth (deepest first, ties by index), the patch's depth, and its
// points chosen in the plane across its normal (choose_patch_points) with their hull's area.
void choose_points(const std::vector<TriContact>& candidates, std::size_t per_patch,
                   ContactPatch& patch, std::vector<double>& along) {
  thread_local std::vector<std::uint64_t> along_key;  // order_key(along)
  along_key.resize(candidates.size());
  for (std::size_t i : patch.members) {
    along[i] = candidates[i].depth * std::clamp(candidates[i].normal.dot(patch.normal), 0.0, 1.0);
  }
  for (std::size_t i : patch.members) along_key[i] = order_key(along[i]);
  std::sort(patch.members.begin(), patch.members.end(), [&](std::size_t a, std::size_t b) {
    return along_key[a] > along_key[b] || (along_key[a] == along_key[b] && a < b);
  });
  patch.depth = along[patch.members.front()];
  const PlaneAxes axes = plane_axes(patch.normal);
  thread_local std::vector<Point2> q, hull;
  thread_local std::vector<std::size_t> chosen;
  q.clear();
  for (std::size_t i : patch.members) {
    q.push_back({candidates[i].pos.dot(axes.u), candidates[i].pos.dot(axes.w)});
  }
  choose_patch_points(patch.members.size(), q, per_patch, chosen, hull);
  patch.selected.reserve(chosen.size());
  for (std::size_t pos : chosen) patch.selected.push_back(patch.members[pos]);
  patch.area = polygon_area(hull);
}

// The indices of the first `count` patches, the largest area first (ties in patch order): the
// order in which the pair's budget hands out a patch's further points (step 3).
void patches_by_area(const std::vector<ContactPatch>& patches, std::size_t count,
                     std::vector<std::size_t>& by_area) {
  by_area.clear();
  for (std::size_t p = 0; p < count; ++p) by_area.push_back(p);
  small_stable_sort(by_area.begin(), by_area.end(), [&](std::size_t a, std::size_t b) {
    return patches[a].area > patches[b].area;
  });
}

// Step 3: the pair's budget of `per_pair` points into `contacts` (ContactManifold::contacts), from
// `patches` sorted deepest first: every patch's deepest point, then the further points by patch
// area. Each point has its patch's normal and its depth along it (`along`).
void spend_pair_budget(const std::vector<TriContact>& candidates,
                       const std::vector<ContactPatch>& patches, const std::vector<double>& along,
                       std::size_t per_pair, ContactManifold& out) {
  const auto emit = [&](std::size_t p, std::size_t i) {
    out.contacts.push_back(TriContact{candidates[i].pos, patches[p].normal, along[i]});
    out.contact_patch.push_back(p);
  };
  out.contacts.reserve(std::min(per_pair, candidates.size()));
  for (std::size_t p = 0; p < patches.size(); ++p) {
    if (out.contacts.size() == per_pair) break;
    emit(p, patches[p].selected.front());
  }
  thread_local std::vector<std::size_t> by_area;
  patches_by_area(patches, patches.size(), by_area);
  for (std::size_t p : by_area) {
    for (std::size_t k = 1; k < patches[p].selected.size() && out.contacts.size() < per_pair; ++k) {
      emit(p, patches[p].selected[k]);
    }
  }
}

// How many points step 3 gives each patch (`patches` deepest first) from a budget of `per_pair`:
// one to each patch in order, then the further selected points by patch area.
void patch_shares(const std::vector<ContactPatch>& patches, std::size_t per_pair,
                  std::vector<std::size_t>& shares) {
  shares.assign(patches.size(), 0);
  std::size_t used = 0;
  for (std::size_t p = 0; p < patches.size() && used < per_pair; ++p) {
    shares[p] = 1;
    ++used;
  }
  thread_local std::vector<std::size_t> by_area;
  patches_by_area(patches, patches.size(), by_area);
  for (std::size_t p : by_area) {
    if (shares[p] == 0) continue;
    const std::size_t more = std::min(patches[p].selected.size() - 1, per_pair - used);
    shares[p] += more;
    used += more;
  }
}

// ---- Moment reduction (build_contact_manifold, "Moment reduction")

// A patch's proxy of its normal force: the net direction N, the size |F|, the centre of pressure c,
// the central-axis point c* = c + N x M / |F| and the anchor's depth (the mean penetration).
struct PatchWrench {
  Vec3 normal = Vec3::UnitZ();
  Vec3 centre = Vec3::Zero();
  Vec3 axis_point = Vec3::Zero();
  double anchor_depth = 0;
};

PatchWrench patch_wrench(const std::vector<TriContact>& candidates, const ContactPatch& patch,
                         const std::vector<double>& along) {
  double total = 0;
  for (std::size_t i : patch.members) total += along[i];
  const bool uniform = !(total > 0);  // every member only touches: all weights 1
  const auto weight = [&](std::size_t i) { return uniform ? 1.0 : along[i]; };
  Vec3 force = Vec3::Zero();
  Vec3 moment_sum = Vec3::Zero();
  double w_sum = 0;
  double depth_sum = 0;
  for (std::size_t i : patch.members) {
    const double w = weight(i);
    force += w * candidates[i].normal;
    moment_sum += w * candidates[i].pos;
    w_sum += w;
    depth_sum += w * along[i];
  }
  PatchWrench out;
  out.centre = moment_sum / w_sum;
  Vec3 moment = Vec3::Zero();
  for (std::size_t i : patch.members) {
    moment += weight(i) * (candidates[i].pos - out.centre).cross(candidates[i].normal);
  }
  const double size = force.norm();
  const bool has_direction = size > 0 && std::isfinite(size);
  out.normal = has_direction ? Vec3(force / size) : patch.normal;
  out.axis_point = has_direction ? Vec3(out.centre + out.normal.cross(moment) / size) : out.centre;
  out.anchor_depth = depth_sum / w_sum;
  return out;
}

// The points of one patch under the moment reduction: the anchor into `anchor` and the patch's
// first `extremes` selected members (choose_points) into `out`, every one with the wrench's
// normal, their depths fitted as build_contact_manifold describes ("Moment reduction").
void fit_patch_points(const std::vector<TriContact>& candidates, const ContactPatch& patch,
                      const PatchWrench& wrench, std::size_t extremes, TriContact& anchor,
                      std::vector<TriContact>& out) {
  const Vec3& nrm = wrench.normal;
  const PlaneAxes axes = plane_axes(nrm);
  const std::size_t first = out.size();
  thread_local std::vector<Point2> offset;  // each extreme's position from c*, across N
  offset.clear();
  Point2 rhs{0, 0};  // minus the extremes' depth-weighted offsets: what the change must make
  double g00 = 0, g01 = 0, g11 = 0;  // the Gram matrix of the offsets
  for (std::size_t k = 0; k < extremes; ++k) {
    const TriContact& c = candidates[patch.selected[k]];
    const double depth = c.depth * std::clamp(c.normal.dot(nrm), 0.0, 1.0);
    const Vec3 d = c.pos - wrench.axis_point;
    const Point2 o{d.dot(axes.u), d.dot(axes.w)};
    offset.push_back(o);
    out.push_back(TriContact{c.pos, nrm, depth});
    rhs[0] -= depth * o[0];
    rhs[1] -= depth * o[1];
    g00 += o[0] * o[0];
    g01 += o[0] * o[1];
    g11 += o[1] * o[1];
  }
  // The least change of the depths (delta_e = o_e . y with G y = rhs; the pseudo-inverse of a
  // rank-one G for collinear extremes), clamped at 0.
  const double trace = g00 + g11;
  const double det = g00 * g11 - g01 * g01;
  Point2 y{0, 0};
  if (trace > 0 && det > 1e-12 * trace * trace) {
    y = {(g11 * rhs[0] - g01 * rhs[1]) / det, (g00 * rhs[1] - g01 * rhs[0]) / det};
  } else if (trace > 0) {
    y = {(g00 * rhs[0] + g01 * rhs[1]) / (trace * trace),
         (g01 * rhs[0] + g11 * rhs[1]) / (trace * trace)};
  }
  Point2 left{0, 0};  // the extremes' depth-weighted offset after the clamp
  for (std::size_t k = 0; k < extremes; ++k) {
    TriContact& c = out[first + k];
    c.depth = std::max(0.0, c.depth + offset[k][0] * y[0] + offset[k][1] * y[1]);
    left[0] += c.depth * offset[k][0];
    left[1] += c.depth * offset[k][1];
  }
  anchor = TriContact{wrench.axis_point, nrm, wrench.anchor_depth};
  if (wrench.anchor_depth > 0) {
    anchor.pos -= (left[0] * axes.u + left[1] * axes.w) / wrench.anchor_depth;
  }
}

// The pair's budget of `per_pair` points under the moment reduction into `contacts`, from
// `patches` sorted deepest first: every patch's anchor, then the patches' extremes by patch area.
void spend_moment_budget(const std::vector<TriContact>& candidates,
                         const std::vector<ContactPatch>& patches, const std::vector<double>& along,
                         std::size_t per_pair, ContactManifold& out) {
  std::vector<TriContact>& contacts = out.contacts;
  const std::size_t anchors = std::min(per_pair, patches.size());
  thread_local std::vector<std::size_t> by_area, extremes;
  patches_by_area(patches, anchors, by_area);
  extremes.assign(anchors, 0);
  std::size_t used = anchors;
  for (std::size_t p : by_area) {
    extremes[p] = std::min(patches[p].selected.size(), per_pair - used);
    used += extremes[p];
  }
  thread_local std::vector<TriContact> further;  // the extremes, patch by patch in patch order
  thread_local std::vector<std::size_t> start;   // each patch's first extreme in `further`
  further.clear();
  start.clear();
  contacts.reserve(used);
  for (std::size_t p = 0; p < anchors; ++p) {
    const PatchWrench wrench = patch_wrench(candidates, patches[p], along);
    start.push_back(further.size());
    TriContact anchor;
    fit_patch_points(candidates, patches[p], wrench, extremes[p], anchor, further);
    contacts.push_back(anchor);
    out.contact_patch.push_back(p);
  }
  for (std::size_t p : by_area) {
    for (std::size_t k = 0; k < extremes[p]; ++k) {
      contacts.push_back(further[start[p] + k]);
      out.contact_patch.push_back(p);
    }
  }
}

// ---- Force reduction (build_contact_manifold, "Force reduction")

// The first `kept` of a patch's `reference` points (positions and depths along `nrm`, in choice
// order) with the reference's summed depth and depth-weighted centre across `nrm`, into `out`.
void fit_force_points(const std::vector<TriContact>& reference, std::size_t kept, const Vec3& nrm,
                      std::vector<TriContact>& out) {
  const std::size_t first = out.size();
  double total = 0;
  Vec3 weighted = Vec3::Zero();
  for (const TriContact& c : reference) {
    total += c.depth;
    weighted += c.depth * c.pos;
  }
  for (std::size_t k = 0; k < kept; ++k) out.push_back(reference[k]);
  if (kept == reference.size() || !(total > 0)) return;  // S itself, or no force to keep
  const Vec3 centre = weighted / total;
  const PlaneAxes axes = plane_axes(nrm);
  double kept_total = 0;
  for (std::size_t k = 0; k < kept; ++k) kept_total += reference[k].depth;
  // Scaled depths, then the least-norm change delta_k = l0 + l . o_k with sum delta = 0 and
  // sum (e_k + delta_k) o_k = 0: [m, sum o^T; sum o, sum o o^T] [l0; l] = [0; -sum e o].
  thread_local std::vector<Point2> offset;
  offset.clear();
  Eigen::Matrix3d gram = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < kept; ++k) {
    TriContact& c = out[first + k];
    c.depth = kept_total > 0 ? c.depth * (total / kept_total) : total / static_cast<double>(kept);
    const Vec3 d = c.pos - centre;
    const Point2 o{d.dot(axes.u), d.dot(axes.w)};
    offset.push_back(o);
    const Eigen::Vector3d row(1, o[0], o[1]);
    gram += row * row.transpose();
    rhs -= c.depth * Eigen::Vector3d(0, o[0], o[1]);
  }
  const Eigen::Vector3d l = gram.completeOrthogonalDecomposition().solve(rhs);
  double sum = 0;
  for (std::size_t k = 0; k < kept; ++k) {
    TriContact& c = out[first + k];
    c.depth = std::max(0.0, c.depth + l[0] + l[1] * offset[k][0] + l[2] * offset[k][1]);
    sum += c.depth;
  }
  // Rescaled to the reference's sum; the centre's remaining offset taken by moving K across N.
  Point2 left{0, 0};
  for (std::size_t k = 0; k < kept; ++k) {
    TriContact& c = out[first + k];
    c.depth = sum > 0 ? c.depth * (total / sum) : total / static_cast<double>(kept);
    left[0] += c.depth * offset[k][0];
    left[1] += c.depth * offset[k][1];
  }
  const Vec3 shift = (left[0] * axes.u + left[1] * axes.w) / total;
  for (std::size_t k = 0; k < kept; ++k) out[first + k].pos -= shift;
}

// The pair's budget of `per_pair` points under the force reduction into `out`, from `patches`
// sorted deepest first: each patch's share of the reference budget `reference` (patch_shares) is
// its set S, its share of `per_pair` its kept points, fitted by fit_force_points and written in
// step 3's order.
void spend_force_budget(const std::vector<TriContact>& candidates,
                        const std::vector<ContactPatch>& patches, const std::vector<double>& along,
                        std::size_t per_pair, std::size_t reference, ContactManifold& out) {
  thread_local std::vector<std::size_t> reference_shares, shares, start;
  thread_local std::vector<TriContact> set, fitted;
  patch_shares(patches, std::max(reference, per_pair), reference_shares);
  patch_shares(patches, per_pair, shares);
  fitted.clear();
  start.clear();
  for (std::size_t p = 0; p < patches.size(); ++p) {
    start.push_back(fitted.size());
    if (shares[p] == 0) continue;
    set.clear();
    for (std::size_t k = 0; k < reference_shares[p]; ++k) {
      const std::size_t i = patches[p].selected[k];
      set.push_back(TriContact{candidates[i].pos, patches[p].normal, along[i]});
    }
    fit_force_points(set, shares[p], patches[p].normal, fitted);
  }
  const auto emit = [&](std::size_t p, std::size_t k) {
    out.contacts.push_back(fitted[start[p] + k]);
    out.contact_patch.push_back(p);
    out.contact_gain.push_back(static_cast<double>(reference_shares[p]) /
                               static_cast<double>(shares[p]));
  };
  out.contacts.reserve(fitted.size());
  for (std::size_t p = 0; p < patches.size() && shares[p] > 0; ++p) emit(p, 0);
  thread_local std::vector<std::size_t> by_area;
  patches_by_area(patches, patches.size(), by_area);
  for (std::size_t p : by_area) {
    for (std::size_t k = 1; k < shares[p]; ++k) emit(p, k);
  }
}

}  // namespace

std::vector<std::size_t> select_contacts(const std::vector<TriContact>& contacts, std::size_t k) {
  const std::size_t n = contacts.size();
  std::vector<std::size_t> chosen;
  if (n == 0 || k == 0) return chosen;
  // The deepest first.
  std::size_t first = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (contacts[i].depth > contacts[first].depth) first = i;
  }
  if (n <= k) {
    chosen.resize(n);
    for (std::size_t i = 0; i < n; ++i) chosen[i] = i;
    std::swap(chosen[0], chosen[first]);
    return chosen;
  }
  // Farthest-point sampling: dist2[i] is the squared distance of i to the chosen set.
  std::vector<double> dist2(n, std::numeric_limits<double>::infinity());
  chosen.push_back(first);
  for (std::size_t round = 1; round < k; ++round) {
    const Vec3& last = contacts[chosen.back()].pos;
    std::size_t next = n;
    for (std::size_t i = 0; i < n; ++i) {
      dist2[i] = std::min(dist2[i], (contacts[i].pos - last).squaredNorm());
      if (dist2[i] <= 0) continue;  // chosen already, or at a chosen position
      if (next == n || dist2[i] > dist2[next] ||
          (dist2[i] == dist2[next] && contacts[i].depth > contacts[next].depth)) {
        next = i;
      }
    }
    if (next == n) break;  // every remaining contact sits on a chosen position
    chosen.push_back(next);
  }
  return chosen;
}

ContactManifold build_contact_manifold(const std::vector<TriContact>& candidates,
                                       const std::vector<Triangle>& faces_a,
                                       const std::vector<Triangle>& faces_b,
                                       const ManifoldOptions& options) {
  const std::size_t n = candidates.size();
  check_one_per_candidate("build_contact_manifold", n, "faces_a", faces_a.size(), "faces_b",
                          faces_b.size());
  if (n == 0) return {};
  return build_contact_manifold_by_ids(candidates, weld_vertex_ids(faces_a),
                                       weld_vertex_ids(faces_b), options);
}

ContactManifold build_contact_manifold_by_ids(const std::vector<TriContact>& candidates,
                                              const std::vector<FaceVertexIds>& vertices_a,
                                              const std::vector<FaceVertexIds>& vertices_b,
                                              const ManifoldOptions& options) {
  ContactManifold out;
  build_contact_manifold_into(candidates, vertices_a, vertices_b, options, out);
  return out;
}

void build_contact_manifold_into(const std::vector<TriContact>& candidates,
                                 const std::vector<FaceVertexIds>& vertices_a,
                                 const std::vector<FaceVertexIds>& vertices_b,
                                 const ManifoldOptions& options, ContactManifold& out) {
  const std::size_t n = candidates.size();
  check_one_per_candidate("build_contact_manifold_by_ids", n, "vertices_a", vertices_a.size(),
                          "vertices_b", vertices_b.size());
  out.contacts.clear();
  out.contact_patch.clear();
  out.contact_gain.clear();
  if (n == 0) {
    out.patches.clear();
    return;
  }
  if (n >> 32) throw std::length_error("build_contact_manifold_by_ids: more than 2^32 candidates");
  check_vertex_ids(vertices_a, vertices_b);
  const auto per_patch = static_cast<std::size_t>(std::max(options.max_per_patch, 1));
  const auto per_pair = static_cast<std::size_t>(std::max(options.max_per_pair, 1));
  // Scratch is thread_local: the MuJoCo layer calls this for every touching pair of every step,
  // and allocating it each time cost a tenth.
  thread_local std::vector<KeyIndex> order;
  thread_local AdjacencyIndex adjacency;
  thread_local std::vector<double> along;  // each candidate's depth along its patch's normal
  sort_deepest_first(candidates, order);
  adjacency.build(vertices_a, vertices_b);
  grow_patches(candidates, order, adjacency, options.patch_cosine, out.patches);
  along.assign(n, 0);
  const bool moment = options.reduction == ManifoldReduction::kMoment;
  // The moment reduction's extremes leave one point of each patch to its anchor.
  const std::size_t extremes = moment ? per_patch - 1 : per_patch;
  for (ContactPatch& patch : out.patches) choose_points(candidates, extremes, patch, along);
  small_stable_sort(out.patches.begin(), out.patches.end(),
                    [](const ContactPatch& a, const ContactPatch& b) { return a.depth > b.depth; });
  if (moment) {
    spend_moment_budget(candidates, out.patches, along, per_pair, out);
    out.contact_gain.assign(out.contacts.size(), 1.0);
  } else if (options.reduction == ManifoldReduction::kForce) {
    const auto reference = static_cast<std::size_t>(std::max(options.reference_per_pair, 1));
    spend_force_budget(candidates, out.patches, along, per_pair, reference, out);
  } else {
    spend_pair_budget(candidates, out.patches, along, per_pair, out);
    out.contact_gain.assign(out.contacts.size(), 1.0);
  }
}

}  // namespace graspcd
