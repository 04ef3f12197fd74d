// The library's front door: include this and use one of three entry points.
// Data are Eigen arrays as libigl has them (V: n x 3 double, F: m x 3 int,
// UV: n x 2 double); every failure is an intrinsic::Error with a kind
// (error.h). The layers under it are drawn in docs/layout.md.
//
// 1. One map of a mesh with boundary (the paper's methods; parameterize.h):
//
//      intrinsic::MeshData data = intrinsic::read_mesh("patch.obj");
//      intrinsic::Mesh mesh = intrinsic::make_mesh(data);   // validated
//      intrinsic::ParamOptions o;
//      o.weights.method = intrinsic::Method::Conformal;     // or Authalic, Mixed...
//      o.boundary = intrinsic::BoundaryShape::Natural;      // or Circle, Square
//      intrinsic::Parameterizer map(mesh, o);                // factors once
//      intrinsic::ParamResult r = map.solve();               // r.UV: one row per vertex
//      // map.set_boundary_shape(...), set_constraints(...): solve again, no refactoring
//      intrinsic::write_mesh("patch_uv.obj", mesh.V, mesh.F, r.UV);
//      // or the whole job (`intrinsic param`) from keys and values, as the
//      // shells give them (param_option_table.h, pipeline.h):
//      // intrinsic::ParamOutcome out = intrinsic::parameterize_file("patch.obj",
//      //     intrinsic::param_request({{"boundary", std::string("natural")}}, intrinsic::OptionSpelling::Keyword));
//
// 2. An atlas of any asset, read and written with everything it carries
//    (pipeline.h: what `intrinsic atlas` runs):
//
//      intrinsic::AtlasRequest request;
//      request.options.charts.max_stretch = 1.08;  // charts within this stretch
//      request.options.pack.resolution = 2048;     // texels the padding is measured in
//      // or from keys and values, as the shells give them (atlas_option_table.h):
//      // request = intrinsic::atlas_request({{"max_stretch", 1.08}}, intrinsic::OptionSpelling::Keyword);
//      intrinsic::AtlasOutcome out = intrinsic::atlas_file("scene.glb", request);
//      // out.result: UV, FUV (per corner), charts, utilization, flipped (0), overlaps (0)
//      // out.input: the mesh read and, beside it, its document (mesh_document.h)
//      intrinsic::write_atlas_file("scene_atlas.glb", out.input, out.result);
//
// 3. The atlas in stages, to look at or change the charts before packing
//    (atlas.h):
//
//      intrinsic::AtlasCharts charts = intrinsic::compute_charts(data, chart_options);
//      intrinsic::AtlasResult packed = intrinsic::pack_charts(charts, pack_options);
#pragma once

// The entry points; pipeline.h brings the headers of the data they take and
// give (atlas.h, atlas_files.h, io.h, mesh_document.h, mesh.h, parameterize.h,
// error.h).
#include "intrinsic/atlas_option_table.h"
#include "intrinsic/param_option_table.h"
#include "intrinsic/parameterizer.h"
#include "intrinsic/pipeline.h"
