// AtlasScope::PerMesh (atlas.h): each mesh of the input gets an atlas of its
// own filling the unit square, as a game engine wants one texture per mesh,
// where the whole-input atlas (the default) suits a lightmap. The meshes
// are a glTF document's meshes (every primitive of a mesh shares its
// texture) or an OBJ file's `o` objects. Each is cut out as a mesh of its
// own, atlased with the same options, and the results are put back side by
// side in the input's vertex and face numbering, so that the writers need
// no change.
#include <algorithm>
#include <cmath>

#include "atlas/atlas_internal.h"
#include "intrinsic/metrics.h"
#include "io/gltf_document.h"

namespace intrinsic::detail {
namespace {

// Per face, its mesh (0..count-1), as the document beside `input` tells them.
std::vector<int> face_meshes(const MeshData& input, const MeshDocument& document, int& count) {
  std::vector<int> group(static_cast<std::size_t>(input.F.rows()), 0);
  std::vector<int> id;  // source mesh or object label -> group
  auto assign = [&](std::size_t f, int key) {
    const auto k = static_cast<std::size_t>(key + 1);  // OBJ faces before the first `o` have -1
    if (id.size() <= k) id.resize(k + 1, -1);
    if (id[k] < 0) id[k] = count++;
    group[f] = id[k];
  };
  count = 0;
  if (document.gltf) {
    const GltfDocument& doc = *document.gltf;
    for (std::size_t f = 0; f < group.size(); ++f)
      assign(f, doc.primitives[static_cast<std::size_t>(doc.face_primitive[f])].mesh);
  } else if (!document.obj.objects.empty()) {
    for (std::size_t f = 0; f < group.size(); ++f) assign(f, document.obj.objects.of_face[f]);
  } else {
    throw_usage("atlas per mesh: " + input.path +
                " has no meshes to tell apart (a glTF document's meshes or an OBJ file's `o` objects)");
  }
  return group;
}

// The faces of one mesh as a mesh of their own, with its vertices' numbers
// in the input (`global`) and the seams among them.
struct Part {
  MeshData mesh;
  std::vector<int> global, faces;
  std::vector<SeamEdge> seams;
};

Part cut_out(const MeshData& input, const std::vector<int>& group, int g, const std::vector<SeamEdge>& seams) {
  Part p;
  std::vector<int> local(static_cast<std::size_t>(input.V.rows()), -1);
  for (int f = 0; f < input.F.rows(); ++f) {
    if (group[static_cast<std::size_t>(f)] != g) continue;
    p.faces.push_back(f);
    for (int k = 0; k < 3; ++k) {
      int& l = local[static_cast<std::size_t>(input.F(f, k))];
      if (l < 0) l = static_cast<int>(p.global.size()), p.global.push_back(input.F(f, k));
    }
  }
  p.mesh.V.resize(static_cast<Eigen::Index>(p.global.size()), 3);
  for (std::size_t v = 0; v < p.global.size(); ++v) p.mesh.V.row(static_cast<Eigen::Index>(v)) = input.V.row(p.global[v]);
  p.mesh.F.resize(static_cast<Eigen::Index>(p.faces.size()), 3);
  for (std::size_t f = 0; f < p.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      p.mesh.F(static_cast<Eigen::Index>(f), k) = local[static_cast<std::size_t>(input.F(p.faces[f], k))];
  p.mesh.path = input.path;
  for (const SeamEdge& s : seams) {
    const int a = local[static_cast<std::size_t>(s.a)], b = local[static_cast<std::size_t>(s.b)];
    if (a >= 0 && b >= 0) p.seams.push_back({a, b});
  }
  return p;
}

void add_counts(AtlasResult& to, const AtlasResult& r) {
  to.components += r.components;
  to.splits += r.splits;
  to.split_groups += r.split_groups;
  AtlasSplits& s = to.split_reasons;
  s.not_disk += r.split_reasons.not_disk, s.refused += r.split_reasons.refused;
  s.solve_failed += r.split_reasons.solve_failed, s.flipped += r.split_reasons.flipped;
  s.boundary_crossing += r.split_reasons.boundary_crossing, s.sparse += r.split_reasons.sparse;
  s.stretch += r.split_reasons.stretch;
  AtlasCleaning& c = to.cleaning;
  c.degenerate_faces += r.cleaning.degenerate_faces, c.nonmanifold_edges += r.cleaning.nonmanifold_edges;
  c.nonmanifold_vertices += r.cleaning.nonmanifold_vertices, c.inconsistent_edges += r.cleaning.inconsistent_edges;
  c.reversed_faces += r.cleaning.reversed_faces, c.orientation_cuts += r.cleaning.orientation_cuts;
  c.welded_vertices += r.cleaning.welded_vertices, c.hard_edges += r.cleaning.hard_edges;
  AtlasTimings& t = to.timings;
  t.clean_ms += r.timings.clean_ms, t.segment_ms += r.timings.segment_ms, t.flatten_ms += r.timings.flatten_ms;
  t.merge_ms += r.timings.merge_ms, t.pack_ms += r.timings.pack_ms, t.total_ms += r.timings.total_ms;
  to.seam_length += r.seam_length;
  to.flipped += r.flipped;
  to.overlapping += r.overlapping;
}

// The meshes' stretch summaries as one: each mesh has its own texel density,
// so the worst percentiles are the largest of the meshes', the root mean
// square and the means are weighted by 3D area (`area`).
void add_stretch(StretchSummary& to, const StretchSummary& s, double area, double& total_area) {
  const double w = total_area + area > 0 ? area / (total_area + area) : 0;
  to.sander_l2 = std::sqrt((1 - w) * to.sander_l2 * to.sander_l2 + w * s.sander_l2 * s.sander_l2);
  to.anisotropy_mean = (1 - w) * to.anisotropy_mean + w * s.anisotropy_mean;
  to.scale_factor = (1 - w) * to.scale_factor + w * s.scale_factor;
  to.sander_linf = std::max(to.sander_linf, s.sander_linf);
  to.face_stretch_p50 = std::max(to.face_stretch_p50, s.face_stretch_p50);
  to.face_stretch_p95 = std::max(to.face_stretch_p95, s.face_stretch_p95);
  to.face_stretch_p99 = std::max(to.face_stretch_p99, s.face_stretch_p99);
  to.face_stretch_max = std::max(to.face_stretch_max, s.face_stretch_max);
  to.faces += s.faces, to.collapsed_faces += s.collapsed_faces, to.degenerate_faces += s.degenerate_faces;
  total_area += area;
}

}  // namespace

AtlasResult atlas_per_mesh(const MeshData& input, const MeshDocument& document, const AtlasOptions& options) {
  const SeamProblem bad = find_seam_problem(input, options.charts.seams);
  if (bad.index >= 0) throw_input("seam edge " + std::to_string(bad.index) + ": " + bad.message);
  int meshes = 0;
  const std::vector<int> group = face_meshes(input, document, meshes);
  AtlasOptions each = options;
  each.scope = AtlasScope::Whole;
  AtlasResult out;
  out.F.resize(input.F.rows(), 3);
  out.FUV.resize(input.F.rows(), 3);
  out.face_chart.assign(static_cast<std::size_t>(input.F.rows()), -1);
  std::vector<MatrixX2d> uvs;
  double area = 0, utilization = 0, stretch_mean = 0;
  Eigen::Index uv_rows = 0;
  for (int g = 0; g < meshes; ++g) {
    Part p = cut_out(input, group, g, options.charts.seams);
    each.charts.seams = p.seams;
    if (!options.charts.face_group.empty()) {  // the part's faces' groups, in the part's face order
      detail::check_face_groups(options.charts.face_group, static_cast<int>(input.F.rows()));
      each.charts.face_group.clear();
      for (int f : p.faces) each.charts.face_group.push_back(options.charts.face_group[static_cast<std::size_t>(f)]);
    }
    const AtlasResult r = atlas(p.mesh, each);
    const int chart0 = static_cast<int>(out.charts.size());
    for (std::size_t f = 0; f < p.faces.size(); ++f) {
      const auto fi = static_cast<Eigen::Index>(f);
      for (int k = 0; k < 3; ++k) {
        out.F(p.faces[f], k) = p.global[static_cast<std::size_t>(r.F(fi, k))];
        out.FUV(p.faces[f], k) = static_cast<int>(uv_rows) + r.FUV(fi, k);
      }
      const int c = r.face_chart[f];
      out.face_chart[static_cast<std::size_t>(p.faces[f])] = c < 0 ? -1 : chart0 + c;
    }
    double a = 0;
    for (AtlasChart c : r.charts) {
      a += c.area_3d;
      c.component += out.components;
      out.charts.push_back(c);
    }
    utilization += r.utilization / meshes;
    stretch_mean += r.stretch_l2_mean * a;
    add_counts(out, r);
    add_stretch(out.stretch, r.stretch, a, area);
    uvs.push_back(r.UV);
    uv_rows += r.UV.rows();
  }
  out.UV.resize(uv_rows, 2);
  Eigen::Index at = 0;
  for (const MatrixX2d& uv : uvs) {
    out.UV.middleRows(at, uv.rows()) = uv;
    at += uv.rows();
  }
  out.utilization = utilization;
  out.stretch_l2_mean = area > 0 ? stretch_mean / area : 1;
  // Vertices no face uses are no mesh's: counted here, once.
  std::vector<bool> used(static_cast<std::size_t>(input.V.rows()), false);
  for (Eigen::Index f = 0; f < input.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(input.F(f, k))] = true;
  out.cleaning.unreferenced_vertices = static_cast<int>(std::count(used.begin(), used.end(), false));
  return out;
}

}  // namespace intrinsic::detail
