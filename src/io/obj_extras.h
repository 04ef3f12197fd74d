// What an OBJ carries beyond positions, texture coordinates and faces, as the
// reader collects it (docs/formats.md, "OBJ"): normals with per-corner
// indices, the mtllib lines, and the state statements usemtl, g, o and s as
// per-face labels (ObjExtras, mesh_document.h). Nothing per face is allocated
// until the file uses it, so plain meshes pay one branch per face.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "intrinsic/mesh_document.h"
#include "io/text_scan.h"

namespace intrinsic::io {

// One kind of state statement while the file is read.
class LabelTrack {
 public:
  // A statement of this kind: `name` is in force for the faces that follow.
  void set(std::string_view name);
  // Labels the next `n` triangles, `before` triangles having been read
  // already (those before the first statement get -1).
  void tag(std::size_t before, std::size_t n, std::size_t hint) {
    if (current_ < 0 && labels_.of_face.empty()) return;
    if (labels_.of_face.empty()) {
      labels_.of_face.reserve(std::max(hint, before + n));
      labels_.of_face.assign(before, -1);
    }
    labels_.of_face.insert(labels_.of_face.end(), n, current_);
  }
  FaceLabels take() { return std::move(labels_); }

 private:
  FaceLabels labels_;
  std::unordered_map<std::string, int> index_;  // name -> row of labels_.names
  int current_ = -1;
};

struct ObjExtrasBuilder {
  std::vector<double> normal;  // 3 per `vn`
  // 3 per triangle, the 0-based normal of each corner or -1; empty until a
  // corner names a normal.
  std::vector<int> tri_n;
  std::vector<std::string> material_libraries;
  LabelTrack materials, groups, objects, smoothing;
  std::size_t triangle_hint = 0;  // the expected face count, to reserve per-face arrays once

  std::int64_t normal_count() const { return static_cast<std::int64_t>(normal.size() / 3); }

  // Reads the x y z of a `vn` line (keyword already consumed); at most
  // `limit` normals.
  void read_normal(TextScanner& s, std::int64_t limit);
  // mtllib, usemtl, g, o, s (keyword already consumed): keeps the rest of the
  // line. Any other keyword is ignored.
  void read_statement(std::string_view keyword, TextScanner& s);
  // The corner normals of one triangle (-1: none), `before` triangles having
  // been read already.
  void add_triangle_normals(std::size_t before, int n0, int n1, int n2) {
    if (tri_n.empty()) {
      if (n0 < 0 && n1 < 0 && n2 < 0) return;
      tri_n.reserve(std::max(triangle_hint, before + 1) * 3);
      tri_n.assign(before * 3, -1);
    }
    tri_n.push_back(n0);
    tri_n.push_back(n1);
    tri_n.push_back(n2);
  }
  void tag_triangles(std::size_t before, std::size_t n) {
    materials.tag(before, n, triangle_hint);
    groups.tag(before, n, triangle_hint);
    objects.tag(before, n, triangle_hint);
    smoothing.tag(before, n, triangle_hint);
  }
  // Range-checks the normal indices once every `vn` is known (positive
  // indices may refer forward), naming the face's line.
  void check(const TextScanner& s, const std::vector<int>& line) const;
  // Everything read, as the file's document keeps it (normals only if a
  // corner uses them).
  ObjExtras finish();
};

}  // namespace intrinsic::io
