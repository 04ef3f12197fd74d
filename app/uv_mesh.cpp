// Re-indexing a mesh by texture coordinate.
#include "uv_mesh.h"

#include <map>
#include <vector>

#include "intrinsic/error.h"

namespace intrinsic::app {

UvMesh split_by_texcoord(const MeshData& data) {
  if (!data.has_uv()) throw_input(data.path + ": the mesh has no texture coordinates (OBJ vt or PLY u, v)");
  UvMesh m;
  m.V.setZero(data.TC.rows(), 3);
  m.F = data.FTC;
  std::vector<int> vertex_of(data.TC.rows(), -1);  // the vertex whose position row t holds
  // A coordinate used at several positions (an atlas collapsing a zero-area
  // face onto a neighbour's UV, or another tool's sharing) gets one row per
  // position, appended after the file's rows.
  std::map<std::pair<int, int>, int> extra;
  std::vector<int> extra_tc, extra_v;
  for (Eigen::Index f = 0; f < data.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int t = data.FTC(f, c), v = data.F(f, c);
      if (t < 0 || t >= data.TC.rows())
        throw_input(data.path + ": texture index out of range in face " + std::to_string(f));
      if (vertex_of[t] < 0) vertex_of[t] = v;
      if (vertex_of[t] == v || data.V.row(vertex_of[t]) == data.V.row(v)) continue;
      const auto [it, fresh] = extra.emplace(std::make_pair(t, v), static_cast<int>(data.TC.rows() + extra_tc.size()));
      if (fresh) extra_tc.push_back(t), extra_v.push_back(v);
      m.F(f, c) = it->second;
    }
  const Eigen::Index n = data.TC.rows(), k = static_cast<Eigen::Index>(extra_tc.size());
  m.V.resize(n + k, 3);
  m.UV.resize(n + k, 2);
  m.UV.topRows(n) = data.TC;
  m.V.topRows(n).setZero();  // rows no face uses stay at the origin
  for (Eigen::Index t = 0; t < n; ++t)
    if (vertex_of[t] >= 0) m.V.row(t) = data.V.row(vertex_of[t]);
  for (Eigen::Index i = 0; i < k; ++i) {
    m.V.row(n + i) = data.V.row(extra_v[i]);
    m.UV.row(n + i) = data.TC.row(extra_tc[i]);
  }
  m.input_vertices = data.V.rows();
  return m;
}

MatrixX2d unmirrored_uv(const UvMesh& m, const UvAtlasMetrics& atlas) {
  MatrixX2d UV = m.UV;
  std::vector<char> done(UV.rows(), 0);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int t = m.F(f, c);
      if (done[t]) continue;
      done[t] = 1;
      if (atlas.charts[atlas.face_chart[f]].mirrored) UV(t, 0) = -UV(t, 0);
    }
  return UV;
}

nlohmann::json atlas_metrics_json(const UvAtlasMetrics& a) {
  nlohmann::json list = nlohmann::json::array();
  for (const UvChart& c : a.charts)
    list.push_back({{"faces", c.faces}, {"uv_area", c.uv_area}, {"area_3d", c.area_3d},
                    {"mirrored", c.mirrored}, {"flipped", c.flipped}, {"collapsed", c.collapsed},
                    {"degenerate", c.degenerate}});
  return {{"charts", static_cast<int>(a.charts.size()) - a.degenerate_charts},
          {"degenerate_charts", a.degenerate_charts},
          {"utilization", a.utilization},
          {"utilization_of", a.utilization_in_unit_square ? "unit_square" : "bounding_square"},
          {"utilization_bbox", a.utilization_bbox},
          {"uv_area", a.uv_area},
          {"mirrored_charts", a.mirrored_charts},
          {"mirrored_faces", a.mirrored_faces},
          {"flipped_triangles", a.flipped_triangles},
          {"collapsed_triangles", a.collapsed_triangles},
          {"degenerate_faces", a.degenerate_faces},
          {"overlapping_triangles", a.overlapping_triangles},
          {"overlapping_pairs_within_charts", a.overlapping_pairs_within_charts},
          {"overlapping_pairs_between_charts", a.overlapping_pairs_between_charts},
          {"chart_list", list}};
}

}  // namespace intrinsic::app
