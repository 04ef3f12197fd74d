// generate_parts (src/generate/generate_parts.cpp), the many-part asset of the
// atlas's scale test, checked against what it promises, counted here from
// the faces alone: one connected piece per part, the face count asked for,
// closed parts closed (every edge in two faces, listed both ways) and
// outward, the boundary loops and Euler characteristic of each shape's
// topology (a table written here, not taken from the generator). And the
// atlas of such an asset: the same bytes with one thread as with two.
#include <gtest/gtest.h>

#include <map>
#include <numeric>
#include <set>

#include "intrinsic/atlas.h"
#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "util/parallel_for.h"

namespace intrinsic {
namespace {

int find(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// Connected components of the faces through shared vertices.
int components(const MatrixX3i& F, int vertices) {
  std::vector<int> parent(vertices);
  std::iota(parent.begin(), parent.end(), 0);
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 1; c < 3; ++c) parent[find(parent, F(f, c))] = find(parent, F(f, 0));
  std::set<int> roots;
  for (int f = 0; f < F.rows(); ++f) roots.insert(find(parent, F(f, 0)));
  return static_cast<int>(roots.size());
}

struct PartTopology {
  int euler = 0, loops = 0;
  bool closed = false, consistent = true;
  double volume = 0;
};

// One part's faces: V - E + F, boundary loops (components of the boundary
// edges), closedness and orientation (each directed edge once, its
// opposite present), signed volume.
PartTopology topology_of(const MeshData& m, const std::vector<int>& faces) {
  std::map<std::pair<int, int>, int> directed;
  std::set<int> vertices;
  PartTopology t;
  for (int f : faces)
    for (int c = 0; c < 3; ++c) {
      const int a = m.F(f, c), b = m.F(f, (c + 1) % 3);
      vertices.insert(a);
      if (++directed[{a, b}] > 1) t.consistent = false;
    }
  std::set<std::pair<int, int>> edges;
  std::vector<std::pair<int, int>> boundary;
  for (const auto& [e, n] : directed) {
    edges.insert({std::min(e.first, e.second), std::max(e.first, e.second)});
    if (!directed.count({e.second, e.first})) boundary.push_back(e);
  }
  t.euler = static_cast<int>(vertices.size()) - static_cast<int>(edges.size()) + static_cast<int>(faces.size());
  t.closed = boundary.empty();
  std::map<int, int> parent;
  for (const auto& [a, b] : boundary) parent[a] = a, parent[b] = b;
  std::function<int(int)> root = [&](int x) { return parent[x] == x ? x : parent[x] = root(parent[x]); };
  for (const auto& [a, b] : boundary) parent[root(a)] = root(b);
  std::set<int> roots;
  for (const auto& [v, p] : parent) roots.insert(root(v));
  t.loops = static_cast<int>(roots.size());
  for (int f : faces) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    t.volume += a.dot(b.cross(c)) / 6;
  }
  return t;
}

TEST(AtlasParts, CountsAndTopologyAsPromised) {
  PartsOptions o;
  o.parts = 60;
  o.faces = 30000;
  o.seed = 7;
  const GeneratedParts g = generate_parts(o);
  const MeshData& m = g.mesh;
  ASSERT_EQ(static_cast<int>(g.shape.size()), o.parts);
  ASSERT_EQ(static_cast<long>(g.face_part.size()), m.F.rows());
  // About the faces asked for: each part rounds its grid (and has at least 48).
  EXPECT_GT(m.F.rows(), 0.8 * o.faces);
  EXPECT_LT(m.F.rows(), 1.2 * o.faces + 48 * o.parts);
  EXPECT_EQ(components(m.F, static_cast<int>(m.V.rows())), o.parts);
  std::vector<std::vector<int>> faces(o.parts);
  for (int f = 0; f < m.F.rows(); ++f) faces[g.face_part[f]].push_back(f);
  // What each shape is, topologically: closed?, Euler characteristic, boundary loops.
  const std::map<PartShape, std::array<int, 3>> expected = {
      {PartShape::Ellipsoid, {1, 2, 0}}, {PartShape::RoundedBox, {1, 2, 0}}, {PartShape::Torus, {1, 0, 0}},
      {PartShape::Tube, {0, 0, 2}},      {PartShape::Plate, {0, 1, 1}},      {PartShape::Bowl, {0, 1, 1}}};
  std::set<PartShape> seen;
  for (int k = 0; k < o.parts; ++k) {
    SCOPED_TRACE("part " + std::to_string(k));
    ASSERT_FALSE(faces[k].empty());
    EXPECT_EQ(components(m.F(faces[k], Eigen::all), static_cast<int>(m.V.rows())), 1);
    const PartTopology t = topology_of(m, faces[k]);
    const std::array<int, 3>& e = expected.at(g.shape[k]);
    EXPECT_TRUE(t.consistent);
    EXPECT_EQ(t.closed, e[0] == 1);
    EXPECT_EQ(t.euler, e[1]);
    EXPECT_EQ(t.loops, e[2]);
    if (t.closed) EXPECT_GT(t.volume, 0);  // outward
    seen.insert(g.shape[k]);
  }
  EXPECT_EQ(seen.size(), 6u);  // every shape among 60 parts
}

TEST(AtlasParts, SameSeedSameMeshAndBadOptionsRefused) {
  PartsOptions o;
  o.parts = 5;
  o.faces = 2000;
  const GeneratedParts a = generate_parts(o), b = generate_parts(o);
  EXPECT_EQ(a.mesh.V, b.mesh.V);
  EXPECT_EQ(a.mesh.F, b.mesh.F);
  o.faces = 47 * o.parts;
  EXPECT_THROW(generate_parts(o), Error);
  o.faces = 2000, o.parts = 0;
  EXPECT_THROW(generate_parts(o), Error);
}

// Charts are flattened, merged (the merge's kept workers take unions in
// whatever order they free up) and packed on several cores: the atlas must
// not depend on how many threads ran (each item's work goes to its own slots).
TEST(AtlasParts, SameAtlasWithOneTwoAndThreeThreads) {
  PartsOptions o;
  o.parts = 12;
  o.faces = 6000;
  const MeshData m = generate_parts(o).mesh;
  std::atomic<int>& limit = detail::thread_limit();
  limit = 1;
  const AtlasResult one = atlas(m);
  for (int threads : {2, 3}) {
    limit = threads;
    const AtlasResult more = atlas(m);
    EXPECT_EQ(one.face_chart, more.face_chart) << threads;
    EXPECT_EQ(one.FUV, more.FUV) << threads;
    ASSERT_EQ(one.UV.rows(), more.UV.rows()) << threads;
    EXPECT_EQ(one.UV, more.UV) << threads;  // bit for bit
    EXPECT_EQ(one.utilization, more.utilization) << threads;
  }
  limit = 0;
}

}  // namespace
}  // namespace intrinsic
