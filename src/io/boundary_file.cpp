// The boundary file format: "vertex_index u v" per line, '#' comments.
#include <charconv>
#include <cmath>
#include <sstream>
#include <unordered_set>

#include "intrinsic/io.h"
#include "intrinsic/boundary.h"
#include "intrinsic/error.h"
#include "io/text_file.h"

namespace intrinsic {

std::vector<FixedVertex> parse_boundary_text(const std::string& text, const std::string& name, int num_vertices) {
  std::vector<FixedVertex> out;
  std::unordered_set<int> seen;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string at = name + ":" + std::to_string(line_no) + ": ";
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream fields(line);
    std::string a, b, c, extra;
    if (!(fields >> a)) continue;  // blank or comment
    if (!(fields >> b >> c)) throw_input(at + "expected 'vertex_index u v'");
    if (fields >> extra) throw_input(at + "unexpected '" + extra + "' after 'vertex_index u v'");
    long long v = 0;
    auto [pv, ev] = std::from_chars(a.data(), a.data() + a.size(), v);
    if (ev != std::errc() || pv != a.data() + a.size()) throw_input(at + "'" + a + "' is not a vertex index");
    double u = 0, w = 0;
    auto [pu, eu] = std::from_chars(b.data(), b.data() + b.size(), u);
    auto [pw, ew] = std::from_chars(c.data(), c.data() + c.size(), w);
    if (eu != std::errc() || pu != b.data() + b.size()) throw_input(at + "'" + b + "' is not a number");
    if (ew != std::errc() || pw != c.data() + c.size()) throw_input(at + "'" + c + "' is not a number");
    if (!std::isfinite(u) || !std::isfinite(w)) throw_input(at + "non-finite position");
    if (v < 0 || v >= num_vertices)
      throw_input(at + "vertex " + a + " is out of range (the mesh has " + std::to_string(num_vertices) + " vertices)");
    if (!seen.insert(static_cast<int>(v)).second) throw_input(at + "vertex " + a + " is listed twice");
    out.push_back({static_cast<int>(v), Eigen::Vector2d(u, w)});
  }
  if (out.empty()) throw_input(name + ": no boundary positions");
  return out;
}

std::vector<FixedVertex> read_boundary_file(const std::string& path, int num_vertices) {
  return parse_boundary_text(detail::read_text_file(path, "boundary file"), path, num_vertices);
}

}  // namespace intrinsic
