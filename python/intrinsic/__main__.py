"""``python3 -m intrinsic ARGS``: the ``intrinsic`` command line (docs/cli.md).

Runs, in this order, the first that exists:

1. the CLI bundled in the installed package (``intrinsic/bin/intrinsic``,
   put there by ``pip install``; docs/python.md "Installing with pip"),
2. the program ``$INTRINSIC_CLI`` names (a build tree's, as the tests set it),
3. ``intrinsic`` on ``PATH``,

replacing this process (its exit code is the command line's). With none of
them it says so on standard error and exits with 127, the shell's code for
a command that is not there. The package's ``intrinsic`` console script runs
this too.
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import List, Optional

# Set while this launcher runs a program, so that an `intrinsic` on PATH that
# is this launcher's own console script does not start it again, forever.
_GUARD = "_INTRINSIC_LAUNCHER"


def bundled_cli() -> Path:
    """Where ``pip install`` puts the command line inside the package."""
    return Path(__file__).resolve().parent / "bin" / ("intrinsic.exe" if os.name == "nt" else "intrinsic")


def find_cli() -> Optional[str]:
    """The command line to run, or None: bundled, $INTRINSIC_CLI, PATH."""
    bundled = bundled_cli()
    if bundled.is_file() and os.access(bundled, os.X_OK):
        return str(bundled)
    named = os.environ.get("INTRINSIC_CLI")
    if named and Path(named).is_file():
        return named
    if os.environ.get(_GUARD):
        return None
    return shutil.which("intrinsic")


def main(argv: Optional[List[str]] = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    cli = find_cli()
    if cli is None:
        sys.stderr.write(
            "intrinsic: error: the intrinsic command line was not found: it is not bundled in this package\n"
            f"  ({bundled_cli()}), $INTRINSIC_CLI is not set to an existing file and there is no intrinsic\n"
            "  on PATH. Install the package with pip (which builds and bundles it) or set INTRINSIC_CLI.\n")
        return 127
    env = dict(os.environ, **{_GUARD: "1"})
    sys.stdout.flush()
    sys.stderr.flush()
    if os.name == "posix":
        os.execve(cli, [cli, *args], env)  # does not return
    return subprocess.run([cli, *args], env=env).returncode


if __name__ == "__main__":
    sys.exit(main())
