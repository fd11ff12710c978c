"""Shared helpers of the validation scenes: running gendpde and reading its thermo output
and H5MD dumps (with the gendpde package of python/), the analytic EOS through
`gendpde eos`, and the results file.

Every scene script writes its numbers into docs/validation/results.json (one entry per
scene, merged) and its figure into docs/validation/<scene>.png; docs/VALIDATION.md quotes
them.
"""
import json
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))  # the gendpde package, installed or not
import gendpde  # noqa: E402
GENDPDE = os.environ.get("GENDPDE", str(Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release" / "gendpde"))
OUT = ROOT / "docs" / "validation"
LJ_TABLE = "table 0.3 8.0 121 0.0 1.2 129"  # the grid the LJ scans use (see fix_eos.md)


def run(example, variables, workdir, ranks=1):
    """Runs examples/<example>/in.<example> with `-var` pairs in `workdir`; returns
    (thermo blocks, wall seconds)."""
    script = ROOT / "examples" / example / f"in.{example}"
    try:
        r = gendpde.run(script, variables, np=ranks, cwd=workdir, binary=GENDPDE)
    except gendpde.GendpdeError as e:
        sys.exit(f"gendpde failed in {workdir}:\n{' '.join(e.command)}\n{e.stdout[-3000:]}\n{e.stderr[-3000:]}")
    (Path(workdir) / "run.json").write_text(json.dumps({"example": example, "variables": variables, "wall_s": r.wall_s}))
    return r.logs, r.wall_s


def run_once(example, variables, workdir):
    """`run`, unless `workdir` holds a finished run of the same example and variables
    (its run.json): then its log's thermo blocks and wall time, so that a driver can redo
    its analysis without the simulation."""
    done = Path(workdir) / "run.json"
    if done.exists():
        record = json.loads(done.read_text())
        if record["example"] == example and record["variables"] == json.loads(json.dumps(variables)):
            return gendpde.read_log(Path(workdir) / "log.gendpde"), record["wall_s"]
    return run(example, variables, workdir)


def mean_sem(values, blocks=10):
    """Mean and its standard error from `blocks` block averages."""
    import numpy as np
    v = np.asarray(values, dtype=float)
    nb = max(2, min(blocks, len(v) // 2))
    b = np.array([c.mean() for c in np.array_split(v, nb)])
    return float(v.mean()), float(b.std(ddof=1) / np.sqrt(nb))


def mean_sem_tau(values):
    """Mean and its standard error sd sqrt(2 tau / n) from the integrated autocorrelation
    time tau (in samples; the sum of the autocorrelation function up to its first negative
    value). Unlike `mean_sem` with 10 blocks, it does not depend on how the blocks fall,
    whose error estimate scatters by a quarter on its own."""
    import numpy as np
    v = np.asarray(values, dtype=float)
    x = v - v.mean()
    var = x.var()
    tau = 0.5
    for k in range(1, len(x) // 4):
        c = (x[:-k] * x[k:]).mean() / var
        if c < 0.0:
            break
        tau += c
    return float(v.mean()), float(np.sqrt(var * 2.0 * tau / len(v)))


def relative(energy):
    """(E(t) - E(0)) / |E(0)| over one run's thermo column."""
    return [(e - energy[0]) / abs(energy[0]) for e in energy]


def drift_rate(time_values, edrift):
    """Slope of a linear fit of (E(t) - E(0))/E(0) against t (SPEC sec 6)."""
    import numpy as np
    return float(np.polyfit(np.asarray(time_values), np.asarray(edrift), 1)[0])


def eos(model, theta, n):
    """`gendpde eos MODEL --theta T --n N` as a dict."""
    out = subprocess.run([GENDPDE, "eos", *model.split(), "--theta", str(theta), "--n", str(n)],
                         capture_output=True, text=True, check=True)
    return {k: float(v) for k, v in (line.split() for line in out.stdout.splitlines())}


def h5md_frames(path, field):
    """[frames, N, ...] values of /particles/all/<field>/value."""
    with gendpde.read_h5md(path) as f:
        return f.array(field)


def pearson(samples, quantile, bins=30):
    """Pearson chi^2 and p-value of `samples` on `bins` bins equiprobable under the
    distribution with quantile function `quantile` (samples treated as independent)."""
    import numpy as np
    from scipy import stats
    edges = np.asarray(quantile(np.linspace(0, 1, bins + 1)), dtype=float)
    edges[0], edges[-1] = -np.inf, np.inf
    counts, _ = np.histogram(samples, bins=edges)
    expected = len(samples) / bins
    chi2 = float(((counts - expected) ** 2 / expected).sum())
    return chi2, float(stats.chi2.sf(chi2, bins - 1))


def lattice_cells(rho, rc, skin=0.4, minimum=None):
    """Lattice cells per side of an sc box at density rho that holds 4 list cells."""
    import math
    n = math.ceil(4 * (rc + skin) * rho ** (1 / 3) + 1e-9)
    return max(n, minimum or 0)


def save(scene, entry):
    """Merges `entry` under `scene` into docs/validation/results.json."""
    OUT.mkdir(parents=True, exist_ok=True)
    path = OUT / "results.json"
    data = json.loads(path.read_text()) if path.exists() else {}
    data[scene] = entry
    path.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")


def series(run, **columns):
    """{name: column of the thermo DataFrame `run`} as lists of 6-digit floats (a driver
    stores its time series in results.json with it, to redraw its figure)."""
    return {name: [float(f"{v:.6g}") for v in run[col]] for name, col in columns.items()}


def saved(scene):
    """The results.json entry of `scene` (what a driver's --plot redraws its figure from)."""
    return json.loads((OUT / "results.json").read_text())[scene]


def figure_path(scene):
    OUT.mkdir(parents=True, exist_ok=True)
    return OUT / f"{scene}.png"


def cached(workdir, compute):
    """The row of a run: read from `workdir`/row.json if an earlier run left it, otherwise
    `compute()`d and written there, so that a rerun only redoes what is missing."""
    cache = Path(workdir) / "row.json"
    if cache.exists():
        return json.loads(cache.read_text())
    row = compute()
    cache.write_text(json.dumps(row))
    return row


def workdir(scene, tag):
    base = Path(os.environ.get("VALIDATION_WORK", "/tmp/gendpde-validation"))
    return base / scene / re.sub(r"[^A-Za-z0-9_.-]", "_", tag)
