// From user constraints to linear rows (paper section 4.1). Points are checked
// and become barycentric rows; a line's path is walked across the faces
// between consecutive points and constrained at every edge crossing.
//
// The walk: between surface points a and b, the surface is cut by the plane
// through a and b that contains the average normal at a and b (so on a flat
// piece it is the straight segment). Signs of the plane's distance at the
// vertices are exact per vertex (zero counts as positive), so every face the
// cut enters has exactly one other crossed edge: the walk is deterministic
// and cannot skip an edge.
#include <algorithm>
#include <cmath>
#include <map>

#include "intrinsic/constraints.h"
#include "intrinsic/error.h"

namespace intrinsic {
namespace {

struct Resolver {
  const Mesh& mesh;
  std::vector<std::vector<int>> vertex_faces;  // built on first need (lines through vertices)

  std::string name_point(const SurfacePoint& p) const {
    return p.vertex >= 0 ? "vertex " + std::to_string(p.vertex) : "face " + std::to_string(p.face);
  }

  // Checks p and returns its terms (zero weights dropped).
  std::vector<std::pair<int, double>> terms(const SurfacePoint& p, const std::string& label) const {
    const int nv = static_cast<int>(mesh.V.rows()), nf = static_cast<int>(mesh.F.rows());
    if (p.vertex >= 0 && p.face >= 0) throw_input(label + ": give a vertex or a face, not both");
    if (p.vertex >= 0) {
      if (p.vertex >= nv)
        throw_input(label + ": vertex " + std::to_string(p.vertex) + " is out of range (the mesh has " +
                    std::to_string(nv) + " vertices)");
      if (!mesh.topology.is_used[p.vertex])
        throw_input(label + ": vertex " + std::to_string(p.vertex) + " is not used by any face");
      return {{p.vertex, 1.0}};
    }
    if (p.face < 0) throw_input(label + ": no vertex or face given");
    if (p.face >= nf)
      throw_input(label + ": face " + std::to_string(p.face) + " is out of range (the mesh has " +
                  std::to_string(nf) + " faces)");
    if (!p.bary.allFinite()) throw_input(label + ": non-finite barycentric coordinates");
    const double sum = p.bary.sum();
    if (std::abs(sum - 1) > kBaryTolerance)
      throw_input(label + ": barycentric coordinates sum to " + std::to_string(sum) + ", not 1");
    if (p.bary.minCoeff() < -kBaryTolerance)
      throw_input(label + ": negative barycentric coordinate " + std::to_string(p.bary.minCoeff()) +
                  " (the point lies outside " + mesh.describe_face(p.face) + ")");
    std::vector<std::pair<int, double>> t;
    for (int c = 0; c < 3; ++c)
      if (p.bary[c] != 0) t.emplace_back(mesh.F(p.face, c), p.bary[c]);
    return t;
  }

  Eigen::Vector3d position(const std::vector<std::pair<int, double>>& t) const {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (auto [v, w] : t) x += w * mesh.V.row(v).transpose();
    return x;
  }

  Eigen::Vector3d face_normal(int f) const {  // area-weighted
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    return (b - a).cross(c - a);
  }

  std::vector<int> faces_of(const SurfacePoint& p) {
    if (p.face >= 0) return {p.face};
    if (vertex_faces.empty()) {
      vertex_faces.resize(mesh.V.rows());
      for (int f = 0; f < mesh.F.rows(); ++f)
        for (int c = 0; c < 3; ++c) vertex_faces[mesh.F(f, c)].push_back(f);
    }
    return vertex_faces[p.vertex];
  }

  struct Crossing {
    int i, j;   // edge endpoints
    double t;   // point = (1 - t) x_i + t x_j
  };

  // Edge crossings of the cut from a to b, in walking order.
  std::vector<Crossing> walk(const SurfacePoint& a, const SurfacePoint& b, const std::string& label) {
    // terms() first: it checks the indices faces_of() relies on.
    const Eigen::Vector3d pa = position(terms(a, label)), pb = position(terms(b, label));
    const std::vector<int> fa = faces_of(a), fb = faces_of(b);
    for (int f : fa)
      if (std::find(fb.begin(), fb.end(), f) != fb.end()) return {};  // same face: no edge in between
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (int f : fa) normal += face_normal(f);
    for (int f : fb) normal += face_normal(f);
    const Eigen::Vector3d dir = pb - pa;
    const Eigen::Vector3d plane = dir.cross(normal);
    if (!(plane.norm() > 1e-12 * dir.norm() * normal.norm()))
      throw_input(label + ": cannot walk from " + name_point(a) + " to " + name_point(b) +
                  " (the points coincide or the path runs along the normal)");
    auto positive = [&](int v) { return plane.dot(mesh.V.row(v).transpose() - pa) >= 0; };
    auto crossing_of = [&](int h) {
      const int i = mesh.source(h), j = mesh.target(h);
      const double di = plane.dot(mesh.V.row(i).transpose() - pa), dj = plane.dot(mesh.V.row(j).transpose() - pa);
      return Crossing{i, j, di / (di - dj)};
    };
    auto point_of = [&](const Crossing& c) -> Eigen::Vector3d {
      return (1 - c.t) * mesh.V.row(c.i).transpose() + c.t * mesh.V.row(c.j).transpose();
    };
    // Start: the crossed edge of a's face(s) that lies furthest towards b.
    int h = -1;
    double best = 0;
    for (int f : fa)
      for (int c = 0; c < 3; ++c) {
        const int e = 3 * f + c;
        if (positive(mesh.source(e)) == positive(mesh.target(e))) continue;
        const double ahead = (point_of(crossing_of(e)) - pa).dot(dir);
        if (ahead > best) { best = ahead; h = e; }
      }
    if (h < 0)
      throw_input(label + ": cannot walk from " + name_point(a) + " towards " + name_point(b) +
                  ": no edge of the start face lies in that direction");
    std::vector<Crossing> out;
    const int limit = static_cast<int>(mesh.F.rows());
    for (int step = 0; step <= limit; ++step) {
      out.push_back(crossing_of(h));
      const int opposite = mesh.topology.twin[h];
      if (opposite < 0)
        throw_input(label + ": the path from " + name_point(a) + " to " + name_point(b) +
                    " leaves the surface at boundary edge (" + std::to_string(out.back().i) + ", " +
                    std::to_string(out.back().j) + "); add intermediate path points");
      const int g = Topology::face_of(opposite);
      if (std::find(fb.begin(), fb.end(), g) != fb.end()) return out;
      const int n1 = Topology::next(opposite), n2 = Topology::prev(opposite);
      h = positive(mesh.source(n1)) != positive(mesh.target(n1)) ? n1 : n2;
    }
    throw_input(label + ": the path from " + name_point(a) + " to " + name_point(b) +
                " does not reach its end (it circles the surface); add intermediate path points");
  }

  void line(const LineConstraint& l, const std::string& label, std::vector<LinearConstraint>& out) {
    const size_t m = l.path.size();
    if (m < 2) throw_input(label + ": a line needs at least 2 path points");
    if (l.to.size() != 2 && l.to.size() != m)
      throw_input(label + ": \"to\" has " + std::to_string(l.to.size()) + " positions; give 2 (a segment) or " +
                  std::to_string(m) + " (one per path point)");
    for (const Eigen::Vector2d& t : l.to)
      if (!t.allFinite()) throw_input(label + ": non-finite target");
    // Every point checked before any walk, so a bad point is named by its
    // place in the path rather than by the piece that reaches it.
    for (size_t k = 0; k < m; ++k) terms(l.path[k], label + ".path[" + std::to_string(k) + "]");
    // Rows in order along the line, with their 3D arc length and piece index.
    struct Row { LinearConstraint c; double s; size_t piece; };
    std::vector<Row> rows;
    std::vector<double> piece_start(m, 0.0);
    double s = 0;
    Eigen::Vector3d last = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < m; ++k) {
      const std::string point_label = label + " point " + std::to_string(k);
      LinearConstraint c;
      c.terms = terms(l.path[k], label + ".path[" + std::to_string(k) + "]");
      c.position = position(c.terms);
      c.label = point_label;
      if (k > 0) s += (c.position - last).norm();
      last = c.position;
      piece_start[k] = s;
      rows.push_back({c, s, k});
      if (k + 1 == m) break;
      int n = 0;
      for (const Crossing& x : walk(l.path[k], l.path[k + 1], label + " piece " + std::to_string(k))) {
        LinearConstraint e;
        e.terms = {{x.i, 1 - x.t}, {x.j, x.t}};
        e.position = position(e.terms);
        e.label = label + " crossing " + std::to_string(n++) + " of piece " + std::to_string(k) + " (edge " +
                  std::to_string(x.i) + "-" + std::to_string(x.j) + ")";
        s += (e.position - last).norm();
        last = e.position;
        rows.push_back({e, s, k});
      }
    }
    const double total = s;
    for (Row& r : rows) {
      if (l.to.size() == 2) {
        const double f = total > 0 ? r.s / total : 0.0;
        r.c.target = (1 - f) * l.to[0] + f * l.to[1];
      } else if (r.piece + 1 == m) {
        r.c.target = l.to[m - 1];
      } else {
        const double len = piece_start[r.piece + 1] - piece_start[r.piece];
        const double f = len > 0 ? (r.s - piece_start[r.piece]) / len : 0.0;
        r.c.target = (1 - f) * l.to[r.piece] + f * l.to[r.piece + 1];
      }
      out.push_back(r.c);
    }
  }
};

// Drops rows whose weights are zero after rounding and merges identical
// points; the same point with two targets is a contradiction.
std::vector<LinearConstraint> merge(std::vector<LinearConstraint> rows) {
  std::map<std::vector<int>, std::vector<size_t>> by_vertices;
  std::vector<LinearConstraint> out;
  for (LinearConstraint& r : rows) {
    std::sort(r.terms.begin(), r.terms.end());
    r.terms.erase(std::remove_if(r.terms.begin(), r.terms.end(), [](auto& t) { return std::abs(t.second) < 1e-14; }),
                  r.terms.end());
    std::vector<int> key;
    for (auto [v, w] : r.terms) key.push_back(v);
    bool duplicate = false;
    for (size_t k : by_vertices[key]) {
      const LinearConstraint& q = out[k];
      bool same = true;
      for (size_t t = 0; t < key.size(); ++t) same = same && std::abs(q.terms[t].second - r.terms[t].second) <= kBaryTolerance;
      if (!same) continue;
      const double tol = 1e-9 * std::max({1.0, q.target.cwiseAbs().maxCoeff(), r.target.cwiseAbs().maxCoeff()});
      if ((q.target - r.target).cwiseAbs().maxCoeff() > tol)
        throw_input(r.label + " and " + q.label + " constrain the same point to different positions (" +
                    std::to_string(r.target.x()) + ", " + std::to_string(r.target.y()) + ") and (" +
                    std::to_string(q.target.x()) + ", " + std::to_string(q.target.y()) + ")");
      duplicate = true;
      break;
    }
    if (duplicate) continue;
    by_vertices[key].push_back(out.size());
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace

std::vector<LinearConstraint> resolve_constraints(const Mesh& mesh, const Constraints& constraints) {
  Resolver r{mesh, {}};
  std::vector<LinearConstraint> rows;
  for (size_t i = 0; i < constraints.points.size(); ++i) {
    const PointConstraint& p = constraints.points[i];
    const std::string label = p.label.empty() ? "points[" + std::to_string(i) + "]" : p.label;
    if (!p.uv.allFinite()) throw_input(label + ": non-finite target");
    LinearConstraint c;
    c.terms = r.terms(p.point, label);
    c.position = r.position(c.terms);
    c.target = p.uv;
    c.label = label;
    rows.push_back(c);
  }
  for (size_t i = 0; i < constraints.lines.size(); ++i) {
    const LineConstraint& l = constraints.lines[i];
    r.line(l, l.label.empty() ? "lines[" + std::to_string(i) + "]" : l.label, rows);
  }
  return merge(std::move(rows));
}

}  // namespace intrinsic
