// Perceptually ordered colour map (dark violet -> blue -> green -> yellow)
// for scalar fields; lightness increases monotonically so the ordering reads
// correctly in greyscale print too.
#pragma once

#include "render/image.h"

namespace intrinsic::render {

// t is clamped to [0, 1]; NaN gives the "no data" grey.
Rgb colormap(double t);

inline constexpr Rgb kNoDataGrey = {150, 150, 150};

}  // namespace intrinsic::render
