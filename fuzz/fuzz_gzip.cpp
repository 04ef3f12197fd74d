// Fuzzes gzip inflation (and the reader behind it) through read_mesh_from_memory
// with a ".gz" name; the inner format is picked from the input size so that
// every reader sees decompressed data.
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace intrinsic;
  static const char* const kNames[] = {"fuzz.obj.gz", "fuzz.off.gz", "fuzz.ply.gz"};
  return fuzz::expect_only_error([&] {
    read_mesh_from_memory(std::string(reinterpret_cast<const char*>(data), size), kNames[size % 3],
                          fuzz::small_limits());
  });
}
