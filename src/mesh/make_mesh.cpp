// Validation of raw mesh data into a Mesh: element-level checks with messages
// that name the element and its source line, then orientation and adjacency.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <sstream>

#include "intrinsic/error.h"
#include "intrinsic/mesh.h"
#include "util/parallel_for.h"
#include "mesh/topology_build.h"

namespace intrinsic {

std::string Mesh::describe_face(int f) const {
  std::string s = "face " + std::to_string(f);
  if (f >= 0 && f < static_cast<int>(face_line.size()) && face_line[f] > 0)
    s += " (line " + std::to_string(face_line[f]) + ")";
  return s;
}

namespace {

std::string where(const Mesh& mesh) { return mesh.path.empty() ? "" : mesh.path + ": "; }

// What is wrong with a face, in the order the messages take precedence.
enum Fault { kBadIndex, kBadCoordinate, kDegenerate, kFaults };

// The first face (in file order) with each fault, in one pass over the faces
// on all cores (each reads its corners once, for every check): m where none.
std::array<int, kFaults> first_faults(const Mesh& mesh, const ValidateOptions& options) {
  const int n = static_cast<int>(mesh.V.rows());
  const int m = static_cast<int>(mesh.F.rows());
  std::array<std::atomic<int>, kFaults> first;
  for (std::atomic<int>& x : first) x = m;
  detail::parallel_for(m, [&](std::int64_t begin, std::int64_t end) {
    std::array<int, kFaults> mine{m, m, m};
    for (int f = static_cast<int>(begin); f < end; ++f) {
      const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
      if (a < 0 || a >= n || b < 0 || b >= n || c < 0 || c >= n || a == b || b == c || a == c) {
        mine[kBadIndex] = std::min(mine[kBadIndex], f);
        break;  // this message wins over any later face's
      }
      const Eigen::Vector3d x0 = mesh.V.row(a), x1 = mesh.V.row(b), x2 = mesh.V.row(c);
      if (!x0.allFinite() || !x1.allFinite() || !x2.allFinite()) {
        mine[kBadCoordinate] = std::min(mine[kBadCoordinate], f);
        continue;
      }
      const double twice_area = (x1 - x0).cross(x2 - x0).norm();
      const double longest = std::max({(x1 - x0).squaredNorm(), (x2 - x1).squaredNorm(), (x0 - x2).squaredNorm()});
      if (!(twice_area > options.degenerate_ratio * longest)) mine[kDegenerate] = std::min(mine[kDegenerate], f);
    }
    for (int k = 0; k < kFaults; ++k) {
      int seen = first[k].load();
      while (mine[k] < seen && !first[k].compare_exchange_weak(seen, mine[k])) {
      }
    }
  });
  return {first[0].load(), first[1].load(), first[2].load()};
}

// The checks in the order their messages take precedence, each reporting
// its first face in file order (the same message as one serial scan).
void check_elements(const Mesh& mesh, const ValidateOptions& options) {
  const int n = static_cast<int>(mesh.V.rows());
  const int m = static_cast<int>(mesh.F.rows());
  if (n == 0) throw_input(where(mesh) + "the mesh has no vertices");
  if (m == 0) throw_input(where(mesh) + "the mesh has no faces");
  const std::array<int, kFaults> first = first_faults(mesh, options);
  if (first[kBadIndex] < m) {
    const int f = first[kBadIndex];
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.F(f, c);
      if (v < 0 || v >= n)
        throw_input(where(mesh) + mesh.describe_face(f) + " refers to vertex " + std::to_string(v) +
                    ", but the mesh has " + std::to_string(n) + " vertices");
    }
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    throw_input(where(mesh) + mesh.describe_face(f) + " repeats vertex " + std::to_string(a == b || a == c ? a : b));
  }
  if (first[kBadCoordinate] < m)
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.F(first[kBadCoordinate], c);
      if (!mesh.V.row(v).allFinite())
        throw_input(where(mesh) + "vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
  if (first[kDegenerate] < m)
    throw_input(where(mesh) + mesh.describe_face(first[kDegenerate]) +
                " is degenerate (zero area: its vertices are coincident or collinear)");
}

}  // namespace

Mesh make_mesh(const MatrixX3d& V, const MatrixX3i& F, const ValidateOptions& options) {
  MeshData data;
  data.V = V;
  data.F = F;
  return detail::make_mesh_taking(std::move(data), options);
}

Mesh make_mesh(const MeshData& data, const ValidateOptions& options) {
  MeshData copy;
  copy.V = data.V;
  copy.F = data.F;
  copy.face_line = data.face_line;
  copy.path = data.path;
  return detail::make_mesh_taking(std::move(copy), options);
}

Mesh detail::make_mesh_taking(MeshData&& data, const ValidateOptions& options) {
  Mesh mesh;
  mesh.V = std::move(data.V);
  mesh.F = std::move(data.F);
  mesh.face_line = std::move(data.face_line);
  mesh.path = std::move(data.path);
  check_elements(mesh, options);
  detail::OrientedAdjacency adjacency;
  mesh.validation.reoriented_faces = detail::orient_faces(mesh, &adjacency);
  detail::build_topology(mesh, &adjacency);
  const Topology& t = mesh.topology;
  for (char used : t.is_used) mesh.validation.unreferenced_vertices += used ? 0 : 1;

  if (t.num_components > 1 && !options.allow_several_components) {
    std::ostringstream s;
    s << where(mesh) << "the mesh has " << t.num_components << " connected components (faces per component:";
    for (int c = 0; c < std::min(t.num_components, 8); ++c) s << ' ' << t.component_faces[c];
    if (t.num_components > 8) s << " ...";
    s << "); use --largest-component to keep only the largest";
    throw_input(s.str());
  }
  if (!options.allow_closed)
    for (int c = 0; c < t.num_components; ++c)
      if (t.component_loops[c].empty())
        throw_input(where(mesh) + (t.num_components > 1 ? "component " + std::to_string(c) + " is" : "the surface is") +
                    " closed (no boundary): use `intrinsic atlas` (library: atlas.h), which cuts it into disk charts");
  return mesh;
}

}  // namespace intrinsic
