// The user's seams (`--seams FILE`; docs/maths.md §9.6): the one
// check that each listed pair is an edge of a face (find_seam_problem, used
// by atlas() and, for file and line, by the seams file reader) and the cut
// itself (no face is glued across a seam for the computation); and the
// hard edges (`--hard-angle`), cut the same way.
#include <cmath>
#include <unordered_map>

#include "atlas/atlas_internal.h"
#include "intrinsic/error.h"

namespace intrinsic {
namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// The first seam out of range or not an edge of a face; with `cut`, every
// half-edge of a face on a seam is set there to -1 (a seam for the computation).
SeamProblem match_seams(const MeshData& mesh, const std::vector<SeamEdge>& seams, std::vector<int>* cut) {
  const long long nv = mesh.V.rows();
  SeamProblem p;
  std::unordered_map<std::uint64_t, char> found;  // seam edge -> seen on a face
  for (size_t i = 0; i < seams.size() && p.index < 0; ++i) {
    const SeamEdge& e = seams[i];
    for (int v : {e.a, e.b})
      if (p.index < 0 && (v < 0 || v >= nv)) {
        p.index = static_cast<int>(i);
        p.message = "vertex " + std::to_string(v) + " is out of range (the mesh has " + std::to_string(nv) + " vertices)";
      }
    if (p.index < 0 && e.a != e.b) found.emplace(edge_key(e.a, e.b), 0);
  }
  const size_t in_range = p.index < 0 ? seams.size() : static_cast<size_t>(p.index);
  for (int f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const auto it = found.find(edge_key(mesh.F(f, c), mesh.F(f, (c + 1) % 3)));
      if (it == found.end()) continue;
      it->second = 1;
      if (cut) (*cut)[3 * f + c] = -1;
    }
  for (size_t i = 0; i < in_range; ++i) {
    const SeamEdge& e = seams[i];
    if (e.a != e.b && found.at(edge_key(e.a, e.b))) continue;
    p.index = static_cast<int>(i);
    p.message = "vertices " + std::to_string(e.a) + " and " + std::to_string(e.b) + " are not an edge of any face";
    break;
  }
  return p;
}

}  // namespace

SeamProblem find_seam_problem(const MeshData& mesh, const std::vector<SeamEdge>& seams) {
  return match_seams(mesh, seams, nullptr);
}

namespace detail {

void cut_seams(const MeshData& input, const std::vector<SeamEdge>& seams, CleanMesh& clean) {
  const SeamProblem p = match_seams(input, seams, &clean.glued);
  if (p.index >= 0) throw_input("seam edge " + std::to_string(p.index) + ": " + p.message);
}

int cut_hard_edges(double hard_angle_deg, CleanMesh& clean) {
  // Normals are those of the orientation used (reversed faces turned), so
  // the angle between them is the dihedral angle's complement to pi.
  const double limit = std::cos(hard_angle_deg * M_PI / 180);
  int cut = 0;
  for (size_t h = 0; h < clean.glued.size(); ++h) {
    const int g = clean.glued[h];
    if (g < 0 || clean.normal[h / 3].dot(clean.normal[g]) >= limit) continue;
    clean.glued[h] = -1;
    ++cut;
  }
  return cut / 2;  // each edge has two half-edges
}

}  // namespace detail
}  // namespace intrinsic
