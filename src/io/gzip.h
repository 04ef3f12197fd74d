// Whole-buffer gzip decompression for ".gz" meshes. Compressed input is
// recognised by its magic bytes, not by the name, and inflation stops at a
// size cap so that a small "zip bomb" cannot exhaust memory.
#pragma once

#include <cstdint>
#include <string>

namespace intrinsic::io {

bool is_gzip(const std::string& bytes);

// Inflates every gzip member in `bytes`. Throws Error(Input) naming `name` if
// the data is corrupt, truncated, or would inflate beyond `max_bytes`.
std::string gunzip(const std::string& bytes, const std::string& name, std::uint64_t max_bytes);

}  // namespace intrinsic::io
