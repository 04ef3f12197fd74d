// Generated test surfaces. The disk triangulation puts 6k points on ring k and
// stitches consecutive rings by merging their points in angle order, which
// always gives a valid disk triangulation; jitter then makes it irregular
// while keeping each point inside its own ring sector, so no triangle folds.
#include "intrinsic/generate.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "intrinsic/error.h"
#include "generate/check_rings.h"

namespace intrinsic {
namespace {

struct PolarDisk {
  std::vector<double> radius, angle;  // per vertex, radius in [0, 1]
  MatrixX3i F;
};

PolarDisk polar_disk(const GenerateOptions& o, double density_skew) {
  if (o.rings < 1 || o.rings > 5000) throw_usage("rings must be between 1 and 5000");
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  PolarDisk d;
  std::vector<int> ring_start;
  d.radius.push_back(0);
  d.angle.push_back(0);
  ring_start.push_back(0);
  for (int k = 1; k <= o.rings; ++k) {
    ring_start.push_back(static_cast<int>(d.radius.size()));
    const int count = 6 * k;
    const double offset = 0.5 * k;  // twist the rings so spokes do not line up
    for (int i = 0; i < count; ++i) {
      double a = 2 * M_PI * (i + offset) / count;
      double r = static_cast<double>(k) / o.rings;
      if (k < o.rings) {
        r += o.jitter * 0.5 / o.rings * unit(rng);
        a += o.jitter * 0.5 * 2 * M_PI / count * unit(rng);
      }
      // Skewed density: more points towards angle 0 on one side of the disk.
      a = a + density_skew * std::sin(a);
      d.radius.push_back(r);
      d.angle.push_back(a);
    }
  }
  ring_start.push_back(static_cast<int>(d.radius.size()));
  std::vector<Eigen::Vector3i> faces;
  for (int i = 0; i < 6; ++i) faces.emplace_back(0, 1 + i, 1 + (i + 1) % 6);
  for (int k = 2; k <= o.rings; ++k) {
    const int in0 = ring_start[k - 1], nin = 6 * (k - 1);
    const int out0 = ring_start[k], nout = 6 * k;
    // Walk both rings by the angle of their points (unwrapped relative to
    // the first point of the inner ring).
    auto unwrapped = [&](int base, int count, int idx, double ref) {
      double a = d.angle[base + idx % count] + 2 * M_PI * (idx / count);
      while (a < ref) a += 2 * M_PI;
      return a;
    };
    const double ref = d.angle[in0] - 1e-9;
    // Start the outer ring at its first point past the inner start.
    int start_out = 0;
    double best = 1e300;
    for (int j = 0; j < nout; ++j) {
      const double a = unwrapped(out0, nout, j, ref);
      if (a < best) { best = a; start_out = j; }
    }
    int i = 0, j = 0;
    while (i < nin || j < nout) {
      const int a = in0 + i % nin, b = out0 + (start_out + j) % nout;
      const double next_in = i < nin ? unwrapped(in0, nin, i + 1, ref) : 1e300;
      const double next_out = j < nout ? unwrapped(out0, nout, start_out + j + 1, ref) : 1e300;
      if (i < nin && (j >= nout || next_in <= next_out)) {
        faces.emplace_back(a, b, in0 + (i + 1) % nin);
        ++i;
      } else {
        faces.emplace_back(a, b, out0 + (start_out + j + 1) % nout);
        ++j;
      }
    }
  }
  d.F.resize(static_cast<int>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) d.F.row(static_cast<int>(f)) = faces[f].transpose();
  return d;
}

MeshData from_polar(const PolarDisk& d, const std::function<Eigen::Vector3d(double, double)>& lift) {
  MeshData m;
  m.V.resize(static_cast<int>(d.radius.size()), 3);
  for (size_t v = 0; v < d.radius.size(); ++v)
    m.V.row(static_cast<int>(v)) = lift(d.radius[v], d.angle[v]).transpose();
  m.F = d.F;
  m.path = "generated";
  return m;
}

}  // namespace

MeshData generate_flat_disk(const GenerateOptions& o) {
  return from_polar(polar_disk(o, 0.3), [](double r, double a) {
    return Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 0);
  });
}

MeshData generate_sphere_cap(const GenerateOptions& o) {
  const double t0 = o.cap_angle;
  return from_polar(polar_disk(o, 0.0), [t0](double r, double a) {
    const double t = r * t0;  // polar angle proportional to radius
    return Eigen::Vector3d(std::sin(t) * std::cos(a), std::sin(t) * std::sin(a), std::cos(t));
  });
}

MeshData generate_wavy_patch(const GenerateOptions& o) {
  return from_polar(polar_disk(o, 0.6), [](double r, double a) {
    const double x = r * std::cos(a), y = r * std::sin(a);
    return Eigen::Vector3d(x, y, 0.25 * std::sin(3 * x) * std::cos(2 * y) + 0.3 * x * x);
  });
}

MeshData generate_sphere_strip(const GenerateOptions& o) {
  // A grid over (longitude in [0, 2pi - gap], z in [-h, h]) with jitter,
  // mapped onto the sphere: a band cut along a meridian, topologically a disk.
  const int rows = std::max(2, o.rings / 2), cols = std::max(4, 4 * o.rings);
  const double h = o.band_height, gap = 2 * M_PI / cols;
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  MeshData m;
  m.V.resize((rows + 1) * (cols + 1), 3);
  for (int i = 0; i <= rows; ++i)
    for (int j = 0; j <= cols; ++j) {
      double z = -h + 2 * h * i / rows, lon = (2 * M_PI - gap) * j / cols;
      // Irregular: a non-uniform longitude warp and jitter inside the grid cell.
      lon = lon + 0.25 * std::sin(lon);
      if (i > 0 && i < rows && j > 0 && j < cols) {
        z += o.jitter * 0.5 * (2 * h / rows) * unit(rng);
        lon += o.jitter * 0.3 * ((2 * M_PI - gap) / cols) * unit(rng);
      }
      const double s = std::sqrt(1 - z * z);
      m.V.row(i * (cols + 1) + j) << s * std::cos(lon), s * std::sin(lon), z;
    }
  m.F.resize(2 * rows * cols, 3);
  int f = 0;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const int a = i * (cols + 1) + j, b = a + 1, c = a + cols + 1, d = c + 1;
      if ((i + j) % 2 == 0) {
        m.F.row(f++) << a, b, d;
        m.F.row(f++) << a, d, c;
      } else {
        m.F.row(f++) << a, b, c;
        m.F.row(f++) << b, d, c;
      }
    }
  m.path = "generated";
  return m;
}

MeshData generate_two_disks(const GenerateOptions& o) {
  MeshData a = generate_flat_disk(o);
  MeshData m;
  const int n = static_cast<int>(a.V.rows()), k = static_cast<int>(a.F.rows());
  m.V.resize(2 * n, 3);
  m.V.topRows(n) = a.V;
  m.V.bottomRows(n) = a.V;
  m.V.bottomRows(n).col(0).array() += 3.0;
  m.F.resize(2 * k, 3);
  m.F.topRows(k) = a.F;
  m.F.bottomRows(k) = a.F.array() + n;
  m.path = "generated";
  return m;
}

// Closed surfaces (inputs for the atlas): regular grids over a parameter domain, jittered
// inside their cells, so every face keeps the orientation of the grid
// (outward normals: counter-clockwise in the domain's (polar, azimuth) or
// (u, v) coordinates).
namespace {

struct Grid {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3i> faces;
};

MeshData to_mesh(const Grid& g) {
  // Only the referenced points, in order of first appearance in the list.
  std::vector<int> index(g.points.size(), -1);
  int n = 0;
  for (const Eigen::Vector3i& f : g.faces)
    for (int c = 0; c < 3; ++c) index[f[c]] = 0;
  for (size_t v = 0; v < g.points.size(); ++v)
    if (index[v] == 0) index[v] = n++;
  MeshData m;
  m.V.resize(n, 3);
  for (size_t v = 0; v < g.points.size(); ++v)
    if (index[v] >= 0) m.V.row(index[v]) = g.points[v].transpose();
  m.F.resize(static_cast<int>(g.faces.size()), 3);
  for (size_t f = 0; f < g.faces.size(); ++f)
    for (int c = 0; c < 3; ++c) m.F(static_cast<int>(f), c) = index[g.faces[f][c]];
  m.path = "generated";
  return m;
}

// Two triangles per cell (a, b) = (i, j), (i+1, j) and (c, d) = (i, j+1),
// (i+1, j+1): counter-clockwise in (i, j).
void add_cell(Grid& g, int a, int b, int c, int d) {
  g.faces.emplace_back(a, b, d);
  g.faces.emplace_back(a, d, c);
}

// Torus grid: nu x nv points, (u, v) periodic; `skip(i, j)` leaves cell (i, j) out.
Grid torus_grid(int nu, int nv, double R, double r, double u0, double v0, const GenerateOptions& o,
                const std::function<bool(int, int)>& skip) {
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Grid g;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = u0 + 2 * M_PI * (i + 0.3 * o.jitter * unit(rng)) / nu;
      const double v = v0 + 2 * M_PI * (j + 0.3 * o.jitter * unit(rng)) / nv;
      g.points.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  auto id = [&](int i, int j) { return (i % nu) * nv + j % nv; };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      if (!skip(i, j)) add_cell(g, id(i, j), id(i + 1, j), id(i, j + 1), id(i + 1, j + 1));
  return g;
}

}  // namespace

MeshData generate_bumpy_sphere(const GenerateOptions& o) {
  detail::check_rings(o);
  const int rows = std::max(3, o.rings), cols = std::max(4, 2 * o.rings);
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Grid g;
  auto lift = [](double t, double p) {
    const double r = 1 + 0.12 * std::sin(5 * t) * std::cos(4 * p) + 0.05 * std::cos(3 * t);
    return Eigen::Vector3d(r * std::sin(t) * std::cos(p), r * std::sin(t) * std::sin(p), r * std::cos(t));
  };
  g.points.push_back(lift(0, 0));  // north pole
  for (int i = 1; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      g.points.push_back(lift(M_PI * (i + 0.3 * o.jitter * unit(rng)) / rows,
                              2 * M_PI * (j + 0.3 * o.jitter * unit(rng) + 0.5 * i) / cols));
  const int south = static_cast<int>(g.points.size());
  g.points.push_back(lift(M_PI, 0));
  auto id = [&](int i, int j) { return 1 + (i - 1) * cols + j % cols; };
  for (int j = 0; j < cols; ++j) {
    g.faces.emplace_back(0, id(1, j), id(1, j + 1));
    g.faces.emplace_back(id(rows - 1, j), south, id(rows - 1, j + 1));
    for (int i = 1; i + 1 < rows; ++i) add_cell(g, id(i, j), id(i + 1, j), id(i, j + 1), id(i + 1, j + 1));
  }
  return to_mesh(g);
}

MeshData generate_torus(const GenerateOptions& o) {
  detail::check_rings(o);
  const int nu = std::max(6, 3 * o.rings), nv = std::max(3, o.rings);
  return to_mesh(torus_grid(nu, nv, 1.0, 0.4, 0, 0, o, [](int, int) { return false; }));
}

// Two tori, each with a rectangular hole facing the other, joined by a tube
// between the two hole loops (the second torus is the mirror image of the
// first, so corresponding loop points face each other): genus 2.
MeshData generate_genus2(const GenerateOptions& o) {
  detail::check_rings(o);
  const int nu = std::max(8, 3 * o.rings), nv = std::max(6, o.rings);
  const int pa = std::max(2, nu / 8), pb = std::max(2, nv / 3), steps = std::max(2, pa);
  const double R = 1.0, r = 0.4, c = R + r + 0.35;
  auto hole = [&](int i, int j) { return i < pa && j < pb; };
  Grid g = torus_grid(nu, nv, R, r, -M_PI * pa / nu, -M_PI * pb / nv, o, hole);
  const int n = static_cast<int>(g.points.size()), m = static_cast<int>(g.faces.size());
  for (int v = 0; v < n; ++v) g.points[v].x() -= c;
  for (int v = 0; v < n; ++v) g.points.push_back(Eigen::Vector3d(-g.points[v].x(), g.points[v].y(), g.points[v].z()));
  for (int f = 0; f < m; ++f) g.faces.emplace_back(g.faces[f][0] + n, g.faces[f][2] + n, g.faces[f][1] + n);
  std::vector<int> loop;  // the hole's perimeter in grid order
  for (int i = 0; i < pa; ++i) loop.push_back(i * nv);
  for (int j = 0; j < pb; ++j) loop.push_back(pa * nv + j);
  for (int i = pa; i > 0; --i) loop.push_back(i * nv + pb);
  for (int j = pb; j > 0; --j) loop.push_back(j);
  const int k = static_cast<int>(loop.size());
  std::vector<std::vector<int>> ring(steps + 1);
  ring[0] = loop;
  for (int s = 1; s < steps; ++s)
    for (int q = 0; q < k; ++q) {
      const double t = static_cast<double>(s) / steps;
      ring[s].push_back(static_cast<int>(g.points.size()));
      g.points.push_back((1 - t) * g.points[loop[q]] + t * g.points[loop[q] + n]);
    }
  for (int q = 0; q < k; ++q) ring[steps].push_back(loop[q] + n);
  // The first torus runs its loop edges one way; the tube runs them the other.
  bool forward = true;
  for (int f = 0; f < m && forward; ++f)
    for (int e = 0; e < 3; ++e)
      if (g.faces[f][e] == loop[0] && g.faces[f][(e + 1) % 3] == loop[1]) forward = false;
  for (int s = 0; s < steps; ++s)
    for (int q = 0; q < k; ++q) {
      const int a = ring[s][q], b = ring[s][(q + 1) % k], cc = ring[s + 1][q], d = ring[s + 1][(q + 1) % k];
      if (forward) add_cell(g, a, b, cc, d);
      else add_cell(g, b, a, d, cc);
    }
  return to_mesh(g);
}

MeshData generate_surface(const std::string& name, const GenerateOptions& o) {
  if (name == "sphere") return generate_bumpy_sphere(o);
  if (name == "torus") return generate_torus(o);
  if (name == "genus2") return generate_genus2(o);
  if (name == "flat") return generate_flat_disk(o);
  if (name == "cap") return generate_sphere_cap(o);
  if (name == "wave") return generate_wavy_patch(o);
  if (name == "strip") return generate_sphere_strip(o);
  if (name == "two-disks") return generate_two_disks(o);
  if (name == "plate") return generate_drilled_plate(o);
  if (name == "box") return generate_box(o);
  if (name == "l-panel") return generate_l_panel(o);
  if (name == "panel-strip") return generate_panel_with_strip(o);
  if (name == "cylinder") return generate_long_cylinder(o);
  if (name == "rectangle") return generate_flat_rectangle(o);
  throw_usage("unknown surface '" + name +
              "' (use flat, cap, wave, strip, two-disks, sphere, torus, genus2, plate, box, l-panel, panel-strip, "
              "cylinder or rectangle)");
}

}  // namespace intrinsic
