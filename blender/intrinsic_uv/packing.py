"""Places the unpinned islands of `uv.intrinsic_unwrap` in [0,1]^2
(docs/blender.md): bounding boxes on shelves, tallest first, left to right,
a new shelf when a row passes 1.2 x the square root of the boxes' total area
(or the widest box), the same rule as the library's own layout of several
charts (src/core/shelf_packing.h). The islands come with parameter area =
3D area (scale "surface"), so one common scale keeps their relative sizes;
the whole layout is then scaled to fit the unit square. Only translations
and one uniform scale: each island's map stays a similarity of the
library's. Pinned islands are not passed here: they stay where the pins put
them, as in Blender's own Unwrap.
"""
import math

import numpy as np


def _shelves(sizes, gap):
    """Lower-left corners of boxes of the given (w, h) sizes, and the extent."""
    total = sum(w * h for w, h in sizes)
    row_limit = max(1.2 * math.sqrt(total), max(w for w, _ in sizes))
    order = sorted(range(len(sizes)), key=lambda k: -sizes[k][1])  # stable: equal heights keep their order
    corners = [None] * len(sizes)
    x = y = shelf_height = width = 0.0
    for k in order:
        w, h = sizes[k]
        if x > 0 and x + w > row_limit:
            y += shelf_height + gap
            x = shelf_height = 0.0
        corners[k] = (x, y)
        x += w + gap
        shelf_height = max(shelf_height, h)
        width = max(width, x - gap)
    return corners, max(width, y + shelf_height)


def pack(uvs, margin):
    """Moves and scales the islands' UV arrays (each n x 2) in place into
    [0,1]^2. `margin`: the gap between boxes as a fraction of the square root
    of their total area, before the common scale."""
    if not uvs:
        return
    lo = [uv.min(axis=0) for uv in uvs]
    sizes = [tuple(uv.max(axis=0) - l) for uv, l in zip(uvs, lo)]
    gap = margin * math.sqrt(sum(w * h for w, h in sizes))
    corners, extent = _shelves(sizes, gap)
    scale = 1.0 / extent if extent > 0 else 1.0
    for uv, l, c in zip(uvs, lo, corners):
        uv -= l
        uv += np.asarray(c)
        uv *= scale
