// Mesh file names and size caps (io.h).

#include <algorithm>
#include <cctype>

#include "intrinsic/io.h"

namespace intrinsic {

std::string mesh_extension(const std::string& path) {
  std::string p = path;
  std::transform(p.begin(), p.end(), p.begin(), [](unsigned char c) { return std::tolower(c); });
  if (p.size() > 3 && p.compare(p.size() - 3, 3, ".gz") == 0) p.resize(p.size() - 3);
  const size_t dot = p.rfind('.');
  const size_t slash = p.rfind('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return p.substr(dot);
}

std::int64_t faces_for_vertices(std::int64_t max_vertices) {
  const std::int64_t default_cap = ReadOptions().max_faces;
  return max_vertices >= default_cap / 4 ? default_cap : 4 * max_vertices + 1000;
}

}  // namespace intrinsic
