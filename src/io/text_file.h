// A small text input file read whole (boundary, constraint and seams files):
// one place for opening and its error message, and for the line-of-fields
// syntax the boundary and seams files share.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace intrinsic::detail {

// The bytes of `path`. Throws Error(Input) "cannot open WHAT 'PATH'" with
// the errno of the failed open (Error::os_error).
std::string read_text_file(const std::string& path, const std::string& what);

// Calls record(fields, at, line_no) for every line of `text` that holds
// whitespace-separated fields once a '#' comment is cut off (blank lines
// are skipped); `at` is "NAME:LINE: ", the prefix of a message about it.
using RecordFn = std::function<void(const std::vector<std::string>& fields, const std::string& at, int line_no)>;
void for_each_record(const std::string& text, const std::string& name, const RecordFn& record);

}  // namespace intrinsic::detail
