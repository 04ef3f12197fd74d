// The boundary file format: "vertex_index u v" per line, '#' comments.
#include <charconv>
#include <cmath>
#include <unordered_set>

#include "intrinsic/io.h"
#include "intrinsic/boundary.h"
#include "intrinsic/error.h"
#include "io/text_file.h"

namespace intrinsic {

std::vector<FixedVertex> parse_boundary_text(const std::string& text, const std::string& name, int num_vertices) {
  std::vector<FixedVertex> out;
  std::unordered_set<int> seen;
  detail::for_each_record(text, name, [&](const std::vector<std::string>& fields, const std::string& at, int) {
    if (fields.size() < 3) throw_input(at + "expected 'vertex_index u v'");
    if (fields.size() > 3) throw_input(at + "unexpected '" + fields[3] + "' after 'vertex_index u v'");
    const std::string &a = fields[0], &b = fields[1], &c = fields[2];
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
  });
  if (out.empty()) throw_input(name + ": no boundary positions");
  return out;
}

std::vector<FixedVertex> read_boundary_file(const std::string& path, int num_vertices) {
  return parse_boundary_text(detail::read_text_file(path, "boundary file"), path, num_vertices);
}

}  // namespace intrinsic
