// Fuzzes the STL reader (ASCII and binary) through read_mesh_from_memory.
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  return fuzz::expect_only_error([&] {
    read_mesh_from_memory(std::string(reinterpret_cast<const char*>(data), size), "fuzz.stl", fuzz::small_limits());
  });
}
