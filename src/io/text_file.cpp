// Reading a small text input file whole (see text_file.h).
#include "io/text_file.h"

#include <fstream>
#include <sstream>

#include "intrinsic/error.h"

namespace intrinsic::detail {

std::string read_text_file(const std::string& path, const std::string& what) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw_input("cannot open " + what + " '" + path + "'");
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace intrinsic::detail
