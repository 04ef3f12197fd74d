// Validation of raw mesh data into a Mesh: element-level checks with messages
// that name the element and its source line, then orientation and adjacency.
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

void check_elements(const Mesh& mesh, const ValidateOptions& options) {
  const int n = static_cast<int>(mesh.V.rows());
  const int m = static_cast<int>(mesh.F.rows());
  if (n == 0) throw_input(where(mesh) + "the mesh has no vertices");
  if (m == 0) throw_input(where(mesh) + "the mesh has no faces");
  for (int f = 0; f < m; ++f) {
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.F(f, c);
      if (v < 0 || v >= n)
        throw_input(where(mesh) + mesh.describe_face(f) + " refers to vertex " + std::to_string(v) +
                    ", but the mesh has " + std::to_string(n) + " vertices");
    }
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    if (a == b || b == c || a == c)
      throw_input(where(mesh) + mesh.describe_face(f) + " repeats vertex " +
                  std::to_string(a == b || a == c ? a : b));
  }
  for (int f = 0; f < m; ++f)
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.F(f, c);
      if (!mesh.V.row(v).allFinite())
        throw_input(where(mesh) + "vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
  // The first degenerate face in file order, found on all cores.
  std::atomic<int> first_degenerate{m};
  detail::parallel_for(m, [&](std::int64_t begin, std::int64_t end) {
    for (int f = static_cast<int>(begin); f < end; ++f) {
      const Eigen::Vector3d x0 = mesh.V.row(mesh.F(f, 0)), x1 = mesh.V.row(mesh.F(f, 1)),
                            x2 = mesh.V.row(mesh.F(f, 2));
      const double twice_area = (x1 - x0).cross(x2 - x0).norm();
      const double longest = std::max({(x1 - x0).squaredNorm(), (x2 - x1).squaredNorm(),
                                       (x0 - x2).squaredNorm()});
      if (!(twice_area > options.degenerate_ratio * longest)) {
        int seen = first_degenerate.load();
        while (f < seen && !first_degenerate.compare_exchange_weak(seen, f)) {
        }
        return;
      }
    }
  });
  if (first_degenerate < m)
    throw_input(where(mesh) + mesh.describe_face(first_degenerate) +
                " is degenerate (zero area: its vertices are coincident or collinear)");
}

}  // namespace

Mesh make_mesh(const MatrixX3d& V, const MatrixX3i& F, const ValidateOptions& options) {
  MeshData data;
  data.V = V;
  data.F = F;
  return make_mesh(data, options);
}

Mesh make_mesh(const MeshData& data, const ValidateOptions& options) {
  Mesh mesh;
  mesh.V = data.V;
  mesh.F = data.F;
  mesh.face_line = data.face_line;
  mesh.path = data.path;
  check_elements(mesh, options);
  mesh.validation.reoriented_faces = detail::orient_faces(mesh);
  detail::build_topology(mesh);
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
