"""Running gendpde from Python."""
import os
import shlex
import shutil
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path

from .log import parse_log, read_log


class GendpdeError(RuntimeError):
    """A failed gendpde run; str() is gendpde's message (its "ERROR: file:line: ..." lines).
    Also: returncode, stdout, stderr, command."""

    def __init__(self, message, returncode=None, stdout="", stderr="", command=()):
        super().__init__(message)
        self.message, self.returncode = message, returncode
        self.stdout, self.stderr, self.command = stdout, stderr, list(command)


@dataclass
class Run:
    """The outcome of `run`: logs (one DataFrame per run, see `parse_log`), outputs (the
    files the run created or changed under its directory, sorted), stdout, stderr, wall_s,
    command."""
    logs: list
    outputs: list
    stdout: str = ""
    stderr: str = ""
    wall_s: float = 0.0
    command: list = field(default_factory=list)


def find_binary():
    """The gendpde executable: $GENDPDE, else `gendpde` on PATH, else the repository's
    target/release/gendpde when this package is used from its source tree."""
    env = os.environ.get("GENDPDE")
    if env:
        if not (os.path.isfile(env) and os.access(env, os.X_OK)):
            raise FileNotFoundError(f"GENDPDE={env} is not an executable file")
        return env
    found = shutil.which("gendpde")
    if found:
        return found
    dev = Path(__file__).resolve().parents[2] / "target" / "release" / "gendpde"
    if dev.is_file() and os.access(dev, os.X_OK):
        return str(dev)
    raise FileNotFoundError("gendpde not found: set GENDPDE, put gendpde on PATH, or build it "
                            "(cargo build --release --features mpi) and install this package with pip install -e")


def _snapshot(root, depth=2):
    """{path: (mtime_ns, size)} of the files under `root`, `depth` folders deep."""
    out = {}

    def walk(d, level):
        try:
            entries = list(os.scandir(d))
        except OSError:
            return
        for e in entries:
            if e.name.startswith("."):
                continue
            if e.is_file(follow_symlinks=False):
                st = e.stat(follow_symlinks=False)
                out[e.path] = (st.st_mtime_ns, st.st_size)
            elif e.is_dir(follow_symlinks=False) and level < depth:
                walk(e.path, level + 1)

    walk(root, 0)
    return out


def error_message(stdout, stderr, returncode):
    """gendpde's ERROR lines (once each, as every MPI rank may print them), else the end
    of stderr."""
    lines = []
    for text in (stderr, stdout):
        for line in text.splitlines():
            if line.lstrip().startswith("ERROR") and line.strip() not in lines:
                lines.append(line.strip())
    if lines:
        return "\n".join(lines)
    tail = stderr.strip().splitlines()[-20:]
    return "\n".join(tail) if tail else f"gendpde exited with status {returncode}"


def run(script, vars=None, np=1, log="log.gendpde", cwd=None, binary=None, args=(), timeout=None):
    """Runs `gendpde run script -var K V ... -log log` in `cwd` (default: the current
    directory), under `mpirun -np np` when np > 1 ($MPIRUN, default "mpirun
    --oversubscribe --mca mpi_yield_when_idle 1": idle ranks yield the core), and returns a `Run`. `log=None` writes no log file (the tables are
    then read from stdout). `script` is taken relative to the caller's directory when it
    exists there, else relative to `cwd`; `args` are further command-line words. Raises `GendpdeError` when gendpde fails.
    """
    cwd = Path(cwd) if cwd is not None else Path.cwd()
    cwd.mkdir(parents=True, exist_ok=True)
    script = Path(script)
    if not script.is_absolute() and script.exists():
        script = script.resolve()
    cmd = [binary or find_binary(), "run", str(script), "-log", log or "none"]
    for k, v in (vars or {}).items():
        cmd += ["-var", str(k), str(v)]
    cmd += [str(a) for a in args]
    env = dict(os.environ)
    if np > 1:
        cmd = shlex.split(os.environ.get("MPIRUN", "mpirun --oversubscribe --mca mpi_yield_when_idle 1")) + ["-np", str(np)] + cmd
        if hasattr(os, "geteuid") and os.geteuid() == 0:  # OpenMPI refuses root unless told
            env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    before = _snapshot(cwd)
    start = time.time()
    out = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, env=env, timeout=timeout)
    wall = time.time() - start
    if out.returncode != 0:
        raise GendpdeError(error_message(out.stdout, out.stderr, out.returncode), out.returncode,
                           out.stdout, out.stderr, cmd)
    after = _snapshot(cwd)
    outputs = sorted(Path(p) for p, stamp in after.items() if before.get(p) != stamp)
    logfile = cwd / log if log else None
    logs = read_log(logfile) if logfile is not None and logfile.exists() else parse_log(out.stdout)
    return Run(logs, outputs, out.stdout, out.stderr, wall, cmd)
