// The seams file of `intrinsic atlas --seams FILE` (issue 13, "uses the
// user's own seams, as artists mark them"): one edge per line, `i j`, two
// 0-based vertex indices in the input's vertex order (as boundary files),
// `#` comments and blank lines allowed. Each pair must be an edge of a face.
#include <charconv>
#include <sstream>
#include <unordered_set>

#include "intrinsic/atlas.h"
#include "intrinsic/error.h"
#include "io/text_file.h"

namespace intrinsic {
namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

int parse_index(const std::string& s, long long num_vertices, const std::string& at) {
  long long v = 0;
  auto [p, e] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (e != std::errc() || p != s.data() + s.size()) throw_input(at + "'" + s + "' is not a vertex index");
  if (v < 0 || v >= num_vertices)
    throw_input(at + "vertex " + s + " is out of range (the mesh has " + std::to_string(num_vertices) + " vertices)");
  return static_cast<int>(v);
}

}  // namespace

std::vector<SeamEdge> parse_seams_text(const std::string& text, const std::string& name, const MeshData& mesh) {
  std::unordered_set<std::uint64_t> edges;
  for (int f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) edges.insert(edge_key(mesh.F(f, c), mesh.F(f, (c + 1) % 3)));
  std::vector<SeamEdge> out;
  std::unordered_set<std::uint64_t> seen;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string at = name + ":" + std::to_string(line_no) + ": ";
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream fields(line);
    std::string a, b, extra;
    if (!(fields >> a)) continue;  // blank or comment
    if (!(fields >> b)) throw_input(at + "expected 'i j' (two vertex indices of an edge)");
    if (fields >> extra) throw_input(at + "unexpected '" + extra + "' after 'i j'");
    const int i = parse_index(a, mesh.V.rows(), at), j = parse_index(b, mesh.V.rows(), at);
    if (i == j || !edges.count(edge_key(i, j)))
      throw_input(at + "vertices " + a + " and " + b + " are not an edge of any face");
    if (seen.insert(edge_key(i, j)).second) out.push_back({i, j});  // a repeated line changes nothing
  }
  if (out.empty()) throw_input(name + ": no seam edges");
  return out;
}

std::vector<SeamEdge> read_seams_file(const std::string& path, const MeshData& mesh) {
  return parse_seams_text(detail::read_text_file(path, "seams file"), path, mesh);
}

}  // namespace intrinsic
