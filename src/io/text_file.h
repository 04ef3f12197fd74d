// A small text input file read whole (boundary, constraint and seams files):
// one place for opening and its error message.
#pragma once

#include <string>

namespace intrinsic::detail {

// The bytes of `path`. Throws Error(Input) "cannot open WHAT 'PATH'" with
// the errno of the failed open (Error::os_error).
std::string read_text_file(const std::string& path, const std::string& what);

}  // namespace intrinsic::detail
