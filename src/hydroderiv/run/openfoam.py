"""Running OpenFOAM utilities and solvers: environment, logs, parallel launch and clear failures."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from functools import lru_cache
from pathlib import Path

from ..errors import HydroderivError

# Where Debian's `openfoam` package puts the project directory (binaries go to /usr/bin).
_DEBIAN_PROJECT_DIR = Path("/usr/share/openfoam")


class OpenFOAMError(HydroderivError):
    """An OpenFOAM utility or solver failed; the message names it, its log and the fatal error."""


def require_openfoam(application: str = "simpleFoam") -> None:
    if shutil.which(application) is None:
        raise OpenFOAMError(
            f"OpenFOAM application {application!r} is not on PATH: install OpenFOAM (scripts/setup.sh installs the "
            "Debian 'openfoam' package) or source your OpenFOAM installation's etc/bashrc"
        )


def foam_environment(case: Path | None = None) -> dict[str, str]:
    """The environment for an OpenFOAM process.

    A sourced installation sets WM_PROJECT_DIR itself; Debian's package does not, and its binaries need it
    to find etc/controlDict. PWD is set to the case so OpenFOAM does not warn that PWD is not the cwd.
    """
    env = dict(os.environ)
    if not env.get("WM_PROJECT_DIR") and _DEBIAN_PROJECT_DIR.is_dir():
        env["WM_PROJECT_DIR"] = str(_DEBIAN_PROJECT_DIR)
    if case is not None:
        env["PWD"] = str(Path(case).resolve())
    return env


def fatal_error_excerpt(log_text: str, lines: int = 12) -> str:
    """The FOAM FATAL ERROR block of a log, or its last lines when there is none."""
    match = re.search(r"--> FOAM FATAL (IO )?ERROR.*", log_text, flags=re.S)
    text = match.group(0) if match else log_text
    return "\n".join(text.strip().splitlines()[:lines] if match else text.strip().splitlines()[-lines:])


def mpi_launcher(n_procs: int) -> list[str]:
    """``mpirun -np N``, adding what Open MPI needs to run as root."""
    if shutil.which("mpirun") is None:
        raise OpenFOAMError("mpirun is not on PATH; install Open MPI (it comes with Debian's openfoam package)")
    command = ["mpirun", "-np", str(n_procs)]
    if os.geteuid() == 0 and _is_open_mpi():
        command.insert(1, "--allow-run-as-root")
    return command


@lru_cache(maxsize=1)
def _is_open_mpi() -> bool:
    out = subprocess.run(["mpirun", "--version"], capture_output=True, text=True).stdout
    return "Open MPI" in out or "OpenRTE" in out


def application_command(application: list[str], n_procs: int = 1) -> list[str]:
    require_openfoam(application[0])
    if n_procs > 1:
        return [*mpi_launcher(n_procs), *application, "-parallel"]
    return list(application)


def run_application(case: Path, application: list[str], log_name: str | None = None, n_procs: int = 1) -> Path:
    """Run an OpenFOAM application in ``case`` with its output in ``case/log.<name>``; raise on failure."""
    case = Path(case)
    log = case / f"log.{log_name or application[0]}"
    command = application_command(application, n_procs)
    with open(log, "w") as handle:
        result = subprocess.run(command, cwd=case, env=foam_environment(case), stdout=handle, stderr=subprocess.STDOUT)
    if result.returncode != 0:
        raise OpenFOAMError(
            f"{' '.join(application)} failed (exit code {result.returncode}) in {case}; log: {log}\n"
            + fatal_error_excerpt(log.read_text(errors="replace"))
        )
    return log


def openfoam_version_from_log(log_text: str) -> str | None:
    """The release recorded in a log header, e.g. '1912' from 'Build  : OPENFOAM=1912 patch=200626'."""
    match = re.search(r"OPENFOAM=(\d+)", log_text) or re.search(r"Version:\s+v?(\d{4})", log_text)
    return match.group(1) if match else None
