// generate_parts (generate.h): a machine-like asset of many disjoint parts,
// the scale test of `intrinsic atlas` (docs/maths.md §9: every part is a
// component of its own, segmented, flattened, merged and packed with the
// rest). Each part is a parameter grid of its own, jittered inside its
// cells, mapped onto one of six shapes of known topology: a closed genus-0
// ellipsoid or rounded box (two poles, Euler characteristic 2), a closed
// torus (0), an open tube (two boundary loops, 0), an open plate or bowl
// (one loop, 1). Sizes vary over a factor of 8 and a part's faces follow its
// surface (about one texel density over the asset, as in a real asset).
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "intrinsic/error.h"
#include "intrinsic/generate.h"

namespace intrinsic {
namespace {

using Surface = std::function<Eigen::Vector3d(double u, double v)>;

struct Piece {
  std::vector<Eigen::Vector3d> V;
  std::vector<Eigen::Vector3i> F;
};

// A grid of nu x nv quads over [0,1]^2, each cut into two triangles;
// wrap_u / wrap_v glue the opposite sides (torus: both, tube: u, plate: none).
// Interior parameters are jittered by up to `jitter` of a cell (never across
// a glued side or off an open one).
Piece lattice(int nu, int nv, bool wrap_u, bool wrap_v, double jitter, std::mt19937_64& rng, const Surface& f) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int cu = wrap_u ? nu : nu + 1, cv = wrap_v ? nv : nv + 1;
  Piece p;
  for (int j = 0; j < cv; ++j)
    for (int i = 0; i < cu; ++i) {
      double u = static_cast<double>(i) / nu, v = static_cast<double>(j) / nv;
      if (wrap_u || (i > 0 && i < nu)) u += jitter * unit(rng) / nu;
      if (wrap_v || (j > 0 && j < nv)) v += jitter * unit(rng) / nv;
      p.V.push_back(f(u, v));
    }
  auto at = [&](int i, int j) { return (j % cv) * cu + (i % cu); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      p.F.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      p.F.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return p;
}

// Rings of nu points around a pole at v = 0: nv - 1 rings and a second pole
// at v = 1 (closed), or nv rings, the last one the boundary (open).
Piece polar(int nu, int nv, bool closed, double jitter, std::mt19937_64& rng, const Surface& f) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Piece p;
  p.V.push_back(f(0, 0));
  const int rings = closed ? nv - 1 : nv;
  for (int j = 1; j <= rings; ++j)
    for (int i = 0; i < nu; ++i) {
      const bool edge = !closed && j == nv;
      const double u = (i + 0.5 * j) / nu + jitter * unit(rng) / nu;
      const double v = (j + (edge ? 0.0 : 0.5 * jitter * unit(rng))) / nv;
      p.V.push_back(f(u, v));
    }
  auto ring = [&](int j, int i) { return 1 + (j - 1) * nu + (i % nu); };
  for (int i = 0; i < nu; ++i) p.F.emplace_back(0, ring(1, i), ring(1, i + 1));
  for (int j = 1; j < rings; ++j)
    for (int i = 0; i < nu; ++i) {
      p.F.emplace_back(ring(j, i), ring(j + 1, i), ring(j + 1, i + 1));
      p.F.emplace_back(ring(j, i), ring(j + 1, i + 1), ring(j, i + 1));
    }
  if (closed) {
    p.V.push_back(f(0, 1));
    const int last = static_cast<int>(p.V.size()) - 1;
    for (int i = 0; i < nu; ++i) p.F.emplace_back(last, ring(rings, i + 1), ring(rings, i));
  }
  return p;
}

double signed_power(double x, double e) { return std::copysign(std::pow(std::abs(x), e), x); }

// The part's grid for about `faces` triangles (nu around, nv along).
Piece make_piece(PartShape shape, long faces, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> in(0.0, 1.0);
  const double a = 0.5 + 0.5 * in(rng), b = 0.5 + 0.5 * in(rng), c = 0.4 + 0.6 * in(rng);
  const int k1 = 2 + static_cast<int>(4 * in(rng)), k2 = 1 + static_cast<int>(3 * in(rng));
  const double jitter = 0.3;
  const int around = std::max(6, static_cast<int>(std::sqrt(static_cast<double>(faces))));
  const int along = std::max(3, static_cast<int>(faces / (2 * around)) + 1);
  switch (shape) {
    case PartShape::Ellipsoid:
      return polar(around, along, true, jitter, rng, [=](double u, double v) -> Eigen::Vector3d {
        const double t = 2 * M_PI * u, p = M_PI * v, bump = 1 + 0.08 * std::sin(k1 * t) * std::sin(k2 * p);
        return Eigen::Vector3d(a * std::sin(p) * std::cos(t), b * std::sin(p) * std::sin(t), c * std::cos(p)) * bump;
      });
    case PartShape::RoundedBox: {
      const double e = 0.25 + 0.3 * in(rng);
      return polar(around, along, true, jitter, rng, [=](double u, double v) -> Eigen::Vector3d {
        const double t = 2 * M_PI * u, p = M_PI * v;
        return Eigen::Vector3d(a * signed_power(std::sin(p), e) * signed_power(std::cos(t), e),
                               b * signed_power(std::sin(p), e) * signed_power(std::sin(t), e),
                               c * signed_power(std::cos(p), e));
      });
    }
    case PartShape::Torus: {
      const double R = 0.6 + 0.3 * in(rng), r = 0.12 + 0.25 * in(rng) * R, squash = 0.5 + 0.5 * in(rng);
      const int nu = std::max(8, static_cast<int>(std::sqrt(2.0 * faces))), nv = std::max(4, static_cast<int>(faces / (2 * nu)));
      return lattice(nu, nv, true, true, jitter, rng, [=](double u, double v) -> Eigen::Vector3d {
        const double t = 2 * M_PI * u, s = 2 * M_PI * v, ring = R + r * std::cos(s);
        return Eigen::Vector3d(ring * std::cos(t), ring * std::sin(t), squash * r * std::sin(s));
      });
    }
    case PartShape::Tube: {
      const double bend = 0.6 * in(rng), length = 1 + in(rng), r0 = 0.15 + 0.2 * in(rng), r1 = 0.15 + 0.2 * in(rng);
      return lattice(around, along, true, false, jitter, rng, [=](double u, double v) -> Eigen::Vector3d {
        const double t = 2 * M_PI * u, r = r0 + (r1 - r0) * v;
        return Eigen::Vector3d(bend * std::sin(M_PI * v) + r * std::cos(t), r * std::sin(t), length * (v - 0.5));
      });
    }
    case PartShape::Plate: {
      const int nv = std::max(2, static_cast<int>(faces / (2 * around)));
      return lattice(around, nv, false, false, jitter, rng, [=](double u, double v) -> Eigen::Vector3d {
        return Eigen::Vector3d(2 * a * (u - 0.5), 2 * b * (v - 0.5),
                               0.2 * c * std::sin(k1 * u) * std::cos(k2 * v) + 0.6 * (u - 0.5) * (u - 0.5));
      });
    }
    case PartShape::Bowl: {
      const double rim = M_PI * (0.3 + 0.45 * in(rng));
      return polar(around, along, false, jitter, rng, [=](double u, double v) -> Eigen::Vector3d {
        const double t = 2 * M_PI * u, p = rim * v;
        return Eigen::Vector3d(a * std::sin(p) * std::cos(t), b * std::sin(p) * std::sin(t), -c * std::cos(p));
      });
    }
  }
  return {};
}

// Closed parts face outward: the signed volume of the piece is positive.
void orient_outward(Piece& p) {
  double volume = 0;
  for (const Eigen::Vector3i& f : p.F) volume += p.V[f[0]].dot(p.V[f[1]].cross(p.V[f[2]]));
  if (volume < 0)
    for (Eigen::Vector3i& f : p.F) std::swap(f[1], f[2]);
}

bool is_closed(PartShape s) { return s == PartShape::Ellipsoid || s == PartShape::RoundedBox || s == PartShape::Torus; }

}  // namespace

GeneratedParts generate_parts(const PartsOptions& o) {
  if (o.parts < 1 || o.parts > 100000) throw_usage("parts must be between 1 and 100000");
  if (o.faces < 48L * o.parts || o.faces > 100000000L)
    throw_usage("faces must be between 48 per part (" + std::to_string(48L * o.parts) + ") and 100000000");
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> in(0.0, 1.0);
  // Sizes log-uniform over [0.25, 2]; faces in proportion to the squared size.
  std::vector<double> size(o.parts), weight(o.parts);
  double total = 0;
  for (int k = 0; k < o.parts; ++k) {
    size[k] = 0.25 * std::pow(8.0, in(rng));
    weight[k] = size[k] * size[k], total += weight[k];
  }
  GeneratedParts g;
  std::vector<Eigen::Vector3d> V;
  std::vector<Eigen::Vector3i> F;
  const int grid = std::max(1, static_cast<int>(std::ceil(std::cbrt(static_cast<double>(o.parts)))));
  const double spacing = 6;  // wider than any part (at most about 2 * 2.3)
  for (int k = 0; k < o.parts; ++k) {
    const auto shape = static_cast<PartShape>(static_cast<int>(6 * in(rng)) % 6);
    const long faces = std::max(48L, static_cast<long>(std::llround(static_cast<double>(o.faces) * weight[k] / total)));
    Piece p = make_piece(shape, faces, rng);
    if (is_closed(shape)) orient_outward(p);
    Eigen::Quaterniond q(in(rng) - 0.5, in(rng) - 0.5, in(rng) - 0.5, in(rng) - 0.5);
    q.normalize();
    const Eigen::Vector3d at(spacing * (k % grid), spacing * ((k / grid) % grid), spacing * (k / (grid * grid)));
    const int base = static_cast<int>(V.size());
    for (const Eigen::Vector3d& v : p.V) V.push_back(at + q * (size[k] * v));
    for (const Eigen::Vector3i& f : p.F) F.push_back(f.array() + base), g.face_part.push_back(k);
    g.shape.push_back(shape);
  }
  g.mesh.V.resize(static_cast<Eigen::Index>(V.size()), 3);
  for (size_t i = 0; i < V.size(); ++i) g.mesh.V.row(static_cast<Eigen::Index>(i)) = V[i];
  g.mesh.F.resize(static_cast<Eigen::Index>(F.size()), 3);
  for (size_t i = 0; i < F.size(); ++i) g.mesh.F.row(static_cast<Eigen::Index>(i)) = F[i];
  return g;
}

}  // namespace intrinsic
