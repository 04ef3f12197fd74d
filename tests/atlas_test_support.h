// An atlas measured a second way: `metrics`' own exact count of folds,
// overlaps and mirrored charts (uv_atlas_metrics, test_atlas_metrics.cpp),
// run on the faces as the atlas wrote them. The atlas's own counters are
// its claim; this is the check that does not share its code.
#pragma once

#include <gtest/gtest.h>

#include "intrinsic/atlas.h"
#include "intrinsic/metrics.h"

namespace intrinsic::test {

// The written faces are the input's unless the atlas reoriented some (then
// AtlasResult::F holds them, corner for corner with FUV).
inline UvAtlasMetrics measure_atlas(const MatrixX3d& V, const MatrixX3i& input_F, const AtlasResult& r) {
  const MatrixX3i& F = r.F.rows() ? r.F : input_F;
  MatrixX3d PT = MatrixX3d::Zero(r.UV.rows(), 3);
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) PT.row(r.FUV(f, c)) = V.row(F(f, c));
  return uv_atlas_metrics(PT, r.FUV, r.UV);
}

// No fold, collapse, mirror or overlap, and the same charts as the atlas
// says (zero-area faces form no chart of their own in `metrics`' count: laid
// along a chart's UV edge, or a component of zero-area faces only).
inline void expect_metrics_accept_atlas(const MatrixX3d& V, const MatrixX3i& input_F, const AtlasResult& r) {
  const UvAtlasMetrics um = measure_atlas(V, input_F, r);
  EXPECT_EQ(um.flipped_triangles, 0);
  EXPECT_EQ(um.collapsed_triangles, 0);
  EXPECT_EQ(um.mirrored_charts, 0);
  EXPECT_EQ(um.overlapping_triangles, 0);
  EXPECT_EQ(um.charts.size() - um.degenerate_charts, r.charts.size());
}

}  // namespace intrinsic::test
