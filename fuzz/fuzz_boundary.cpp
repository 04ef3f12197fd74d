// Fuzzes the boundary file parser ("vertex_index u v" lines).
#include "fuzz_support.h"
#include "intrinsic/io.h"
#include "intrinsic/boundary.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  return fuzz::expect_only_error([&] {
    parse_boundary_text(std::string(reinterpret_cast<const char*>(data), size), "fuzz.txt", 100);
  });
}
