// The seams file of `intrinsic atlas --seams FILE` (so the atlas uses the
// user's own seams, as artists mark them): one edge per line, `i j`, two
// 0-based vertex indices in the input's vertex order (as boundary files),
// `#` comments and blank lines allowed. Each pair must be an edge of a face
// (find_seam_problem, src/atlas/seam_edges.cpp).
#include <charconv>
#include <sstream>
#include <set>

#include "intrinsic/atlas_files.h"
#include "intrinsic/io.h"
#include "intrinsic/atlas.h"
#include "intrinsic/error.h"
#include "io/text_file.h"

namespace intrinsic {
namespace {

int parse_index(const std::string& s, long long num_vertices, const std::string& at) {
  long long v = 0;
  auto [p, e] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (e != std::errc() || p != s.data() + s.size()) throw_input(at + "'" + s + "' is not a vertex index");
  if (v < 0 || v >= num_vertices)
    throw_input(at + "vertex " + s + " is out of range (the mesh has " + std::to_string(num_vertices) + " vertices)");
  return static_cast<int>(v);
}

}  // namespace

// Syntax and range here, line by line; whether each pair is an edge is the
// library's one check (find_seam_problem), its seam index mapped back to the
// line that listed it.
std::vector<SeamEdge> parse_seams_text(const std::string& text, const std::string& name, const MeshData& mesh) {
  std::vector<SeamEdge> out;
  std::vector<int> line_of;  // per seam in `out`
  std::set<std::pair<int, int>> seen;
  detail::for_each_record(text, name, [&](const std::vector<std::string>& fields, const std::string& at, int line_no) {
    if (fields.size() < 2) throw_input(at + "expected 'i j' (two vertex indices of an edge)");
    if (fields.size() > 2) throw_input(at + "unexpected '" + fields[2] + "' after 'i j'");
    const std::string &a = fields[0], &b = fields[1];
    const int i = parse_index(a, mesh.V.rows(), at), j = parse_index(b, mesh.V.rows(), at);
    if (!seen.insert({std::min(i, j), std::max(i, j)}).second) return;  // a repeated line changes nothing
    out.push_back({i, j});
    line_of.push_back(line_no);
  });
  if (out.empty()) throw_input(name + ": no seam edges");
  const SeamProblem p = find_seam_problem(mesh, out);
  if (p.index >= 0) throw_input(name + ":" + std::to_string(line_of[p.index]) + ": " + p.message);
  return out;
}

std::vector<SeamEdge> read_seams_file(const std::string& path, const MeshData& mesh) {
  return parse_seams_text(detail::read_text_file(path, "seams file"), path, mesh);
}

}  // namespace intrinsic
