// Reading a small text input file whole (see text_file.h).
#include "io/text_file.h"

#include <cerrno>
#include <fstream>
#include <sstream>

#include "intrinsic/error.h"

namespace intrinsic::detail {

std::string read_text_file(const std::string& path, const std::string& what) {
  // The stream opens the file with open(2), whose errno (missing file,
  // permission) it leaves in place; cleared first so another reason is 0.
  errno = 0;
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    const int err = errno;
    throw_input_file("cannot open " + what + " '" + path + "'", err);
  }
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

void for_each_record(const std::string& text, const std::string& name, const RecordFn& record) {
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  std::vector<std::string> fields;
  while (std::getline(in, line)) {
    ++line_no;
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    fields.clear();
    for (std::string w; words >> w;) fields.push_back(w);
    if (!fields.empty()) record(fields, name + ":" + std::to_string(line_no) + ": ", line_no);
  }
}

}  // namespace intrinsic::detail
