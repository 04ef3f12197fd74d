"""intrinsic.transfer_texture and compute_tangents on numpy arrays: an image
that is a smooth function of the old UVs, moved into a layout where every
triangle is turned and placed elsewhere, reads the same function at every
covered texel centre (computed here through the new triangle's barycentric
coordinates); an identity layout gives the image back exactly; bad
arguments are UsageErrors naming the keyword."""
import numpy as np
import pytest

import intrinsic


def grid_triangles(n):
    """Old UVs of a grid of 2 n^2 triangles over [0, 1]^2, 3 rows per face."""
    tris = []
    for i in range(n):
        for j in range(n):
            a, b, c, d = (i / n, j / n), ((i + 1) / n, j / n), ((i + 1) / n, (j + 1) / n), (i / n, (j + 1) / n)
            tris += [a, b, c, a, c, d]
    return np.array(tris, dtype=np.float64)


def f(uv):
    return np.stack([0.5 + 0.4 * np.sin(2 * np.pi * uv[..., 0]), 0.5 + 0.4 * np.cos(2 * np.pi * uv[..., 1])], axis=-1)


def test_shuffled_layout_reads_the_function():
    n, size, out = 4, 256, 512
    old = grid_triangles(n)
    # New layout: each triangle turned a quarter, shrunk and moved to its own cell of an 8 x 4 grid.
    new = np.empty_like(old)
    for t in range(len(old) // 3):
        tri = old[3 * t:3 * t + 3]
        c = tri.mean(axis=0)
        rot = (tri - c) @ np.array([[0.0, -1.0], [1.0, 0.0]]) * 0.45  # 0.1125 across: inside its cell
        cell = np.array([(t % 8 + 0.5) / 8, (t // 8 + 0.5) / 4])
        new[3 * t:3 * t + 3] = rot + cell
    x = (np.arange(size) + 0.5) / size
    U, V = np.meshgrid(x, x)  # rows: v down (image convention), top row first
    image = f(np.stack([U, V], axis=-1)).astype(np.float32)
    baked = intrinsic.transfer_texture(old, new, image, width=out, height=out, role="data", padding=0)
    assert baked.shape == (out, out, 2)
    worst, checked = 0.0, 0
    centres = (np.arange(out) + 0.5) / out
    for t in range(len(old) // 3):
        A = new[3 * t:3 * t + 3]
        M = np.array([A[1] - A[0], A[2] - A[0]]).T
        lo, hi = A.min(axis=0), A.max(axis=0)
        xs = centres[(centres > lo[0]) & (centres < hi[0])]
        ys = centres[(centres > lo[1]) & (centres < hi[1])]
        for y in ys:
            for xx in xs:
                l1, l2 = np.linalg.solve(M, np.array([xx, y]) - A[0])
                if min(l1, l2, 1 - l1 - l2) < 1e-9:
                    continue
                uv_old = old[3 * t] + l1 * (old[3 * t + 1] - old[3 * t]) + l2 * (old[3 * t + 2] - old[3 * t])
                got = baked[int(y * out), int(xx * out)]
                worst = max(worst, np.abs(got - f(uv_old)).max())
                checked += 1
    assert checked > 10000
    # Bilinear interpolation of f (second derivative <= 0.4 (2 pi)^2) over a texel h = 1/256:
    # error <= h^2 / 8 * 0.4 * (2 pi)^2 * 2 ~ 6e-5, plus float32 rounding.
    assert worst < 2e-4


def test_identity_layout_is_exact():
    old = grid_triangles(3)
    image = np.random.default_rng(1).random((32, 32, 4)).astype(np.float32)
    baked = intrinsic.transfer_texture(old, old, image, width=32, height=32, role="data")
    assert np.array_equal(baked, image)


def test_bad_arguments():
    old = grid_triangles(2)
    image = np.zeros((8, 8, 3), np.float32)
    with pytest.raises(intrinsic.UsageError, match="role"):
        intrinsic.transfer_texture(old, old, image, role="albedo")
    with pytest.raises(intrinsic.UsageError, match="wrap_u"):
        intrinsic.transfer_texture(old, old, image, wrap_u="tile")
    with pytest.raises(intrinsic.UsageError, match="image"):
        intrinsic.transfer_texture(old, old, np.zeros((8, 8, 5), np.float32))
    with pytest.raises(intrinsic.UsageError, match="normals"):
        intrinsic.transfer_texture(old, old, image, role="normal")


def test_tangents_of_a_plane():
    old = grid_triangles(2)
    P = np.c_[old, np.zeros(len(old))]
    N = np.tile([0.0, 0.0, 1.0], (len(old), 1))
    T = intrinsic.compute_tangents(P, N, old)
    assert T.shape == (len(old), 4)
    assert np.allclose(T[:, :3], [1, 0, 0]) and np.all(np.abs(T[:, 3]) == 1)
