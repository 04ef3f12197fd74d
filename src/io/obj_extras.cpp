// The OBJ reader's keeping of normals, material libraries and state
// statements (obj_extras.h; docs/formats.md, "OBJ").
#include "io/obj_extras.h"

#include <algorithm>
#include <cmath>

namespace intrinsic::io {

namespace {

// The rest of the current line, without surrounding blanks. Names are kept
// verbatim, '#' included: exporters write material names such as
// "Material #25", and giving back exactly what was read is the point.
std::string_view rest_of_line(TextScanner& s) {
  s.skip_blanks();
  const char* b = s.pos();
  const char* e = std::find(b, s.end(), '\n');  // statements are few: no need for memchr
  while (e > b && is_blank(e[-1])) --e;
  return {b, static_cast<std::size_t>(e - b)};
}

}  // namespace

void LabelTrack::set(std::string_view name) {
  const auto [it, fresh] = index_.emplace(std::string(name), static_cast<int>(labels_.names.size()));
  if (fresh) labels_.names.emplace_back(name);
  current_ = it->second;
}

void ObjExtrasBuilder::read_normal(TextScanner& s, std::int64_t limit) {
  double c[3];
  for (double& x : c) {
    if (!s.parse_double(x)) s.fail("expected a number after 'vn'");
  }
  if (normal_count() >= limit) s.fail("more than " + std::to_string(limit) + " normals (the limit)");
  if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]))
    s.fail("normal " + std::to_string(normal_count() + 1) + " has a non-finite coordinate");
  normal.insert(normal.end(), c, c + 3);
}

void ObjExtrasBuilder::read_statement(std::string_view keyword, TextScanner& s) {
  if (keyword == "usemtl") materials.set(rest_of_line(s));
  else if (keyword == "g") groups.set(rest_of_line(s));
  else if (keyword == "o") objects.set(rest_of_line(s));
  else if (keyword == "s") smoothing.set(rest_of_line(s));
  else if (keyword == "mtllib") material_libraries.emplace_back(rest_of_line(s));
}

void ObjExtrasBuilder::check(const TextScanner& s, const std::vector<int>& line) const {
  const std::int64_t n = normal_count();
  for (std::size_t i = 0; i < tri_n.size(); ++i) {
    if (tri_n[i] >= n) {
      s.fail_at(line[i / 3], "face normal index " + std::to_string(std::int64_t(tri_n[i]) + 1) +
                                 " out of range (file has " + std::to_string(n) + " normals)");
    }
  }
}

ObjExtras ObjExtrasBuilder::finish() {
  using RowX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  using RowX3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
  ObjExtras x;
  if (!tri_n.empty()) {
    x.N = Eigen::Map<const RowX3d>(normal.data(), normal_count(), 3);
    x.FN = Eigen::Map<const RowX3i>(tri_n.data(), static_cast<Eigen::Index>(tri_n.size() / 3), 3);
  }
  x.material_libraries = std::move(material_libraries);
  x.materials = materials.take();
  x.groups = groups.take();
  x.objects = objects.take();
  x.smoothing = smoothing.take();
  return x;
}

}  // namespace intrinsic::io
