// Cleaning for the atlas (every change reported, never silent): the
// input is never changed; this decides which faces take part in a solve
// (non-degenerate ones, by the same area test as make_mesh) and across which
// edges charts may be glued: edges with exactly two such faces that list the
// edge in opposite directions (after the minority of each piece is reversed,
// with ChartOptions::reorient). Everything else (non-manifold edges,
// inconsistently oriented edges, hence every non-orientable piece) is a seam,
// so every chart is manifold and oriented as its faces are written
// (docs/maths.md §9.6).
#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <unordered_map>

#include "atlas/atlas_internal.h"
#include "util/union_find.h"
#include "intrinsic/error.h"

namespace intrinsic::detail {
namespace {

void check_input(const MeshData& in) {
  const std::string where = in.path.empty() ? "" : in.path + ": ";
  if (in.V.rows() == 0) throw_input(where + "the mesh has no vertices");
  if (in.F.rows() == 0) throw_input(where + "the mesh has no faces");
  for (int f = 0; f < in.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (in.F(f, c) < 0 || in.F(f, c) >= in.V.rows())
        throw_input(where + "face " + std::to_string(f) + " refers to vertex " + std::to_string(in.F(f, c)) +
                    ", but the mesh has " + std::to_string(in.V.rows()) + " vertices");
  for (int v = 0; v < in.V.rows(); ++v)
    if (!in.V.row(v).allFinite()) throw_input(where + "vertex " + std::to_string(v) + " has a non-finite coordinate");
}

// Normals, areas, centroids and the degenerate test (make_mesh's: twice the area against the longest edge squared).
void face_geometry(const MeshData& in, double ratio, CleanMesh& m) {
  const int nf = static_cast<int>(in.F.rows());
  m.good.assign(nf, 0);
  m.normal.assign(nf, Eigen::Vector3d::Zero());
  m.area.assign(nf, 0);
  m.centroid.resize(nf);
  for (int f = 0; f < nf; ++f) {
    const Eigen::Vector3d x0 = in.V.row(in.F(f, 0)), x1 = in.V.row(in.F(f, 1)), x2 = in.V.row(in.F(f, 2));
    m.centroid[f] = (x0 + x1 + x2) / 3;
    const Eigen::Vector3d n = (x1 - x0).cross(x2 - x0);
    const double longest = std::max({(x1 - x0).squaredNorm(), (x2 - x1).squaredNorm(), (x0 - x2).squaredNorm()});
    const bool repeated = in.F(f, 0) == in.F(f, 1) || in.F(f, 1) == in.F(f, 2) || in.F(f, 0) == in.F(f, 2);
    m.area[f] = 0.5 * n.norm();
    if (!repeated && n.norm() > ratio * longest) {
      m.good[f] = 1;
      m.normal[f] = n.normalized();
    } else {
      ++m.cleaning.degenerate_faces;
    }
  }
  for (double a : m.area) m.surface_area += a;
}

// CleanMesh::rank and ranked: faces ordered by their corners' positions
// (ties, faces on the same corners, by index).
void rank_faces(const MeshData& in, CleanMesh& m) {
  const int nf = static_cast<int>(in.F.rows());
  using Key = std::array<double, 9>;
  std::vector<Key> key(nf);
  for (int f = 0; f < nf; ++f) {
    std::array<Eigen::Vector3d, 3> c = {in.V.row(in.F(f, 0)), in.V.row(in.F(f, 1)), in.V.row(in.F(f, 2))};
    std::sort(c.begin(), c.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    });
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) key[f][3 * k + d] = c[k][d];
  }
  m.ranked.resize(nf);
  std::iota(m.ranked.begin(), m.ranked.end(), 0);
  std::sort(m.ranked.begin(), m.ranked.end(), [&](int a, int b) { return key[a] != key[b] ? key[a] < key[b] : a < b; });
  m.rank.assign(nf, 0);
  for (int k = 0; k < nf; ++k) m.rank[m.ranked[k]] = k;
}

// Manifold edges (exactly two good faces) as pairs of half-edges, from the
// half-edges of good faces sorted by undirected edge; counts the others and
// the inconsistently listed ones.
std::vector<std::pair<int, int>> manifold_edges(const MeshData& in, CleanMesh& m) {
  const int nf = static_cast<int>(in.F.rows());
  std::vector<std::tuple<int, int, int>> he;  // (min vertex, max vertex, half-edge)
  he.reserve(3 * nf);
  for (int f = 0; f < nf; ++f)
    if (m.good[f])
      for (int c = 0; c < 3; ++c) {
        const int a = in.F(f, c), b = in.F(f, (c + 1) % 3);
        he.emplace_back(std::min(a, b), std::max(a, b), 3 * f + c);
      }
  std::sort(he.begin(), he.end());
  std::vector<std::pair<int, int>> pairs;
  for (size_t i = 0; i < he.size();) {
    size_t j = i;
    while (j < he.size() && std::get<0>(he[j]) == std::get<0>(he[i]) && std::get<1>(he[j]) == std::get<1>(he[i])) ++j;
    if (j - i > 2) ++m.cleaning.nonmanifold_edges;
    if (j - i == 2) {
      const int h = std::get<2>(he[i]), k = std::get<2>(he[i + 1]);
      if (in.F(h / 3, h % 3) == in.F(k / 3, k % 3)) ++m.cleaning.inconsistent_edges;  // same direction in both
      pairs.emplace_back(h, k);
    }
    i = j;
  }
  return pairs;
}

// ChartOptions::reorient: by breadth-first search over manifold edges, a
// face is reversed when its neighbour's orientation requires it; in each
// connected piece the smaller set of faces is the one reversed.
void orient_pieces(const MeshData& in, const std::vector<std::pair<int, int>>& pairs, CleanMesh& m) {
  const int nf = static_cast<int>(in.F.rows());
  std::vector<int> across(3 * nf, -1);  // half-edge -> the other half-edge of its manifold edge
  for (const auto& [h, k] : pairs) across[h] = k, across[k] = h;
  std::vector<int> piece(nf, -1), queue;
  for (int s = 0; s < nf; ++s) {
    if (!m.good[s] || piece[s] >= 0) continue;
    queue.assign(1, s);
    piece[s] = s;
    long flipped = 0;
    for (size_t q = 0; q < queue.size(); ++q) {
      const int f = queue[q];
      flipped += m.reversed[f];
      for (int c = 0; c < 3; ++c) {
        const int k = across[3 * f + c], g = k < 0 ? -1 : k / 3;
        if (g < 0 || piece[g] >= 0) continue;
        piece[g] = s;
        const bool same_direction = in.F(f, c) == in.F(g, k % 3);
        m.reversed[g] = static_cast<char>(m.reversed[f] ^ (same_direction ? 1 : 0));
        queue.push_back(g);
      }
    }
    if (2 * flipped > static_cast<long>(queue.size()))
      for (int f : queue) m.reversed[f] ^= 1;
  }
}

// Glues each manifold edge whose two faces list it in opposite directions
// once the `reversed` faces are taken 0, 2, 1. Without reorient none is, as
// the output keeps the input's winding: a chart may then only span faces
// that agree, and an edge listed the same way by both faces is cut (a seam)
// rather than one face reoriented, which would lay that face (or a whole
// chart made of such faces) out mirrored against its own listing
// (docs/maths.md §9.6). Either way every non-orientable piece is cut.
void orient_and_glue(const MeshData& in, bool reorient, CleanMesh& m) {
  const int nf = static_cast<int>(in.F.rows());
  const std::vector<std::pair<int, int>> pairs = manifold_edges(in, m);
  m.reversed.assign(nf, 0);
  if (reorient) orient_pieces(in, pairs, m);
  m.glued.assign(3 * nf, -1);
  for (const auto& [h, k] : pairs) {
    const bool same_direction = in.F(h / 3, h % 3) == in.F(k / 3, k % 3);
    if ((m.reversed[h / 3] ^ m.reversed[k / 3]) != (same_direction ? 1 : 0)) {
      ++m.cleaning.orientation_cuts;
      continue;
    }
    m.glued[h] = k / 3;
    m.glued[k] = h / 3;
  }
  for (int f = 0; f < nf; ++f) {
    m.cleaning.reversed_faces += m.reversed[f];
    if (m.reversed[f]) m.normal[f] = -m.normal[f];  // the normal of the orientation used
  }
}

// Components (faces sharing a vertex), non-manifold vertices (corners of a
// vertex in several glued fans) and unreferenced vertices.
void count_components(const MeshData& in, CleanMesh& m) {
  const int nv = static_cast<int>(in.V.rows()), nf = static_cast<int>(in.F.rows());
  std::vector<int> parent(nv), corner(3 * nf);
  std::iota(parent.begin(), parent.end(), 0);
  std::iota(corner.begin(), corner.end(), 0);
  for (int f = 0; f < nf; ++f)
    for (int c = 1; c < 3; ++c) parent[find_root(parent, in.F(f, c))] = find_root(parent, in.F(f, 0));
  for (int h = 0; h < 3 * nf; ++h) {
    const int g = m.glued[h];
    if (g < 0) continue;
    const int f = h / 3, a = in.F(f, h % 3), b = in.F(f, (h % 3 + 1) % 3);
    for (int c = 0; c < 3; ++c)
      if (in.F(g, c) == a || in.F(g, c) == b) {
        const int mine = 3 * f + (in.F(g, c) == a ? h % 3 : (h % 3 + 1) % 3);
        corner[find_root(corner, 3 * g + c)] = find_root(corner, mine);
      }
  }
  std::vector<int> root_of(nv, -1), label(nv, -1);
  std::vector<char> counted(nv, 0), used(nv, 0);
  for (int h = 0; h < 3 * nf; ++h) {
    const int v = in.F(h / 3, h % 3);
    used[v] = 1;
    if (!m.good[h / 3]) continue;
    const int r = find_root(corner, h);
    if (root_of[v] < 0) root_of[v] = r;
    else if (root_of[v] != r && !counted[v]) counted[v] = 1, ++m.cleaning.nonmanifold_vertices;
  }
  for (int v = 0; v < nv; ++v) m.cleaning.unreferenced_vertices += used[v] ? 0 : 1;
  m.component.assign(nf, 0);
  for (int f = 0; f < nf; ++f) {
    const int r = find_root(parent, in.F(f, 0));
    if (label[r] < 0) label[r] = m.components++;
    m.component[f] = label[r];
  }
  // Each component's bounding box diagonal, from its faces' corners.
  std::vector<Eigen::Vector3d> lo(m.components, Eigen::Vector3d::Constant(INFINITY)), hi(m.components, -lo[0]);
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d x = in.V.row(in.F(f, c));
      lo[m.component[f]] = lo[m.component[f]].cwiseMin(x), hi[m.component[f]] = hi[m.component[f]].cwiseMax(x);
    }
  m.component_diameter.assign(m.components, 0.0);
  for (int k = 0; k < m.components; ++k) m.component_diameter[k] = (hi[k] - lo[k]).norm();
}

}  // namespace

// Greedy in input order: a vertex joins the earliest kept vertex within the
// distance (cells of that size, the 27 around it searched), else is kept.
// Chains never form (only kept vertices attract), so the result does not
// depend on anything but the input order.
MeshData weld_vertices(const MeshData& input, double relative_distance, int& welded) {
  check_input(input);
  welded = 0;
  // Only what the computation reads: the input's other attributes (texture
  // coordinates, normals, materials, a glTF document) stay with the input,
  // which is what the output is written from.
  MeshData out;
  out.V = input.V;
  out.F = input.F;
  out.path = input.path;
  out.face_line = input.face_line;
  if (!(relative_distance > 0)) return out;
  const Eigen::Vector3d lo = input.V.colwise().minCoeff(), hi = input.V.colwise().maxCoeff();
  const double d = relative_distance * (hi - lo).norm();
  if (!(d > 0) || !std::isfinite(d)) return out;
  const int nv = static_cast<int>(input.V.rows());
  std::vector<int> rep(nv), next(nv, -1);
  std::unordered_map<std::uint64_t, int> head;  // cell -> first kept vertex in it (a list through `next`)
  head.reserve(static_cast<size_t>(nv));  // no rehashing: most vertices open a cell of their own
  // Cells of side 2d: the ball of radius d around a point meets its own
  // cell and, per axis, the neighbour on the side of the nearer face, so 8
  // cells hold every candidate (27 with cells of side d).
  const double side = 2 * d;
  auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    // Colliding cells only add candidates: distances decide.
    return static_cast<std::uint64_t>(x) * 73856093u ^ static_cast<std::uint64_t>(y) * 19349663u ^
           static_cast<std::uint64_t>(z) * 83492791u;
  };
  std::array<std::int64_t, 3> c, step;
  for (int v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k) {
      const double x = (input.V(v, k) - lo[k]) / side;
      c[k] = static_cast<std::int64_t>(std::floor(x));
      step[k] = x - c[k] < 0.5 ? -1 : 1;
    }
    int best = v;
    for (int corner = 0; corner < 8; ++corner) {
      const auto it = head.find(key(c[0] + (corner & 1 ? step[0] : 0), c[1] + (corner & 2 ? step[1] : 0),
                                    c[2] + (corner & 4 ? step[2] : 0)));
      for (int u = it == head.end() ? -1 : it->second; u >= 0; u = next[u])
        if (u < best && (input.V.row(u) - input.V.row(v)).norm() <= d) best = u;
    }
    rep[v] = best;
    if (best != v) {
      ++welded;
      continue;
    }
    auto [it, fresh] = head.emplace(key(c[0], c[1], c[2]), v);
    if (!fresh) next[v] = it->second, it->second = v;
  }
  for (int f = 0; f < out.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) out.F(f, c) = rep[out.F(f, c)];
  return out;
}

CleanMesh clean_mesh(const MeshData& input, const ChartOptions& options) {
  check_input(input);
  CleanMesh m;
  face_geometry(input, options.degenerate_ratio, m);
  rank_faces(input, m);
  orient_and_glue(input, options.reorient, m);
  count_components(input, m);
  return m;
}

}  // namespace intrinsic::detail
