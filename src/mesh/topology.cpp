// Adjacency of a triangle mesh: orientation repair, half-edge twins,
// manifold-vertex check, boundary loops and connected components.
// Everything is built from a CSR list of outgoing half-edges per vertex, which
// costs two linear passes and finds each twin among a handful of candidates
// (no global sort of edges). The orientation pass builds that list and every
// half-edge's mate once; when it flips nothing (the usual case) the list and
// the mates are the topology's own (a mate is then the twin), so they are not
// built a second time.
#include <algorithm>
#include <atomic>
#include <mutex>
#include <numeric>
#include <queue>
#include <sstream>

#include "intrinsic/error.h"
#include "util/parallel_for.h"
#include "mesh/topology_build.h"

namespace intrinsic::detail {
namespace {

// Outgoing half-edges of each vertex, in compressed rows, with each one's
// target beside it: the twin searches then read one short contiguous run
// per vertex instead of looking every candidate's target up in F (a cache
// miss each: the search was most of validation's time at 1M vertices).
struct OutgoingLists {
  std::vector<int> begin;  // size n+1
  std::vector<int> halfedges;
  std::vector<int> target;  // target[k]: where halfedges[k] ends
};

OutgoingLists outgoing_lists(const Mesh& mesh) {
  const int n = static_cast<int>(mesh.V.rows());
  const int m = static_cast<int>(mesh.F.rows());
  OutgoingLists out;
  out.begin.assign(n + 1, 0);
  for (int c = 0; c < 3; ++c)  // F is column-major: one column at a time
    for (int f = 0; f < m; ++f) ++out.begin[mesh.F(f, c) + 1];
  std::partial_sum(out.begin.begin(), out.begin.end(), out.begin.begin());
  out.halfedges.resize(3 * static_cast<size_t>(m));
  out.target.resize(3 * static_cast<size_t>(m));
  std::vector<int> fill(out.begin.begin(), out.begin.end() - 1);
  for (int f = 0; f < m; ++f)
    for (int c = 0; c < 3; ++c) {
      const int k = fill[mesh.F(f, c)]++;
      out.halfedges[k] = 3 * f + c;
      out.target[k] = mesh.F(f, c == 2 ? 0 : c + 1);
    }
  return out;
}

std::string edge_name(int a, int b) {
  std::ostringstream s;
  s << "edge (" << std::min(a, b) << ", " << std::max(a, b) << ")";
  return s.str();
}

// Counts the other half-edges on h's undirected edge (either direction).
int count_edge_mates(const Mesh& mesh, const OutgoingLists& out, int h) {
  const int a = mesh.source(h), b = mesh.target(h);
  int count = 0;
  for (int k = out.begin[b]; k < out.begin[b + 1]; ++k) count += out.target[k] == a;
  for (int k = out.begin[a]; k < out.begin[a + 1]; ++k) count += out.halfedges[k] != h && out.target[k] == b;
  return count;
}

// For every half-edge, the one other half-edge on the same undirected edge
// (either direction), or -1; throws if an edge has more than two faces.
// `same_direction`: set when some mate runs the same way as its half-edge
// (only then may faces need flipping).
std::vector<int> edge_mates(const Mesh& mesh, const OutgoingLists& out, bool& same_direction) {
  const int m = static_cast<int>(mesh.F.rows());
  std::vector<int> mate(3 * static_cast<size_t>(m), -1);
  std::atomic<bool> same{false};
  // In parallel; each piece remembers its first non-manifold half-edge, and
  // the smallest is reported (the same message as a serial scan).
  std::vector<int> first_bad;
  std::mutex bad_mutex;
  parallel_for(3 * static_cast<std::int64_t>(m), [&](std::int64_t begin, std::int64_t end) {
    for (int h = static_cast<int>(begin); h < end; ++h) {
      const int a = mesh.source(h), b = mesh.target(h);
      int count = 0, other = -1;
      for (int k = out.begin[b]; k < out.begin[b + 1]; ++k)
        if (out.target[k] == a) {
          ++count;
          other = out.halfedges[k];
        }
      for (int k = out.begin[a]; k < out.begin[a + 1]; ++k)
        if (out.target[k] == b && out.halfedges[k] != h) {
          ++count;
          other = out.halfedges[k];
          same.store(true, std::memory_order_relaxed);
        }
      if (count > 1) {
        const std::lock_guard<std::mutex> lock(bad_mutex);
        first_bad.push_back(h);
        return;
      }
      mate[h] = other;
    }
  });
  if (!first_bad.empty()) {
    // Recounted serially: the parallel scan stopped at the first excess.
    const int h = *std::min_element(first_bad.begin(), first_bad.end());
    throw_input(mesh.path + (mesh.path.empty() ? "" : ": ") + edge_name(mesh.source(h), mesh.target(h)) +
                " has " + std::to_string(count_edge_mates(mesh, out, h) + 1) +
                " faces (non-manifold edge; e.g. " + mesh.describe_face(h / 3) + ")");
  }
  same_direction = same.load();
  return mate;
}

// Flood-fills the component of seed into `component`, setting flip (0 keep,
// 1 flip) relative to seed; throws if two faces cannot agree.
void propagate_orientation(const Mesh& mesh, const std::vector<int>& mate, int seed,
                           std::vector<signed char>& flip, std::vector<int>& component) {
  component.clear();
  flip[seed] = 0;
  component.push_back(seed);
  for (size_t q = 0; q < component.size(); ++q) {
    const int f = component[q];
    for (int c = 0; c < 3; ++c) {
      const int h = 3 * f + c, g = mate[h];
      if (g < 0) continue;
      const bool same_direction = mesh.source(g) == mesh.source(h);
      const signed char want = static_cast<signed char>(flip[f] ^ (same_direction ? 1 : 0));
      const int nb = g / 3;
      if (flip[nb] < 0) {
        flip[nb] = want;
        component.push_back(nb);
      } else if (flip[nb] != want) {
        throw_input(mesh.path + (mesh.path.empty() ? "" : ": ") +
                    "the surface is not orientable (" + mesh.describe_face(f) + " and " +
                    mesh.describe_face(nb) + " cannot agree across " +
                    edge_name(mesh.source(h), mesh.target(h)) + ")");
      }
    }
  }
}

// Applies a component's flips, inverted if that flips fewer faces (keeping
// the majority as listed); returns the number of faces flipped.
int apply_flips(Mesh& mesh, const std::vector<int>& component, std::vector<signed char>& flip) {
  size_t flips = 0;
  for (int f : component) flips += flip[f];
  const bool invert = flips * 2 > component.size();  // keep the majority as listed
  int flipped = 0;
  for (int f : component) {
    if (invert) flip[f] ^= 1;
    if (flip[f]) {
      std::swap(mesh.F(f, 1), mesh.F(f, 2));
      ++flipped;
    }
  }
  return flipped;
}

// Fills t.twin: the opposite half-edge b->a of each a->b, or -1 on the boundary.
void find_twins(const Mesh& mesh, const OutgoingLists& out, Topology& t) {
  const int m = static_cast<int>(mesh.F.rows());
  t.twin.assign(3 * static_cast<size_t>(m), -1);
  parallel_for(3 * static_cast<std::int64_t>(m), [&](std::int64_t begin, std::int64_t end) {
    for (int h = static_cast<int>(begin); h < end; ++h) {
      const int a = mesh.source(h), b = mesh.target(h);
      for (int k = out.begin[b]; k < out.begin[b + 1]; ++k)
        if (out.target[k] == a) {
          t.twin[h] = out.halfedges[k];
          break;
        }
    }
  });
}

// Fills is_used, is_boundary and vertex_out (the boundary half-edge of a
// boundary vertex); throws on a vertex whose faces form more than one fan
// (the first such vertex, though the vertices are classified on all cores).
void classify_vertices(const Mesh& mesh, const OutgoingLists& out, Topology& t) {
  const int n = static_cast<int>(mesh.V.rows());
  t.is_used.assign(n, 0);
  t.is_boundary.assign(n, 0);
  t.vertex_out.assign(n, -1);
  std::atomic<int> first_bad{n};
  parallel_for(n, [&](std::int64_t first, std::int64_t last) {
    for (int v = static_cast<int>(first); v < last; ++v) {
      const int valence = out.begin[v + 1] - out.begin[v];
      if (valence == 0) continue;
      t.is_used[v] = 1;
      int start = out.halfedges[out.begin[v]];
      int boundary_count = 0;
      for (int k = out.begin[v]; k < out.begin[v + 1]; ++k) {
        const int h = out.halfedges[k];
        if (t.twin[h] < 0) { ++boundary_count; start = h; }
      }
      // Rotate around v: from outgoing h, prev(h) comes into v and its twin
      // leaves v in the neighbouring face. A manifold vertex's faces form one fan.
      int visited = 0, h = start;
      do {
        ++visited;
        const int back = t.twin[Topology::prev(h)];
        if (back < 0) break;
        h = back;
      } while (h != start && visited <= valence);
      if (boundary_count > 1 || visited != valence) {
        int seen = first_bad.load();
        while (v < seen && !first_bad.compare_exchange_weak(seen, v)) {
        }
        return;
      }
      t.is_boundary[v] = boundary_count > 0;
      t.vertex_out[v] = start;
    }
  });
  if (first_bad < n)
    throw_input(mesh.path + (mesh.path.empty() ? "" : ": ") + "vertex " + std::to_string(first_bad.load()) +
                " is non-manifold (its faces form more than one fan)");
}

// Components by flood fill over twins: face_component, num_components and
// component_faces (the face count of each).
void find_components(int num_faces, Topology& t) {
  t.face_component.assign(num_faces, -1);
  t.num_components = 0;
  t.component_faces.clear();
  std::vector<int> stack;
  for (int seed = 0; seed < num_faces; ++seed) {
    if (t.face_component[seed] >= 0) continue;
    const int id = t.num_components++;
    int count = 0;
    stack.push_back(seed);
    t.face_component[seed] = id;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      ++count;
      for (int c = 0; c < 3; ++c) {
        const int g = t.twin[3 * f + c];
        if (g >= 0 && t.face_component[g / 3] < 0) {
          t.face_component[g / 3] = id;
          stack.push_back(g / 3);
        }
      }
    }
    t.component_faces.push_back(count);
  }
}

// Traces boundary_loops and loop_length in half-edge order; returns the
// component of each loop.
std::vector<int> trace_boundary_loops(const Mesh& mesh, Topology& t) {
  const int m = static_cast<int>(mesh.F.rows());
  // From a boundary half-edge a->b, the next one is b's (unique, since b is
  // manifold) outgoing boundary half-edge.
  t.boundary_loops.clear();
  t.loop_length.clear();
  std::vector<char> seen(3 * static_cast<size_t>(m), 0);
  std::vector<int> loop_component;
  for (int h0 = 0; h0 < 3 * m; ++h0) {
    if (t.twin[h0] >= 0 || seen[h0]) continue;
    std::vector<int> loop;
    double length = 0;
    int h = h0;
    do {
      seen[h] = 1;
      loop.push_back(mesh.source(h));
      length += (mesh.V.row(mesh.target(h)) - mesh.V.row(mesh.source(h))).norm();
      h = t.vertex_out[mesh.target(h)];
    } while (h != h0 && !seen[h]);
    t.boundary_loops.push_back(std::move(loop));
    t.loop_length.push_back(length);
    loop_component.push_back(t.face_component[h0 / 3]);
  }
  return loop_component;
}

// Fills component_loops (longest first) and renumbers the loops so the
// global list reads component by component, outer first.
void group_loops_by_component(const std::vector<int>& loop_component, Topology& t) {
  t.component_loops.assign(t.num_components, {});
  for (size_t l = 0; l < t.boundary_loops.size(); ++l)
    t.component_loops[loop_component[l]].push_back(static_cast<int>(l));
  for (auto& loops : t.component_loops)
    std::stable_sort(loops.begin(), loops.end(),
                     [&](int a, int b) { return t.loop_length[a] > t.loop_length[b]; });
  std::vector<std::vector<int>> loops_sorted;
  std::vector<double> length_sorted;
  for (auto& loops : t.component_loops)
    for (int& l : loops) {
      loops_sorted.push_back(std::move(t.boundary_loops[l]));
      length_sorted.push_back(t.loop_length[l]);
      l = static_cast<int>(loops_sorted.size()) - 1;
    }
  t.boundary_loops = std::move(loops_sorted);
  t.loop_length = std::move(length_sorted);
}

}  // namespace

int orient_faces(Mesh& mesh, OrientedAdjacency* kept) {
  const int m = static_cast<int>(mesh.F.rows());
  OutgoingLists out = outgoing_lists(mesh);
  bool same_direction = false;
  std::vector<int> mate = edge_mates(mesh, out, same_direction);
  // Every mate running the other way: already consistent (and so orientable),
  // the flood fill would keep every face.
  std::vector<signed char> flip(same_direction ? m : 0, -1);  // -1 unvisited, 0 keep, 1 flip
  int flipped_total = 0;
  std::vector<int> component;
  for (int seed = 0; same_direction && seed < m; ++seed) {
    if (flip[seed] >= 0) continue;
    propagate_orientation(mesh, mate, seed, flip, component);
    flipped_total += apply_flips(mesh, component, flip);
  }
  // With no face flipped, the half-edge numbering is unchanged and every
  // mate runs the opposite way (propagate_orientation would have flipped a
  // neighbour otherwise): the outgoing lists and twins are already known.
  if (kept && flipped_total == 0) {
    kept->begin = std::move(out.begin);
    kept->halfedges = std::move(out.halfedges);
    kept->target = std::move(out.target);
    kept->twin = std::move(mate);
  }
  return flipped_total;
}

void build_topology(Mesh& mesh, OrientedAdjacency* known) {
  Topology& t = mesh.topology;
  t.num_vertices = static_cast<int>(mesh.V.rows());
  t.num_faces = static_cast<int>(mesh.F.rows());
  OutgoingLists out;
  if (known && !known->twin.empty()) {
    out.begin = std::move(known->begin);
    out.halfedges = std::move(known->halfedges);
    out.target = std::move(known->target);
    t.twin = std::move(known->twin);
  } else {
    out = outgoing_lists(mesh);
    find_twins(mesh, out, t);
  }
  classify_vertices(mesh, out, t);
  find_components(t.num_faces, t);
  group_loops_by_component(trace_boundary_loops(mesh, t), t);
}

}  // namespace intrinsic::detail
