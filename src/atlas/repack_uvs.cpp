// Re-packing an asset's own UVs (atlas.h AtlasOptions::pack_only; docs/cli.md
// "Re-packing existing UVs"): the input's charts, faces connected through
// shared texture coordinate rows, handed to the pack stage as they are. The
// packer then only turns them by quarter turns (PackOptions::keep_orientation),
// scales them all by one factor and moves them, so each output chart is an
// exact similarity of its input chart. Charts that overlap each other in the
// input (mirrored halves sharing texels) are separate charts, and so come out
// apart; with keep_overlaps they are one chart and keep lying on each other.
#include <algorithm>
#include <numeric>

#include "atlas/atlas_internal.h"
#include "intrinsic/error.h"
#include "intrinsic/metrics.h"

namespace intrinsic::detail {
namespace {

struct Sets {
  std::vector<int> parent;
  explicit Sets(int n) : parent(static_cast<size_t>(n)) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

// Per face its piece: faces sharing a UV row are in one piece.
std::vector<int> uv_pieces(const MeshData& m) {
  Sets rows(static_cast<int>(m.TC.rows()));
  for (int f = 0; f < m.FTC.rows(); ++f) rows.join(m.FTC(f, 0), m.FTC(f, 1)), rows.join(m.FTC(f, 0), m.FTC(f, 2));
  std::vector<int> id(m.TC.rows(), -1), piece(static_cast<size_t>(m.F.rows()));
  int n = 0;
  for (int f = 0; f < m.F.rows(); ++f) {
    int& k = id[rows.find(m.FTC(f, 0))];
    if (k < 0) k = n++;
    piece[f] = k;
  }
  return piece;
}

// Pieces whose UV triangles overlap each other's joined (keep_overlaps), then
// numbered again in order of first face.
void join_overlapping(const MeshData& m, std::vector<int>& piece) {
  const int n = piece.empty() ? 0 : *std::max_element(piece.begin(), piece.end()) + 1;
  const std::vector<char> over = overlapping_uv_triangles(m.FTC, m.TC, nullptr, nullptr, &piece);
  // Faces that overlap another piece's: join their piece with every piece
  // whose overlapping face's UV box meets theirs (exact enough: such boxes
  // meet only where the triangles do, or where they nearly do).
  std::vector<int> faces;
  for (int f = 0; f < m.F.rows(); ++f)
    if (over[f]) faces.push_back(f);
  auto box = [&](int f) {
    Eigen::AlignedBox2d b;
    for (int c = 0; c < 3; ++c) b.extend(m.TC.row(m.FTC(f, c)).transpose());
    return b;
  };
  Sets sets(n);
  for (size_t i = 0; i < faces.size(); ++i)
    for (size_t j = i + 1; j < faces.size(); ++j)
      if (piece[faces[i]] != piece[faces[j]] && box(faces[i]).intersects(box(faces[j])))
        sets.join(piece[faces[i]], piece[faces[j]]);
  std::vector<int> renum(static_cast<size_t>(n), -1);
  int next = 0;
  for (int& p : piece) {
    int& r = renum[sets.find(p)];
    if (r < 0) r = next++;
    p = r;
  }
}

}  // namespace

AtlasCharts charts_of_uvs(const MeshData& m, bool keep_overlaps) {
  if (!m.has_uv())
    throw_input(m.path + ": no texture coordinates on every face to re-pack (pack_only needs the input's own UVs)");
  if (!m.TC.allFinite()) throw_input(m.path + ": a texture coordinate is not finite");
  std::vector<int> piece = uv_pieces(m);
  if (keep_overlaps) join_overlapping(m, piece);
  const int n = piece.empty() ? 0 : *std::max_element(piece.begin(), piece.end()) + 1;
  AtlasCharts c;
  c.V = m.V;
  c.F = m.F;
  c.FUV.resize(m.F.rows(), 3);
  c.face_chart = piece;
  c.charts.resize(static_cast<size_t>(n));
  // Each chart's rows one block, in chart order: a row is copied per chart
  // that uses it (keep_overlaps may put one row in one chart only anyway).
  std::vector<std::vector<int>> faces(static_cast<size_t>(n));
  for (int f = 0; f < m.F.rows(); ++f) faces[piece[f]].push_back(f);
  std::vector<Eigen::Vector2d> rows;
  for (int k = 0; k < n; ++k) {
    std::vector<int> local(m.TC.rows(), -1);
    double area = 0;
    for (int f : faces[k]) {
      for (int j = 0; j < 3; ++j) {
        int& r = local[m.FTC(f, j)];
        if (r < 0) r = static_cast<int>(rows.size()), rows.push_back(m.TC.row(m.FTC(f, j)).transpose());
        c.FUV(f, j) = r;
      }
      const Eigen::Vector2d a = rows[c.FUV(f, 1)] - rows[c.FUV(f, 0)], b = rows[c.FUV(f, 2)] - rows[c.FUV(f, 0)];
      area += std::abs(a.x() * b.y() - a.y() * b.x()) / 2;
    }
    AtlasChart& s = c.charts[k];
    s.faces = static_cast<int>(faces[k].size());
    s.area_3d = area;  // UV area: one common scale is all the packer needs
  }
  c.UV.resize(static_cast<Eigen::Index>(rows.size()), 2);
  for (size_t r = 0; r < rows.size(); ++r) c.UV.row(static_cast<Eigen::Index>(r)) = rows[r].transpose();
  for (int k = 0; k < n; ++k) c.charts[k].vertices = 0;
  return c;
}

}  // namespace intrinsic::detail
