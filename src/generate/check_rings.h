// The ring count's range, shared by the generated surfaces that take one.
#pragma once

#include "intrinsic/error.h"
#include "intrinsic/generate.h"

namespace intrinsic::detail {

inline void check_rings(const GenerateOptions& o) {
  if (o.rings < 1 || o.rings > 5000) throw_usage("rings must be between 1 and 5000");
}

}  // namespace intrinsic::detail
