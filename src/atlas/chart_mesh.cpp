// A chart as a mesh of its own (so that non-manifold edges and vertices are
// split into manifold pieces for the computation). Its vertices are the
// corners of its faces, glued across the chart's interior edges by union-find,
// so a vertex of the input shared by pieces that meet only there becomes one
// vertex per piece, and never across the chart's own cuts (ChartMesh::cuts). make_mesh is then called on this data (chart_flatten.cpp).
#include <algorithm>
#include <numeric>

#include "atlas/atlas_internal.h"
#include "util/union_find.h"

namespace intrinsic::detail {

ChartMesh chart_mesh(const MeshData& input, const CleanMesh& clean, const std::vector<int>& faces,
                     std::vector<int> cuts) {
  ChartMesh chart;
  chart.faces = faces;
  chart.cuts = std::move(cuts);
  const int k = static_cast<int>(faces.size());
  const ChartFaceIndex index(faces, static_cast<int>(clean.glued.size() / 3));
  std::vector<int> parent(3 * k);
  std::iota(parent.begin(), parent.end(), 0);
  for (int i = 0; i < k; ++i) {
    const int f = faces[i];
    for (int c = 0; c < 3; ++c) {
      const int g = clean.glued[3 * f + c];
      const bool cut = std::binary_search(chart.cuts.begin(), chart.cuts.end(), 3 * f + c);
      const int j = g < 0 || cut ? -1 : index(g);
      if (j < 0) {
        ++chart.open_edges;
        chart.boundary_length += (input.V.row(input.F(f, c)) - input.V.row(input.F(f, (c + 1) % 3))).norm();
        continue;
      }
      for (int e = 0; e < 3; ++e)
        for (int d : {c, (c + 1) % 3})
          if (input.F(g, e) == input.F(f, d)) parent[find_root(parent, 3 * j + e)] = find_root(parent, 3 * i + d);
    }
  }
  // Local vertices numbered in order of first corner.
  std::vector<int> local(3 * k, -1);
  std::vector<int> vertex;  // local -> input vertex
  chart.corner.resize(3 * k);
  for (int h = 0; h < 3 * k; ++h) {
    const int r = find_root(parent, h);
    if (local[r] < 0) {
      local[r] = static_cast<int>(vertex.size());
      vertex.push_back(input.F(faces[h / 3], h % 3));
    }
    chart.corner[h] = local[r];
  }
  chart.data.V.resize(static_cast<int>(vertex.size()), 3);
  for (size_t v = 0; v < vertex.size(); ++v) chart.data.V.row(static_cast<int>(v)) = input.V.row(vertex[v]);
  chart.data.F.resize(k, 3);
  for (int i = 0; i < k; ++i)
    for (int c = 0; c < 3; ++c) chart.data.F(i, c) = chart.corner[3 * i + (clean.reversed[faces[i]] ? (3 - c) % 3 : c)];
  chart.data.path = input.path;
  return chart;
}

}  // namespace intrinsic::detail
