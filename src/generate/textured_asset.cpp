// The generated textured asset of generate.h: an ellipsoid cut into many
// tiny charts, each in its own tile of a grid, with a texture that is a known
// function of the surface point. It stands in for a scan or a badly packed
// game asset in the texture-transfer tests and bench (docs/textures.md): the
// baked texture of any new atlas can be checked texel by texel against
// textured_asset_colour.
#include <cmath>
#include <map>
#include <tuple>

#include "intrinsic/error.h"
#include "intrinsic/generate.h"

namespace intrinsic {
namespace {

constexpr double kRadius[3] = {1.0, 0.9, 0.8};
constexpr int kGutter = 2;  // texels around a chart inside its tile, filled with the chart's nearest point

// One chart: a block of cells of one cube face, its grid vertices (row-major,
// (ni + 1) x (nj + 1)) and where its tile lies in the texture.
struct Chart {
  int ni = 0, nj = 0;
  std::vector<int> vertex;  // mesh vertex per block grid point
  int tile_x = 0, tile_y = 0;  // tile's top-left texel
};

struct Layout {
  int tile = 0;  // tile side in texels
  std::vector<Chart> charts;
};

// The ellipsoid point of cube point c (integer coordinates in [-n, n]).
Eigen::Vector3d surface_point(const Eigen::Vector3d& c) {
  const Eigen::Vector3d s = c.normalized();
  return {kRadius[0] * s.x(), kRadius[1] * s.y(), kRadius[2] * s.z()};
}

// The surface point of a chart's block parameter (s, t) in [0, ni] x [0, nj]:
// on the flat triangle of the cell that contains it, split along the
// diagonal (i, j)-(i+1, j+1) as the faces are.
Eigen::Vector3d chart_point(const MeshData& m, const Chart& c, double s, double t) {
  s = std::clamp(s, 0.0, static_cast<double>(c.ni));
  t = std::clamp(t, 0.0, static_cast<double>(c.nj));
  const int i = std::min(static_cast<int>(s), c.ni - 1), j = std::min(static_cast<int>(t), c.nj - 1);
  const double a = s - i, b = t - j;
  auto P = [&](int di, int dj) -> Eigen::Vector3d {
    return m.V.row(c.vertex[static_cast<std::size_t>((i + di) * (c.nj + 1) + j + dj)]).transpose();
  };
  if (a >= b) return (1 - a) * P(0, 0) + (a - b) * P(1, 0) + b * P(1, 1);
  return (1 - b) * P(0, 0) + a * P(1, 1) + (b - a) * P(0, 1);
}

// Vertices shared between charts and cube faces (welded by their integer cube
// coordinates, so the surface is closed), the charts and their faces.
Layout build_mesh(const TexturedAssetOptions& o, MeshData& m) {
  const int n = o.cells, k = o.chart_cells;
  std::map<std::tuple<int, int, int>, int> index;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3i> faces;
  Layout layout;
  for (int d = 0; d < 6; ++d) {
    const int a = d / 2, sign = d % 2 ? -1 : 1, b = (a + 1) % 3, c = (a + 2) % 3;
    auto vertex = [&](int i, int j) {
      int x[3];
      x[a] = sign * n, x[b] = 2 * i - n, x[c] = 2 * j - n;
      const auto [it, fresh] = index.emplace(std::make_tuple(x[0], x[1], x[2]), static_cast<int>(points.size()));
      if (fresh) points.push_back(surface_point(Eigen::Vector3d(x[0], x[1], x[2])));
      return it->second;
    };
    for (int bi = 0; bi < n; bi += k)
      for (int bj = 0; bj < n; bj += k) {
        Chart ch;
        ch.ni = std::min(k, n - bi), ch.nj = std::min(k, n - bj);
        for (int i = 0; i <= ch.ni; ++i)
          for (int j = 0; j <= ch.nj; ++j) ch.vertex.push_back(vertex(bi + i, bj + j));
        layout.charts.push_back(ch);
      }
  }
  m.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v) m.V.row(static_cast<Eigen::Index>(v)) = points[v].transpose();
  return layout;
}

// Faces and per-chart UVs: a chart's block grid goes affinely into its tile
// inside the gutter; (i, j) -> (u, v) keeps the cube face's orientation, so a
// face counter-clockwise on the surface is counter-clockwise in UV.
void add_faces_and_uvs(const TexturedAssetOptions& o, Layout& layout, MeshData& m) {
  const int count = static_cast<int>(layout.charts.size());
  const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
  layout.tile = o.texture_size / columns;
  if (layout.tile < 2 * kGutter + 4)
    throw_usage("texture_size " + std::to_string(o.texture_size) + " leaves under 8 texels per tile for " +
                std::to_string(count) + " charts");
  std::vector<Eigen::Vector3i> F, FTC;
  std::vector<Eigen::Vector2d> TC;
  const int per_face = count / 6;
  for (int ci = 0; ci < count; ++ci) {
    Chart& ch = layout.charts[static_cast<std::size_t>(ci)];
    ch.tile_x = (ci % columns) * layout.tile, ch.tile_y = (ci / columns) * layout.tile;
    const bool reversed = (ci / per_face) % 2 == 1;  // cube faces on the negative side of their axis
    const double inner = layout.tile - 2.0 * kGutter, k = o.chart_cells;
    const int first = static_cast<int>(TC.size());
    for (int i = 0; i <= ch.ni; ++i)
      for (int j = 0; j <= ch.nj; ++j) {
        // j runs up the tile (v up), so (i, j) -> (u, v) keeps orientation.
        const double x = ch.tile_x + kGutter + inner * i / k, y = ch.tile_y + layout.tile - kGutter - inner * j / k;
        TC.emplace_back(x / o.texture_size, 1 - y / o.texture_size);
      }
    auto id = [&](int i, int j) { return i * (ch.nj + 1) + j; };
    for (int i = 0; i < ch.ni; ++i)
      for (int j = 0; j < ch.nj; ++j) {
        Eigen::Vector3i t1(id(i, j), id(i + 1, j), id(i + 1, j + 1)), t2(id(i, j), id(i + 1, j + 1), id(i, j + 1));
        if (reversed) std::swap(t1[1], t1[2]), std::swap(t2[1], t2[2]);
        for (const Eigen::Vector3i& t : {t1, t2}) {
          F.emplace_back(ch.vertex[t[0]], ch.vertex[t[1]], ch.vertex[t[2]]);
          FTC.push_back(t + Eigen::Vector3i::Constant(first));
        }
      }
  }
  m.F.resize(static_cast<Eigen::Index>(F.size()), 3);
  m.FTC.resize(m.F.rows(), 3);
  for (std::size_t f = 0; f < F.size(); ++f)
    m.F.row(static_cast<Eigen::Index>(f)) = F[f].transpose(), m.FTC.row(static_cast<Eigen::Index>(f)) = FTC[f].transpose();
  m.TC.resize(static_cast<Eigen::Index>(TC.size()), 2);
  for (std::size_t t = 0; t < TC.size(); ++t) m.TC.row(static_cast<Eigen::Index>(t)) = TC[t].transpose();
  m.had_texcoords = true;
}

// Every texel of a tile shows the colour of the chart point its centre maps
// to (gutter texels: the nearest point of the chart); texels of no tile grey.
Image bake(const TexturedAssetOptions& o, const Layout& layout, const MeshData& m) {
  Image img(o.texture_size, o.texture_size, 128);
  const double inner = layout.tile - 2.0 * kGutter;
  for (const Chart& ch : layout.charts)
    for (int y = ch.tile_y; y < ch.tile_y + layout.tile; ++y)
      for (int x = ch.tile_x; x < ch.tile_x + layout.tile; ++x) {
        const double s = (x + 0.5 - ch.tile_x - kGutter) / inner * o.chart_cells;
        const double t = (ch.tile_y + layout.tile - kGutter - (y + 0.5)) / inner * o.chart_cells;
        const Eigen::Vector3d c = textured_asset_colour(chart_point(m, ch, s, t));
        for (int q = 0; q < 3; ++q)
          img.pixel(x, y)[q] = static_cast<std::uint8_t>(std::lround(std::clamp(c[q], 0.0, 1.0) * 255));
      }
  return img;
}

}  // namespace

Eigen::Vector3d textured_asset_colour(const Eigen::Vector3d& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  return {0.5 + 0.3 * std::sin(2 * x + 0.3) + 0.1 * std::sin(3 * (y + z)),
          0.5 + 0.3 * std::sin(2 * y + 1.1) + 0.1 * std::sin(3 * (z + x)),
          0.5 + 0.3 * std::sin(2 * z + 2.0) + 0.1 * std::sin(3 * (x + y))};
}

TexturedAsset generate_textured_asset(const TexturedAssetOptions& o) {
  if (o.cells < 1 || o.cells > 2000) throw_usage("cells must be between 1 and 2000");
  if (o.chart_cells < 1 || o.chart_cells > o.cells) throw_usage("chart_cells must be between 1 and cells");
  if (o.texture_size < 16 || o.texture_size > 16384) throw_usage("texture_size must be between 16 and 16384");
  TexturedAsset a;
  Layout layout = build_mesh(o, a.mesh);
  add_faces_and_uvs(o, layout, a.mesh);
  a.mesh.path = "generated";
  a.texture = bake(o, layout, a.mesh);
  return a;
}

}  // namespace intrinsic
