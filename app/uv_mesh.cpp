// Re-indexing a mesh by texture coordinate.
#include "uv_mesh.h"

#include <vector>

#include "intrinsic/error.h"

namespace intrinsic::app {

UvMesh split_by_texcoord(const MeshData& data) {
  if (!data.has_uv()) throw_input(data.path + ": the mesh has no texture coordinates (OBJ vt or PLY u, v)");
  UvMesh m;
  m.V.setZero(data.TC.rows(), 3);
  std::vector<char> seen(data.TC.rows(), 0);
  for (Eigen::Index f = 0; f < data.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int t = data.FTC(f, c);
      if (t < 0 || t >= data.TC.rows())
        throw_input(data.path + ": texture index out of range in face " + std::to_string(f));
      if (seen[t] && m.V.row(t) != data.V.row(data.F(f, c)))
        throw_input(data.path + ": texture coordinate " + std::to_string(t) +
                    " is shared by corners at different positions");
      m.V.row(t) = data.V.row(data.F(f, c));
      seen[t] = 1;
    }
  m.F = data.FTC;
  m.UV = data.TC;
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
                    {"mirrored", c.mirrored}, {"flipped", c.flipped}, {"collapsed", c.collapsed}});
  return {{"charts", a.charts.size()},
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
