"""``python3 -m intrinsic.batch INPUT_DIR OUTPUT_DIR [options]``: ``intrinsic param``
(or, with ``--command atlas``, ``intrinsic atlas``) over every mesh file of a
folder, on a Dask cluster (docs/python.md "Batches").

Every ``.obj``, ``.off`` and ``.ply`` file of INPUT_DIR (optionally ``.gz``; not
recursive) is one task: the worker runs :func:`intrinsic.parameterize` on the
file with the given options (the command line's ``param`` options, same
names), writes ``OUTPUT_DIR/NAME.obj`` (or ``.ply``) and then the report
``OUTPUT_DIR/NAME.report.json``, each to a temporary file in OUTPUT_DIR renamed
into place. The report, written last, marks a file as complete: a rerun skips
every file whose report exists, names the same input and output, and whose
output exists. A failing file is recorded (kind, exit code and message as the
command line gives them) and never stops the batch.

``OUTPUT_DIR/manifest.json`` (written atomically, also while the batch runs)
lists every file: input, status (done, skipped, failed), kind (None when
done or skipped; usage, input, numerical, output, internal), exit_code (what
``intrinsic param`` would return: 0, 1-4, 5 for internal), message, output,
report, seconds.

Exit code: 0 when every file is done or skipped, 1 otherwise; 2 when the
batch's own command line is wrong (argparse's convention: unknown option,
bad value, missing INPUT_DIR, an option combination ``intrinsic param``
refuses).

The cluster: ``--workers N`` local worker processes (default 2, one thread
each; Dask sets OMP/OPENBLAS/MKL_NUM_THREADS=1 in them), or ``--scheduler
tcp://HOST:8786`` for a running cluster (``dask scheduler``, ``dask worker
tcp://HOST:8786``) whose workers import the same ``intrinsic`` package and see
INPUT_DIR and OUTPUT_DIR under the same paths.
"""

import argparse
import json
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any, Dict, List, Optional

MESH_SUFFIXES = (".obj", ".off", ".ply", ".stl")
KINDS = {"UsageError": "usage", "InputError": "input", "NumericalError": "numerical", "OutputError": "output"}
INTERNAL_EXIT_CODE = 5  # the command line's code for an internal error
MANIFEST = "manifest.json"


# --------------------------------------------------------------------------- files

def mesh_stem(name: str) -> Optional[str]:
    """'a.obj' -> 'a', 'a.ply.gz' -> 'a'; None when not a mesh file name."""
    base = name[:-3] if name.lower().endswith(".gz") else name
    for s in MESH_SUFFIXES:
        if base.lower().endswith(s) and len(base) > len(s):
            return base[: -len(s)]
    return None


def find_inputs(input_dir: Path) -> List[Path]:
    return sorted(p for p in input_dir.iterdir() if p.is_file() and mesh_stem(p.name) is not None)


def plan_outputs(inputs: List[Path], output_dir: Path, fmt: str) -> List[Dict[str, str]]:
    """Output and report path per input: NAME.obj and NAME.report.json, NAME
    the file name without extension (and .gz); when two inputs share NAME
    (a.obj, a.off) they keep their whole file name (a.obj.obj, a.off.obj)."""
    stems = [mesh_stem(p.name) for p in inputs]
    jobs = []
    for p, stem in zip(inputs, stems):
        name = stem if stems.count(stem) == 1 else p.name
        jobs.append({"input": str(p), "output": str(output_dir / f"{name}.{fmt}"),
                     "report": str(output_dir / f"{name}.report.json")})
    return jobs


def write_atomic(path: str, text: str) -> None:
    """Writes `text` to a temporary file next to `path`, then renames it into place."""
    directory = os.path.dirname(path) or "."
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", suffix=".tmp", dir=directory)
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def is_complete(job: Dict[str, str]) -> bool:
    """The report exists, is valid JSON naming this input and output, and the output exists."""
    try:
        with open(job["report"]) as f:
            report = json.load(f)
    except (OSError, ValueError):
        return False
    return (isinstance(report, dict) and report.get("output") == job["output"]
            and report.get("input") == job["input"] and os.path.isfile(job["output"]))


# --------------------------------------------------------------------------- the task

def _solve_and_write(command: str, job: Dict[str, str], options: Dict[str, Any], binary: bool) -> Dict[str, Any]:
    """The command's result written to job["output"]; returns its report (timings without the write)."""
    import intrinsic
    if command == "atlas":
        r = intrinsic.atlas(job["input"], **options)
        intrinsic.write_atlas(job["output"], r)  # temp file + rename
    else:
        r = intrinsic.parameterize(job["input"], **options)
        intrinsic.write_mesh(job["output"], r.V, r.F, uv=r.uv, binary=binary)  # temp file + rename
    return r.report


def run_job(command: str, job: Dict[str, str], options: Dict[str, Any], binary: bool) -> Dict[str, Any]:
    """One file, in a worker: `param` or `atlas`, write the mesh, then the report.
    Never raises: failures become the entry's kind, exit_code and message."""
    t0 = time.perf_counter()
    entry: Dict[str, Any] = dict(input=job["input"], status="done", kind=None, exit_code=0, message="",
                                 output=job["output"], report=job["report"])
    try:
        import intrinsic
        try:
            t_solve = time.perf_counter()
            report = _solve_and_write(command, job, options, binary)
            report["output"] = job["output"]
            timings = dict(report.get("timings_ms") or {})
            solved = sum(v for k, v in timings.items() if k not in ("total", "read"))
            if command == "param":
                timings["render"] = 0.0
            # What the library did not time: the write (and, for param, nothing else).
            timings["write"] = max(0.0, (time.perf_counter() - t_solve) * 1e3 - solved)
            timings["total"] = (time.perf_counter() - t0) * 1e3
            report["timings_ms"] = timings
            write_atomic(job["report"], json.dumps(report, indent=2) + "\n")
        except intrinsic.Error as e:
            entry.update(status="failed", kind=KINDS.get(type(e).__name__, "internal"),
                         exit_code=int(getattr(e, "exit_code", INTERNAL_EXIT_CODE)), message=str(e))
    except MemoryError:
        entry.update(status="failed", kind="input", exit_code=2, message="out of memory")  # as the CLI
    except Exception as e:  # noqa: BLE001  (recorded, never stops the batch)
        entry.update(status="failed", kind="internal", exit_code=INTERNAL_EXIT_CODE,
                     message=f"{type(e).__name__}: {e}")
    if entry["status"] == "failed":
        try:  # no stale report claiming an earlier success
            os.unlink(job["report"])
        except OSError:
            pass
    entry["seconds"] = time.perf_counter() - t0
    return entry


# --------------------------------------------------------------------------- command line

def pair(text: str):
    parts = text.split(",")
    if len(parts) != 2:
        raise argparse.ArgumentTypeError(f"expected LO,HI, got {text!r}")
    return (float(parts[0]), float(parts[1]))


def make_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="python3 -m intrinsic.batch",
        description="Run `intrinsic param` on every mesh file (.obj .off .ply, optionally .gz) of INPUT_DIR "
                    "with Dask; write NAME.obj + NAME.report.json per file and OUTPUT_DIR/manifest.json. "
                    "Exit code 0 when every file is done or skipped, 1 otherwise, 2 for a bad command line.")
    p.add_argument("input_dir", metavar="INPUT_DIR")
    p.add_argument("output_dir", metavar="OUTPUT_DIR")
    p.add_argument("--command", default="param", choices=("param", "atlas"),
                   help="param (default) or atlas (whole assets: disk charts packed into [0,1]^2)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS", help="an existing Dask scheduler, e.g. tcp://host:8786")
    where.add_argument("--workers", type=int, metavar="N", help="local worker processes (default 2)")
    p.add_argument("--format", choices=("obj", "ply", "glb"),
                   help="output format (default obj; ply with --binary; atlas: obj or glb)")
    p.add_argument("--force", action="store_true", help="redo files whose output is already complete")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress on standard error")
    g = p.add_argument_group("param options (as `intrinsic param`, docs/param-options.md)")
    S = argparse.SUPPRESS  # only options given are passed: the library's defaults apply
    add_table_flags(g, param_table(), S)
    g.add_argument("--binary", action="store_true", help="binary little-endian PLY output")
    p.atlas_only = add_table_flags(p.add_argument_group("atlas options (as `intrinsic atlas`)"), atlas_table(), S)
    return p


BATCH_KEYS = {"input_dir", "output_dir", "command", "scheduler", "workers", "format", "force", "quiet", "binary"}


def atlas_table() -> List[Dict[str, Any]]:
    """The library's atlas options (intrinsic.atlas_option_table) that apply to a batch: all but seams,
    which name the edges of one mesh."""
    from intrinsic import _intrinsic
    return [o for o in _intrinsic.atlas_option_table() if o["key"] != "seams"]


def param_table() -> List[Dict[str, Any]]:
    """The library's param options (intrinsic.param_option_table): every one applies to a batch."""
    from intrinsic import _intrinsic
    return _intrinsic.param_option_table()


def add_table_flags(group, table: List[Dict[str, Any]], suppress) -> set:
    """One flag per option of a library table, as the library declares it, except flags the parser has
    already (the atlas options `param` shares: --method, --boundary, ...). Returns the keys added."""
    added = set()
    for o in table:
        kw: Dict[str, Any] = {"dest": o["key"], "default": suppress, "help": o["help"].replace("%", "%%")}
        if o["value_name"]:
            kw["metavar"] = o["value_name"]
        if o["type"] == "bool":
            kw["action"] = "store_false" if o["flag_negates"] else "store_true"
        elif o["type"] == "int":
            kw["type"] = int
        elif o["type"] == "float":
            kw["type"] = float
        elif o["type"] == "pair":
            kw["type"] = pair
        elif o["type"] == "choice":
            kw["choices"] = o["choices"]
        if o["repeated"]:
            kw["action"] = "append"
        try:
            group.add_argument(o["flag"], **kw)
            added.add(o["key"])
        except argparse.ArgumentError:  # a flag of the param group
            pass
    return added

# A small disk (hexagon fan around one interior vertex): the options are tried on
# it first, so a usage error (--lambda without --method mixed, an unknown value)
# stops the batch at once instead of failing every file.
_PROBE_V = [[0.0, 0.0, 0.0]] + [[float(x), float(y), 0.0] for x, y in
                                ((1, 0), (0.5, 0.866), (-0.5, 0.866), (-1, 0), (-0.5, -0.866), (0.5, -0.866))]
_PROBE_F = [[0, i, i % 6 + 1] for i in range(1, 7)]


def check_options(parser: argparse.ArgumentParser, command: str, options: Dict[str, Any]) -> None:
    import numpy as np

    import intrinsic
    atlas_keys = {o["key"] for o in atlas_table()}
    for key in options:
        if (key in parser.atlas_only and command != "atlas") or (key not in atlas_keys and command == "atlas"):
            parser.error(f"--{key.replace('_', '-')} does not apply to --command {command}")
    solve = intrinsic.atlas if command == "atlas" else intrinsic.parameterize
    try:
        solve(np.array(_PROBE_V), np.array(_PROBE_F, dtype=np.int32), **options)
    except intrinsic.UsageError as e:
        parser.error(str(e))
    except intrinsic.Error:
        pass  # input or numerical on the probe (pins, constraints for other meshes): the files decide


def parse(argv: Optional[List[str]]):
    parser = make_parser()
    a = parser.parse_args(argv)
    if a.workers is not None and a.workers < 1:
        parser.error("--workers: at least 1")
    if not Path(a.input_dir).is_dir():
        parser.error(f"INPUT_DIR {a.input_dir}: not a directory")
    fmt = a.format or ("ply" if a.binary else "obj")
    if a.binary and fmt != "ply":
        parser.error("--binary writes PLY: use --format ply")
    if a.command == "atlas" and fmt not in ("obj", "glb"):
        parser.error("--command atlas writes .obj (one texture coordinate per corner) or .glb")
    options = {k: v for k, v in vars(a).items() if k not in BATCH_KEYS}
    for key in ("boundary", "constraints"):  # files: absolute, so that workers find them
        if key in options and os.path.exists(options[key]):
            options[key] = os.path.abspath(options[key])
    check_options(parser, a.command, options)
    return a, options, fmt


# --------------------------------------------------------------------------- the batch

class Progress:
    def __init__(self, total: int, quiet: bool):
        self.total, self.quiet, self.n = total, quiet, 0
        self.counts = {"done": 0, "skipped": 0, "failed": 0}
        self.tty = sys.stderr.isatty()
        self.t0 = time.perf_counter()

    def update(self, entry: Dict[str, Any]) -> None:
        self.n += 1
        self.counts[entry["status"]] += 1
        if self.quiet:
            return
        width = 28
        filled = width * self.n // max(self.total, 1)
        line = (f"[{'#' * filled}{'.' * (width - filled)}] {self.n}/{self.total}  done {self.counts['done']}  "
                f"skipped {self.counts['skipped']}  failed {self.counts['failed']}  "
                f"{time.perf_counter() - self.t0:.1f} s  {os.path.basename(entry['input'])}")
        if entry["status"] == "failed":
            sys.stderr.write(("\r\033[K" if self.tty else "") + f"intrinsic.batch: {entry['input']}: "
                             f"{entry['kind']} error: {entry['message']}\n")
        sys.stderr.write(("\r\033[K" + line) if self.tty else line + "\n")
        if self.tty and self.n == self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def write_manifest(path: Path, meta: Dict[str, Any], entries: List[Optional[Dict[str, Any]]]) -> None:
    files = [e for e in entries if e is not None]
    counts = {s: sum(e["status"] == s for e in files) for s in ("done", "skipped", "failed")}
    doc = dict(meta, counts=counts, complete=len(files) == len(entries), files=files)
    write_atomic(str(path), json.dumps(doc, indent=2) + "\n")


def run(argv: Optional[List[str]] = None) -> int:
    a, options, fmt = parse(argv)
    # Run as `python3 -m intrinsic.batch`, this file is __main__: the task must
    # come from the importable module so that workers unpickle it by name.
    from intrinsic import batch as mod

    input_dir = Path(a.input_dir).resolve()
    output_dir = Path(a.output_dir).resolve()
    output_dir.mkdir(parents=True, exist_ok=True)
    jobs = mod.plan_outputs(mod.find_inputs(input_dir), output_dir, fmt)
    t0 = time.perf_counter()
    meta = dict(command=a.command, input_dir=str(input_dir), output_dir=str(output_dir),
                options={k: list(v) if isinstance(v, tuple) else v for k, v in options.items()},
                format=fmt, binary=a.binary,
                cluster=a.scheduler or f"LocalCluster(n_workers={a.workers or 2}, threads_per_worker=1)")
    entries: List[Optional[Dict[str, Any]]] = [None] * len(jobs)
    progress = Progress(len(jobs), a.quiet)
    todo = []
    for i, job in enumerate(jobs):
        if not a.force and mod.is_complete(job):
            entries[i] = dict(input=job["input"], status="skipped", kind=None, exit_code=0, message="",
                              output=job["output"], report=job["report"], seconds=0.0)
            progress.update(entries[i])
        else:
            todo.append(i)
    manifest = output_dir / MANIFEST
    if todo:
        from distributed import Client, LocalCluster, as_completed
        cluster = None
        if a.scheduler:
            client = Client(a.scheduler)
        else:
            cluster = LocalCluster(n_workers=a.workers or 2, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            client = Client(cluster)
        try:
            futures = {client.submit(mod.run_job, a.command, jobs[i], options, a.binary, key=f"intrinsic-{i}-{os.getpid()}",
                                     pure=False): i for i in todo}
            last_write = 0.0
            for fut in as_completed(futures):
                i = futures[fut]
                try:
                    entry = fut.result()
                except Exception as e:  # noqa: BLE001  (a worker died: KilledWorker, lost connection)
                    entry = dict(input=jobs[i]["input"], status="failed", kind="internal",
                                 exit_code=INTERNAL_EXIT_CODE, message=f"{type(e).__name__}: {e}",
                                 output=jobs[i]["output"], report=jobs[i]["report"], seconds=0.0)
                entries[i] = entry
                progress.update(entry)
                if time.perf_counter() - last_write > 1.0:  # what is known so far, if the batch is killed
                    meta["seconds"] = time.perf_counter() - t0
                    mod.write_manifest(manifest, meta, entries)
                    last_write = time.perf_counter()
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    meta["seconds"] = time.perf_counter() - t0
    mod.write_manifest(manifest, meta, entries)
    failed = sum(e["status"] == "failed" for e in entries if e)
    if not a.quiet:
        c = progress.counts
        sys.stderr.write(f"intrinsic.batch: {len(jobs)} files: {c['done']} done, {c['skipped']} skipped, "
                         f"{c['failed']} failed in {meta['seconds']:.1f} s; {manifest}\n")
    return 0 if failed == 0 else 1


def main(argv: Optional[List[str]] = None) -> int:
    return run(argv)


if __name__ == "__main__":
    sys.exit(main())
