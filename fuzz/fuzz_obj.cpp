// Fuzzes the OBJ reader through read_mesh_from_memory.
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  return fuzz::expect_only_error([&] {
    read_mesh_from_memory(std::string(reinterpret_cast<const char*>(data), size), "fuzz.obj", fuzz::small_limits());
  });
}
