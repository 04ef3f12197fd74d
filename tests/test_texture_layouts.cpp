// Tests for the texel transfer (transfer_texture) between two UV layouts of
// the same triangles: an analytic texture through a shuffled, rotated,
// mirrored and scaled layout against the function itself (within the
// bilinear interpolation error bound), the identity layout texel for texel,
// supersampling as the box mean, dilation ring by ring, and tangent-space
// normal maps giving the same world normals before and after. Each expected
// value is computed here (own point location, own frames), not by the code.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "intrinsic/error.h"
#include "intrinsic/texture.h"

using namespace intrinsic;

namespace {

// n x n cells of [0,1]^2, two triangles per cell (corner rows 3f + k),
// positions on the height field z = h(x, y) with its normals, old uv = (x, y).
struct Layouts {
  int cells = 0;
  Eigen::MatrixX3d p, n;
  TransferMesh mesh;
};

const int kQuad[2][3] = {{0, 1, 2}, {0, 2, 3}};
const double kCorner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};

double height(double x, double y, double amp) { return amp * std::sin(3 * x) * std::cos(2 * y); }

// New layout: cell c goes to slot perm[c] of a k x k grid, inset by 10% of
// the slot, turned by a random quarter turn and mirrored at random; with
// `identity` new uv = old uv.
Layouts make_layouts(int cells, double amp, bool identity, unsigned seed) {
  Layouts L;
  L.cells = cells;
  const int m = 2 * cells * cells;
  L.p.resize(3 * m, 3), L.n.resize(3 * m, 3);
  L.mesh.old_uv.resize(3 * m, 2), L.mesh.new_uv.resize(3 * m, 2);
  const int k = static_cast<int>(std::ceil(std::sqrt(cells * cells)));
  std::vector<int> perm(cells * cells);
  std::iota(perm.begin(), perm.end(), 0);
  std::mt19937 rng(seed);
  std::shuffle(perm.begin(), perm.end(), rng);
  int r = 0;
  for (int c = 0; c < cells * cells; ++c) {
    const int turns = static_cast<int>(rng() % 4);
    const bool mirror = rng() % 2;
    for (const auto& tri : kQuad)
      for (int j = 0; j < 3; ++j, ++r) {
        double a = kCorner[tri[j]][0], b = kCorner[tri[j]][1];
        const double x = (c % cells + a) / cells, y = (c / cells + b) / cells;
        L.p.row(r) << x, y, height(x, y, amp);
        L.n.row(r) = Eigen::RowVector3d(-3 * amp * std::cos(3 * x) * std::cos(2 * y),
                                        2 * amp * std::sin(3 * x) * std::sin(2 * y), 1).normalized();
        L.mesh.old_uv.row(r) << x, y;
        if (mirror) a = 1 - a;
        for (int t = 0; t < turns; ++t) std::tie(a, b) = std::make_pair(1 - b, a);
        const int s = perm[c];
        L.mesh.new_uv.row(r) << (s % k + 0.1 + 0.8 * a) / k, (s / k + 0.1 + 0.8 * b) / k;
        if (identity) L.mesh.new_uv.row(r) = L.mesh.old_uv.row(r);
      }
  }
  return L;
}

// The face of the new layout containing texel-space point q, and its
// barycentric coordinates (face -1: none).
struct Hit {
  int face = -1;
  double b[3] = {0, 0, 0};
};

Hit locate(const Eigen::MatrixX2d& uv, int w, int h, double qx, double qy) {
  Hit hit;
  for (Eigen::Index f = 0; f < uv.rows() / 3; ++f) {
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) x[k] = uv(3 * f + k, 0) * w, y[k] = uv(3 * f + k, 1) * h;
    const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    double b[3];
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      b[k] = ((x[i] - qx) * (y[j] - qy) - (x[j] - qx) * (y[i] - qy)) / area;
    }
    if (b[0] >= -1e-12 && b[1] >= -1e-12 && b[2] >= -1e-12) {
      hit.face = static_cast<int>(f);
      std::copy(b, b + 3, hit.b);
      return hit;
    }
  }
  return hit;
}

Eigen::Vector2d old_uv_at(const TransferMesh& m, const Hit& h) {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  for (int k = 0; k < 3; ++k) uv += h.b[k] * m.old_uv.row(3 * h.face + k).transpose();
  return uv;
}

// The analytic texture: channel c is 0.5 + 0.4 sin(2 pi (u + c/7)) cos(2 pi v),
// periodic (so Repeat wrapping is exact at the image border).
double f(double u, double v, int c) { return 0.5 + 0.4 * std::sin(2 * M_PI * (u + c / 7.0)) * std::cos(2 * M_PI * v); }

Texture analytic_texture(int size) {
  Texture t;
  t.width = t.height = size, t.channels = 3, t.bits = 16;
  t.texels.resize(static_cast<std::size_t>(size) * size * 3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (int c = 0; c < 3; ++c)
        t.texels[(static_cast<std::size_t>(y) * size + x) * 3 + c] =
            static_cast<float>(f((x + 0.5) / size, (y + 0.5) / size, c));
  return t;
}

// Bilinear interpolation of g on a grid of spacing h errs by at most
// (h^2 / 8) (max |g_uu| + max |g_vv|); for f both are 0.4 (2 pi)^2.
double bilinear_bound(int size) { return 2 * 0.4 * 4 * M_PI * M_PI / (8.0 * size * size); }

}  // namespace

TEST(TextureTransfer, AnalyticTextureThroughShuffledLayout) {
  const Layouts L = make_layouts(6, 0, false, 11);
  const int S = 256, W = 512;
  const Texture src = analytic_texture(S);
  TransferOptions o;
  o.width = o.height = W, o.role = TextureRole::Data, o.padding = 0;
  const TransferResult r = transfer_texture(L.mesh, src, TextureSampler{}, o);
  ASSERT_EQ(r.texture.width, W);
  ASSERT_EQ(r.texture.channels, 3);
  const double tol = bilinear_bound(S) + 2e-6;  // plus float rounding
  long inside = 0;
  double worst = 0;
  for (int y = 0; y < W; ++y)
    for (int x = 0; x < W; ++x) {
      const Hit h = locate(L.mesh.new_uv, W, W, x + 0.5, y + 0.5);
      const std::size_t t = static_cast<std::size_t>(y) * W + x;
      ASSERT_EQ(r.covered[t], h.face >= 0 ? 1 : 0) << x << "," << y;
      if (h.face < 0) continue;
      ++inside;
      const Eigen::Vector2d uv = old_uv_at(L.mesh, h);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(r.texture.texels[t * 3 + c] - f(uv.x(), uv.y(), c)));
    }
  EXPECT_LE(worst, tol);
  RecordProperty("worst_error_e9", static_cast<int>(worst * 1e9));  // in the XML report
  EXPECT_EQ(r.texels_covered, inside);
  EXPECT_GT(r.texels_edge, 0);
  EXPECT_EQ(r.texels_dilated, 0);
  // Partly covered texels carry chart values (f's range), background is 0.
  long edge = 0;
  for (std::size_t t = 0; t < r.covered.size(); ++t) {
    const float v = r.texture.texels[t * 3];
    if (r.covered[t] || v == 0) continue;
    ++edge;
    EXPECT_TRUE(v >= 0.1 - tol && v <= 0.9 + tol);
  }
  EXPECT_EQ(edge, r.texels_edge);
}

TEST(TextureTransfer, SupersampleIsTheBoxMean) {
  const Layouts L = make_layouts(4, 0, false, 5);
  const int S = 256, W = 128, ss = 2;
  TransferOptions o;
  o.width = o.height = W, o.role = TextureRole::Data, o.padding = 0, o.supersample = ss;
  const TransferResult r = transfer_texture(L.mesh, analytic_texture(S), TextureSampler{}, o);
  long checked = 0;
  for (int y = 0; y < W; ++y)
    for (int x = 0; x < W; ++x) {
      double mean[3] = {0, 0, 0};
      bool all_inside = true;
      for (int sy = 0; sy < ss && all_inside; ++sy)
        for (int sx = 0; sx < ss && all_inside; ++sx) {
          const Hit h = locate(L.mesh.new_uv, W, W, x + (sx + 0.5) / ss, y + (sy + 0.5) / ss);
          all_inside = h.face >= 0;
          if (!all_inside) break;
          const Eigen::Vector2d uv = old_uv_at(L.mesh, h);
          for (int c = 0; c < 3; ++c) mean[c] += f(uv.x(), uv.y(), c) / (ss * ss);
        }
      if (!all_inside) continue;
      ++checked;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(r.texture.texels[(static_cast<std::size_t>(y) * W + x) * 3 + c], mean[c], bilinear_bound(S) + 2e-6);
    }
  EXPECT_GT(checked, W * W / 4);
}

TEST(TextureTransfer, IdentityLayoutReproducesSourceTexelForTexel) {
  const Layouts L = make_layouts(5, 0, true, 1);
  const int S = 40;
  std::mt19937 rng(9);
  Texture src;
  src.width = src.height = S, src.channels = 4, src.bits = 8;
  src.texels.resize(static_cast<std::size_t>(S) * S * 4);
  for (float& v : src.texels) v = static_cast<float>(rng() % 256) / 255.0f;
  for (TextureRole role : {TextureRole::Color, TextureRole::Data}) {
    TransferOptions o;
    o.width = o.height = S, o.role = role;
    const TransferResult r = transfer_texture(L.mesh, src, TextureSampler{}, o);
    EXPECT_EQ(r.texels_covered, S * S);
    for (std::size_t i = 0; i < src.texels.size(); ++i)
      ASSERT_EQ(std::lround(r.texture.texels[i] * 255), std::lround(src.texels[i] * 255)) << i;
  }
}

TEST(TextureTransfer, DilationFillsExactlyPaddingRings) {
  Layouts L = make_layouts(1, 0, false, 3);  // one quad chart
  for (Eigen::Index i = 0; i < L.mesh.new_uv.rows(); ++i)
    L.mesh.new_uv.row(i) = (0.3 + 0.27 * L.mesh.old_uv.row(i).array()).matrix();
  Texture src = analytic_texture(32);
  src.channels = 4;  // alpha 1 marks filled texels
  src.texels.clear();
  for (int i = 0; i < 32 * 32; ++i) src.texels.insert(src.texels.end(), {0.2f, 0.5f, 0.7f, 1.0f});
  const int W = 64;
  TransferOptions o;
  o.width = o.height = W, o.role = TextureRole::Data, o.padding = 0;
  const TransferResult base = transfer_texture(L.mesh, src, TextureSampler{}, o);
  auto filled = [W](const TransferResult& r, int x, int y) { return r.texture.texels[(y * W + x) * 4 + 3] > 0; };
  for (int padding : {1, 3, -1}) {
    o.padding = padding;
    const TransferResult r = transfer_texture(L.mesh, src, TextureSampler{}, o);
    long expect_dilated = 0;
    for (int y = 0; y < W; ++y)
      for (int x = 0; x < W; ++x) {
        int dist = 1 << 20;  // Chebyshev distance to the transferred chart
        for (int yy = 0; yy < W; ++yy)
          for (int xx = 0; xx < W; ++xx)
            if (filled(base, xx, yy)) dist = std::min(dist, std::max(std::abs(xx - x), std::abs(yy - y)));
        const bool want = padding < 0 || dist <= padding;
        if (dist > 0 && want) ++expect_dilated;
        const float* t = &r.texture.texels[(y * W + x) * 4];
        if (want) {
          EXPECT_FLOAT_EQ(t[3], 1.0f) << x << "," << y;  // means of chart texels
          EXPECT_NEAR(t[0], 0.2, 1e-6);
        } else {
          EXPECT_EQ(t[0] + t[1] + t[2] + t[3], 0.0f) << x << "," << y;
        }
      }
    EXPECT_EQ(r.texels_dilated, expect_dilated);
    // No chart texel has a background bilinear neighbour.
    for (int y = 1; y + 1 < W; ++y)
      for (int x = 1; x + 1 < W; ++x)
        if (filled(base, x, y))
          for (int d = 0; d < 9; ++d) EXPECT_TRUE(filled(r, x + d % 3 - 1, y + d / 3 - 1));
  }
}

namespace {

// The frame at barycentric point b of face fc (interpolated, Gram-Schmidt,
// bitangent = w cross(n, t)), written independently of the library's.
Eigen::Matrix3d frame(const Layouts& L, const Eigen::MatrixX4d& tan, int fc, const double b[3]) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero(), t = Eigen::Vector3d::Zero();
  double w = 0;
  for (int k = 0; k < 3; ++k) {
    n += b[k] * L.n.row(3 * fc + k).transpose();
    t += b[k] * tan.row(3 * fc + k).head<3>().transpose();
    w += b[k] * tan(3 * fc + k, 3);
  }
  n.normalize();
  t = (t - n.dot(t) * n).normalized();
  Eigen::Matrix3d m;
  m.col(0) = t, m.col(1) = (w < 0 ? -1 : 1) * n.cross(t), m.col(2) = n;
  return m;
}

Eigen::Vector3d world_normal(const Texture& map, const Eigen::Matrix3d& fr, double u, double v) {
  TextureSampler s;
  s.wrap_u = s.wrap_v = TextureWrap::ClampToEdge;
  const auto c = sample_texture(map, s, u, v, TextureRole::Data);
  return (fr * Eigen::Vector3d(2 * c[0] - 1, 2 * c[1] - 1, 2 * c[2] - 1)).normalized();
}

// Tangents of a layout for glTF (v down in the image): computed on v-up uv,
// so the bitangent points up the image like a normal map's green channel.
Eigen::MatrixX4d tangents(const Layouts& L, const Eigen::MatrixX2d& uv) {
  Eigen::MatrixX2d up = uv;
  up.col(1) = (1 - uv.col(1).array()).matrix();
  return compute_tangents(L.p, L.n, up);
}

}  // namespace

TEST(TextureTransfer, FlatNormalMapStaysFlat) {
  Layouts L = make_layouts(4, 0.15, false, 21);
  L.mesh.normal = L.n;
  L.mesh.old_tangent = tangents(L, L.mesh.old_uv);
  L.mesh.new_tangent = tangents(L, L.mesh.new_uv);
  Texture flat;
  flat.width = flat.height = 16, flat.channels = 3, flat.bits = 8;
  for (int i = 0; i < 256; ++i) flat.texels.insert(flat.texels.end(), {0.5f, 0.5f, 1.0f});
  TransferOptions o;
  o.width = o.height = 128, o.role = TextureRole::TangentNormal, o.padding = 2, o.supersample = 2;
  const TransferResult r = transfer_texture(L.mesh, flat, TextureSampler{}, o);
  for (std::size_t t = 0; t < r.covered.size(); ++t) {
    const float* p = &r.texture.texels[t * 3];
    if (p[0] == 0 && p[1] == 0 && p[2] == 0) continue;  // background
    EXPECT_NEAR(p[0], 0.5, 1e-5);
    EXPECT_NEAR(p[1], 0.5, 1e-5);
    EXPECT_NEAR(p[2], 1.0, 1e-5);
  }
}

TEST(TextureTransfer, BumpedNormalMapKeepsWorldNormals) {
  Layouts L = make_layouts(8, 0.15, false, 4);
  L.mesh.normal = L.n;
  L.mesh.old_tangent = tangents(L, L.mesh.old_uv);
  L.mesh.new_tangent = tangents(L, L.mesh.new_uv);
  const int S = 256;
  Texture bump;
  bump.width = bump.height = S, bump.channels = 3, bump.bits = 16;
  for (int y = 0; y < S; ++y)
    for (int x = 0; x < S; ++x) {
      const double u = (x + 0.5) / S, v = (y + 0.5) / S;
      const Eigen::Vector3d n = Eigen::Vector3d(0.3 * std::cos(4 * M_PI * u), 0.3 * std::sin(4 * M_PI * v), 1).normalized();
      for (int c = 0; c < 3; ++c) bump.texels.push_back(static_cast<float>(0.5 * n[c] + 0.5));
    }
  TransferOptions o;
  o.width = o.height = 512, o.role = TextureRole::TangentNormal;
  const TransferResult r = transfer_texture(L.mesh, bump, TextureSampler{}, o);
  double worst = 0;
  const double points[2][3] = {{1 / 3.0, 1 / 3.0, 1 / 3.0}, {0.6, 0.2, 0.2}};
  for (Eigen::Index fc = 0; fc < L.mesh.old_uv.rows() / 3; ++fc)
    for (const auto& b : points) {
      Eigen::Vector2d a = Eigen::Vector2d::Zero(), n = Eigen::Vector2d::Zero();
      for (int k = 0; k < 3; ++k)
        a += b[k] * L.mesh.old_uv.row(3 * fc + k).transpose(), n += b[k] * L.mesh.new_uv.row(3 * fc + k).transpose();
      const Eigen::Vector3d wa = world_normal(bump, frame(L, L.mesh.old_tangent, fc, b), a.x(), a.y());
      const Eigen::Vector3d wb = world_normal(r.texture, frame(L, L.mesh.new_tangent, fc, b), n.x(), n.y());
      worst = std::max(worst, std::acos(std::min(1.0, wa.dot(wb))));
    }
  EXPECT_LT(worst * 180 / M_PI, 0.05);  // measured 0.0023 degrees
  RecordProperty("worst_angle_microdeg", static_cast<int>(worst * 180 / M_PI * 1e6));
  // The layouts differ by quarter turns and mirrors: the transferred texels
  // are not the source's (the re-expression did something).
  double moved = 0;
  for (int i = 0; i < 1000; ++i) moved = std::max(moved, std::abs(double(r.texture.texels[i * 700 % r.texture.texels.size()]) - 0.5));
  EXPECT_GT(moved, 0.05);
}

TEST(TextureTransfer, BadRequestsRefused) {
  Layouts L = make_layouts(2, 0, false, 1);
  const Texture src = analytic_texture(8);
  TransferOptions o;
  o.width = 0;
  EXPECT_THROW(transfer_texture(L.mesh, src, TextureSampler{}, o), Error);
  o = TransferOptions{};
  o.supersample = 5;
  EXPECT_THROW(transfer_texture(L.mesh, src, TextureSampler{}, o), Error);
  o = TransferOptions{};
  o.role = TextureRole::TangentNormal;  // no frames given
  EXPECT_THROW(transfer_texture(L.mesh, src, TextureSampler{}, o), Error);
  o = TransferOptions{};
  o.width = o.height = 64;
  L.mesh.new_uv(4, 1) = NAN;
  try {
    transfer_texture(L.mesh, src, TextureSampler{}, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find("face 1"), std::string::npos) << e.what();
  }
}
