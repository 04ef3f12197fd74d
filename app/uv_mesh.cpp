// Re-indexing a mesh by texture coordinate.
#include "uv_mesh.h"

#include <vector>

#include "intrinsic/error.h"

namespace intrinsic::app {

UvMesh split_by_texcoord(const MeshData& data) {
  if (!data.has_uv()) throw_input(data.path + ": the mesh has no texture coordinates (OBJ vt or PLY u, v)");
  UvMesh m;
  m.V.setZero(data.TC.rows(), 3);
  std::vector<char> seen(data.TC.rows(), 0);
  for (Eigen::Index f = 0; f < data.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int t = data.FTC(f, c);
      if (t < 0 || t >= data.TC.rows())
        throw_input(data.path + ": texture index out of range in face " + std::to_string(f));
      if (seen[t] && m.V.row(t) != data.V.row(data.F(f, c)))
        throw_input(data.path + ": texture coordinate " + std::to_string(t) +
                    " is shared by corners at different positions");
      m.V.row(t) = data.V.row(data.F(f, c));
      seen[t] = 1;
    }
  m.F = data.FTC;
  m.UV = data.TC;
  m.input_vertices = data.V.rows();
  return m;
}

}  // namespace intrinsic::app
