// intrinsic::atlas (atlas.h): the one-call form, the charts stage and the
// pack stage in turn (chart_stage.cpp, pack_stage.cpp), every option checked
// first so that a bad packing option fails before the charts are computed;
// one atlas per mesh is atlas_per_mesh.cpp's (the meshes a file's document
// tells apart).
#include "atlas/atlas_internal.h"

namespace intrinsic {

AtlasResult atlas(const MeshData& input, const AtlasOptions& options) {
  if (options.scope == AtlasScope::PerMesh) return detail::atlas_per_mesh(input, MeshDocument{}, options);
  const ChartOptions& chart = options.charts;
  const PackOptions pack = pack_options(options);
  detail::check_chart_options(chart);
  detail::check_pack_options(pack);
  if (options.pack_only) return pack_charts(detail::charts_of_uvs(input, options.keep_overlaps), pack);
  return pack_charts(compute_charts(input, chart), pack);
}

AtlasResult atlas(const MeshFile& input, const AtlasOptions& options) {
  if (options.scope == AtlasScope::PerMesh) return detail::atlas_per_mesh(input.mesh, input.document, options);
  return atlas(input.mesh, options);
}

}  // namespace intrinsic
