"""Throughput of ``python3 -m intrinsic.batch`` with 1 and 2 local workers.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/batch_throughput.py [MESH_DIR] [--runs 3]

Input: every mesh file directly in MESH_DIR (default ../shared/meshes next to
the source tree) except max-planck-partial-loop2.obj.gz, linked into a
temporary folder. Each run writes into a fresh output folder (nothing
skipped) and is timed as a whole command (Python start, LocalCluster start,
all files, shutdown). Prints per worker count the median of the runs: total
seconds, files/s, the sum of per-file seconds from the manifest, and how
many files were done / failed (closed meshes fail as the CLI does).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
EXCLUDE = {"max-planck-partial-loop2.obj.gz"}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesh_dir", nargs="?", default=str(HERE.parent.parent.parent / "shared" / "meshes"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("options", nargs=argparse.REMAINDER, help="after --: param options for the batch")
    a = ap.parse_args()
    options = [o for o in a.options if o != "--"]
    from intrinsic.batch import mesh_stem

    with tempfile.TemporaryDirectory(prefix="batch_bench_") as tmp:
        src = Path(tmp) / "in"
        src.mkdir()
        names = sorted(p.name for p in Path(a.mesh_dir).iterdir()
                       if p.is_file() and mesh_stem(p.name) and p.name not in EXCLUDE)
        for n in names:
            os.symlink(Path(a.mesh_dir).resolve() / n, src / n)
        print(f"{len(names)} files: {' '.join(names)}", flush=True)
        for w in map(int, a.workers.split(",")):
            walls, work, counts = [], [], None
            for run in range(a.runs):
                out = Path(tmp) / f"out_{w}_{run}"
                t0 = time.perf_counter()
                p = subprocess.run([sys.executable, "-m", "intrinsic.batch", str(src), str(out), "--workers", str(w),
                                    "-q", *options], capture_output=True, text=True)
                walls.append(time.perf_counter() - t0)
                if p.returncode not in (0, 1):
                    sys.exit(p.stderr)
                m = json.loads((out / "manifest.json").read_text())
                work.append(sum(e["seconds"] for e in m["files"]))
                counts = m["counts"]
                print(f"  workers={w} run {run}: {walls[-1]:.2f} s", flush=True)
            t = statistics.median(walls)
            print(f"workers={w}: {t:.2f} s total, {len(names) / t:.2f} files/s (median of {a.runs}); "
                  f"per-file seconds summed {statistics.median(work):.2f} s; done {counts['done']}, "
                  f"failed {counts['failed']}", flush=True)


if __name__ == "__main__":
    main()
