"""Thread scaling of intrinsic.parameterize (the GIL is released while
solving): one call, then two threads each parameterizing its own mesh.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/threads.py build/intrinsic [RINGS]

Generates two wave surfaces with the CLI (`intrinsic generate wave`, about
3*RINGS^2 vertices; default 183: 100k) and prints medians of 3 runs.
"""
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import intrinsic


def timed(f):
    t = time.perf_counter()
    f()
    return time.perf_counter() - t


def main():
    cli, rings = sys.argv[1], (sys.argv[2] if len(sys.argv) > 2 else "183")
    with tempfile.TemporaryDirectory() as d:
        meshes = []
        for seed in ("1", "2"):
            p = Path(d) / f"wave{seed}.obj"
            subprocess.run([cli, "generate", "wave", "--rings", rings, "--seed", seed, "-o", str(p)], check=True,
                           capture_output=True)
            meshes.append(intrinsic.read_mesh(p))
    print(f"{meshes[0][0].shape[0]} vertices per mesh")
    one = statistics.median(timed(lambda: intrinsic.parameterize(*meshes[0])) for _ in range(3))

    def two():
        ts = [threading.Thread(target=intrinsic.parameterize, args=m) for m in meshes]
        for t in ts:
            t.start()
        for t in ts:
            t.join()

    both = statistics.median(timed(two) for _ in range(3))
    print(f"one mesh {one:.3f} s; two meshes in two threads {both:.3f} s ({both / one:.2f}x one; 2x = no overlap)")


if __name__ == "__main__":
    main()
