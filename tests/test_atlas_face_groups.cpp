// Face groups (ChartOptions::face_group, atlas.h) on generated closed
// surfaces: triangles paired into quads across shared edges, as a host
// such as Blender gives the loop triangles of its polygons. Every group must
// end in one chart, so each vertex a group's triangles share has one UV for
// the whole polygon; the atlas stays valid (no flipped face, no overlap),
// and groups given as -1 or of one face change nothing.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "intrinsic/atlas.h"
#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "intrinsic/metrics.h"
#include "test_support.h"

namespace intrinsic {
namespace {

// Pairs each face with an unpaired neighbour across an edge (greedy, in
// face order): the quads of a triangulated quad mesh, written separately
// from the library's adjacency.
std::vector<int> quad_groups(const MatrixX3i& F) {
  std::map<std::pair<int, int>, std::vector<int>> edge_faces;
  for (int f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      const int a = F(f, j), b = F(f, (j + 1) % 3);
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  std::vector<int> group(F.rows(), -1);
  int next = 0;
  for (int f = 0; f < F.rows(); ++f) {
    if (group[f] >= 0) continue;
    group[f] = next;
    for (int j = 0; j < 3 && group[f] == next; ++j) {
      const int a = F(f, j), b = F(f, (j + 1) % 3);
      for (int g : edge_faces[{std::min(a, b), std::max(a, b)}])
        if (g != f && group[g] < 0) {
          group[g] = next;
          break;
        }
    }
    ++next;
  }
  return group;
}

// Per group, every input vertex its faces share has one UV.
void expect_one_uv_per_group_vertex(const AtlasResult& r, const std::vector<int>& group) {
  std::map<std::pair<int, int>, Eigen::Vector2d> seen;  // (group, vertex) -> UV
  int shared = 0;
  for (int f = 0; f < r.F.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector2d uv = r.UV.row(r.FUV(f, j));
      auto [it, fresh] = seen.try_emplace({group[f], r.F(f, j)}, uv);
      if (!fresh) {
        ++shared;
        EXPECT_EQ(it->second, uv) << "face " << f << " corner " << j << " group " << group[f];
      }
    }
  EXPECT_GT(shared, r.F.rows() / 2);  // the two triangles of a quad share two vertices
}

AtlasOptions small_charts() {
  AtlasOptions o;
  o.charts.max_stretch = 1.02;  // many charts, so many chart boundaries to cross quads
  o.charts.min_chart_faces = 0;
  return o;
}

TEST(AtlasFaceGroups, QuadsStayInOneChart) {
  GenerateOptions g;
  g.rings = 14;
  for (const MeshData& m : {generate_bumpy_sphere(g), generate_torus(g), generate_genus2(g)}) {
    const std::vector<int> group = quad_groups(m.F);
    AtlasOptions o = small_charts();
    const AtlasResult plain = atlas(m, o);
    int plain_split = 0;  // the test means something only if plain charts cut quads
    {
      std::map<int, std::set<int>> charts_of;
      for (int f = 0; f < m.F.rows(); ++f) charts_of[group[f]].insert(plain.face_chart[f]);
      for (const auto& [gid, cs] : charts_of) plain_split += cs.size() > 1;
    }
    EXPECT_GT(plain_split, 0);
    o.charts.face_group = group;
    const AtlasResult r = atlas(m, o);
    EXPECT_EQ(r.split_groups, 0);
    std::map<int, std::set<int>> charts_of;
    for (int f = 0; f < m.F.rows(); ++f) charts_of[group[f]].insert(r.face_chart[f]);
    for (const auto& [gid, cs] : charts_of) EXPECT_EQ(cs.size(), 1u) << "group " << gid;
    expect_one_uv_per_group_vertex(r, group);
    for (int f = 0; f < r.F.rows(); ++f) EXPECT_GT(test::signed_uv_area(r.UV, r.FUV, f), 0) << "face " << f;
    const std::vector<char> overlap = overlapping_uv_triangles(r.FUV, r.UV);
    EXPECT_EQ(std::count(overlap.begin(), overlap.end(), 1), 0);
  }
}

TEST(AtlasFaceGroups, NoGroupsChangeNothing) {
  GenerateOptions g;
  g.rings = 10;
  const MeshData m = generate_torus(g);
  AtlasOptions o = small_charts();
  const AtlasResult plain = atlas(m, o);
  for (int kind = 0; kind < 2; ++kind) {
    o.charts.face_group.assign(m.F.rows(), -1);
    if (kind == 1)
      for (int f = 0; f < m.F.rows(); ++f) o.charts.face_group[f] = f;  // one face each
    const AtlasResult r = atlas(m, o);
    EXPECT_TRUE(r.UV == plain.UV);
    EXPECT_EQ(r.face_chart, plain.face_chart);
    EXPECT_EQ(r.split_groups, 0);
  }
}

TEST(AtlasFaceGroups, BadGroupsAreRefused) {
  GenerateOptions g;
  g.rings = 6;
  const MeshData m = generate_torus(g);
  AtlasOptions o;
  o.charts.face_group.assign(m.F.rows() - 1, 0);
  test::expect_error([&] { atlas(m, o); }, ErrorKind::Usage, "face groups number");
  o.charts.face_group.assign(m.F.rows(), 0);
  o.charts.face_group[3] = -2;
  test::expect_error([&] { atlas(m, o); }, ErrorKind::Usage, "face 3: group -2");
}

}  // namespace
}  // namespace intrinsic
