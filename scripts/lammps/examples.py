#!/usr/bin/env python3
"""Runs LAMMPS's own DPD example scripts unchanged in gendpde and in the reference LAMMPS,
side by side, and writes docs/LAMMPS_EXAMPLES.md.

The inputs are LAMMPS's example folders, kept verbatim in scripts/lammps/examples/ (see its
README; large data files are stored gzipped and unpacked into the run folder). For every
example both programs run the same input in their own folder under
target/lammps-examples/<example>/; the script then compares the thermo columns both print:
the mean of each column over the second half of the last run, with a standard error from
block averages, and z = (gendpde - LAMMPS) / sqrt(se_g^2 + se_L^2). A column agrees when
|z| < 3 (statistical: each program uses its own random numbers, so only averages can agree).
Step, Time, Atoms and columns that are constant in both runs are compared exactly instead.

    python3 scripts/lammps/examples.py                  # all examples, both programs
    python3 scripts/lammps/examples.py --only dpd,mdpd  # some of them
    python3 scripts/lammps/examples.py --check          # gendpde `check` only (no LAMMPS)

Environment: GENDPDE (default target/release/gendpde), LMP (default
/work/shared/lammps/lmp or ../shared/lammps/lmp next to the repository).
"""
import argparse
import gzip
import hashlib
import json
import math
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "scripts" / "lammps" / "examples"
WORK = ROOT / "target" / "lammps-examples"
sys.path.insert(0, str(ROOT / "python"))
import gendpde  # noqa: E402

GENDPDE = os.environ.get("GENDPDE", str(Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release" / "gendpde"))
LMP_CANDIDATES = [os.environ.get("LMP", ""), "/work/shared/lammps/lmp", str(ROOT.parent / "shared" / "lammps" / "lmp")]
# the box columns (Lx, Volume, ...) are compared exactly when constant in both runs, and
# as averages when a barostat moves them (fix nph)
EXACT = {"Step", "Time", "Atoms", "Elapsed"}


def inputs():
    """(name, folder, input file) of every example, in package order."""
    found = []
    for script in sorted(EXAMPLES.glob("*/*/in.*")):
        found.append((script.name[3:], script.parent, script))
    return found


def stage(folder, dest, script, k):
    """Copies an example folder into `dest`, unpacking *.gz files, with the input's seeds
    moved by `k` (`reseed`)."""
    if dest.exists():
        shutil.rmtree(dest)
    dest.mkdir(parents=True)
    for f in folder.iterdir():
        if f.suffix == ".gz":
            with gzip.open(f, "rb") as src, open(dest / f.stem, "wb") as out:
                shutil.copyfileobj(src, out)
        else:
            shutil.copy(f, dest / f.name)
    (dest / script).write_text(reseed((folder / script).read_text(), k))


SEEDED = {"dpd", "dpd/fdt", "dpd/fdt/energy", "dpd/tstat", "dpd/ext", "dpd/ext/tstat", "mdpd", "edpd"}


def number(word):
    """A numeric argument, or a variable that gives one (`${T}`, `$T`)."""
    if word.startswith("$"):
        return True
    try:
        float(word)
        return True
    except ValueError:
        return False


def reseed(text, k):
    """The input with its noise and velocity seeds moved by k (k = 0: unchanged): the last
    argument of each seeded pair sub-style (its seed, by LAMMPS's syntax) and the seed of
    `velocity ... create T SEED`."""
    if k == 0:
        return text
    out = []
    for line in text.splitlines():
        words = line.split()
        if words[:1] == ["pair_style"]:
            for a, w in enumerate(words):
                if w in SEEDED:
                    last = a
                    while last + 1 < len(words) and number(words[last + 1]):
                        last += 1
                    if last > a and words[last].isdigit():
                        words[last] = str(int(words[last]) + 7919 * k)
            line = " ".join(words)
        elif words[:1] == ["velocity"] and "create" in words:
            i = words.index("create") + 2
            if i < len(words) and words[i].isdigit():
                words[i] = str(int(words[i]) + 7919 * k)
                line = " ".join(words)
        out.append(line)
    return "\n".join(out) + "\n"


def run(command, cwd, timeout):
    """Runs `command` in `cwd`; (exit code, wall seconds, last error line)."""
    start = time.monotonic()
    try:
        p = subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, timeout, f"timed out after {timeout} s"
    wall = time.monotonic() - start
    (cwd / "stdout.txt").write_text(p.stdout)
    (cwd / "stderr.txt").write_text(p.stderr)
    lines = [l for l in (p.stderr + "\n" + p.stdout).splitlines() if "ERROR" in l or "error" in l.lower()]
    return p.returncode, wall, (lines[-1].strip() if lines else "")


def mean_sem(values, blocks=5):
    """Mean and its standard error from `blocks` block averages (0 for constant columns)."""
    v = [float(x) for x in values]
    n = len(v)
    mean = sum(v) / n
    nb = max(2, min(blocks, n // 2))
    if n < 4:
        return mean, float("nan")
    size = n // nb
    b = [sum(v[k * size:(k + 1) * size]) / size for k in range(nb)]
    bm = sum(b) / nb
    var = sum((x - bm) ** 2 for x in b) / (nb - 1)
    return mean, math.sqrt(var / nb)


def last_run(log):
    runs = gendpde.read_log(log)
    return runs[-1] if runs else None


def compare(g_logs, l_logs):
    """Rows (column, gendpde mean, se, LAMMPS mean, se, z, verdict) for the thermo columns
    both programs print in their last run. One seed set: mean over the second half, error
    from block means; several: the mean of the per-run means, error from their spread."""
    g_runs = [last_run(p) for p in g_logs]
    l_runs = [last_run(p) for p in l_logs]
    if any(r is None for r in g_runs + l_runs):
        return []
    rows = []
    for col in l_runs[0].columns:
        if col not in g_runs[0].columns:
            continue
        gv, lv = g_runs[0][col].to_numpy(), l_runs[0][col].to_numpy()
        half_g, half_l = gv[len(gv) // 2:], lv[len(lv) // 2:]
        if col in EXACT or (half_g.min() == half_g.max() and half_l.min() == half_l.max()):
            same = len(gv) == len(lv) and all(math.isclose(a, b, rel_tol=1e-6, abs_tol=1e-12) for a, b in zip(gv, lv))
            rows.append((col, half_g.mean(), 0.0, half_l.mean(), 0.0, None, "same" if same else "DIFFERENT"))
            continue
        (mg, sg), (ml, sl) = (estimate([r[col].to_numpy() for r in runs]) for runs in (g_runs, l_runs))
        se = math.hypot(sg, sl)
        if math.isnan(se):
            rows.append((col, mg, sg, ml, sl, None, "too few rows for an error"))
            continue
        z = (mg - ml) / se if se > 0 else float("inf")
        rows.append((col, mg, sg, ml, sl, z, "agrees" if abs(z) < 3 else "differs"))
    return rows


def estimate(series):
    """Mean of a column over the second half of each run, and its standard error."""
    halves = [s[len(s) // 2:] for s in series]
    if len(halves) == 1:
        return mean_sem(halves[0])
    means = [float(h.mean()) for h in halves]
    m = sum(means) / len(means)
    return m, math.sqrt(sum((x - m) ** 2 for x in means) / (len(means) - 1) / len(means))


def reference(lmp, folder, script, ldir, timeout, k):
    """Runs LAMMPS on the example, or reuses the finished run of the same inputs in
    `ldir` (the reference does not change between gendpde versions)."""
    digest = hashlib.sha256(b"".join(f.read_bytes() for f in sorted(folder.iterdir())) + bytes([k])).hexdigest()
    stamp = ldir / "inputs.sha256"
    if stamp.exists() and stamp.read_text().split()[0] == digest:
        _, wall = stamp.read_text().split()
        return 0, float(wall), ""
    stage(folder, ldir, script.name, k)
    code, wall, err = run([lmp, "-in", script.name, "-log", "log.lammps"], ldir, timeout)
    if code == 0:
        stamp.write_text(f"{digest} {wall:.1f}")
    return code, wall, err


def lmp_path():
    for c in LMP_CANDIDATES:
        if c and Path(c).exists():
            return c
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--only", help="comma-separated example names (in.NAME)")
    ap.add_argument("--check", action="store_true", help="only `gendpde check` each input")
    ap.add_argument("--timeout", type=float, default=900)
    ap.add_argument("--seeds", type=int, default=1, help="runs per program with moved seeds (errors from their spread when > 2)")
    ap.add_argument("--out", default=str(ROOT / "docs" / "LAMMPS_EXAMPLES.md"))
    args = ap.parse_args()
    wanted = set(args.only.split(",")) if args.only else None
    lmp = None if args.check else lmp_path()
    if not args.check and lmp is None:
        sys.exit("reference LAMMPS not found: run ../shared/lammps/setup.sh or set LMP")
    report = []
    for name, folder, script in inputs():
        if wanted and name not in wanted:
            continue
        package = folder.parent.name
        if args.check:
            gdir = WORK / name / "check"
            stage(folder, gdir, script.name, 0)
            code, wall, err = run([GENDPDE, "check", script.name], gdir, args.timeout)
            print(f"{package}/{name}: {'ok' if code == 0 else err}", flush=True)
            report.append((package, name, code, err))
            continue
        results = []
        for k in range(args.seeds):
            gdir = WORK / name / f"gendpde-{k}"
            stage(folder, gdir, script.name, k)
            code, gwall, gerr = run([GENDPDE, "-in", script.name, "-log", "log.gendpde"], gdir, args.timeout)
            ldir = WORK / name / f"lammps-{k}"
            lcode, lwall, lerr = reference(lmp, folder, script, ldir, args.timeout, k)
            print(f"{package}/{name} seed set {k}: gendpde {'ok' if code == 0 else gerr} ({gwall:.1f} s), "
                  f"LAMMPS {'ok' if lcode == 0 else lerr} ({lwall:.1f} s)", flush=True)
            results.append((code, gerr, gwall, lcode, lerr, lwall, gdir / "log.gendpde", ldir / "log.lammps"))
            if code != 0 or lcode != 0:
                break
        rows = compare([r[6] for r in results], [r[7] for r in results]) if all(r[0] == 0 and r[3] == 0 for r in results) else []
        for r in rows:
            print("    " + fmt_row(r))
        code, gerr, gwall, lcode, lerr, lwall = results[-1][:6]
        report.append((package, name, code, gerr, gwall, lcode, lerr, lwall, rows, len(results)))
    if not args.check:
        write_report(Path(args.out), merge(report))
    bad = [r for r in report if r[2] != 0]
    return 1 if args.check and bad else 0


def fmt_row(r):
    col, mg, sg, ml, sl, z, verdict = r
    if z is None:
        return f"{col}: {mg:.6g} vs {ml:.6g} ({verdict})"
    return f"{col}: {mg:.6g} +- {sg:.2g} vs {ml:.6g} +- {sl:.2g}, z = {z:+.2f} ({verdict})"


def merge(report):
    """The results of this invocation merged by example into docs/lammps_examples.json (so
    examples run separately, with different seed counts, share one report); all of them,
    in input order."""
    store = ROOT / "docs" / "lammps_examples.json"
    known = json.loads(store.read_text()) if store.exists() else {}
    for entry in report:
        known[entry[1]] = [None if isinstance(x, float) and math.isnan(x) else x for x in entry[:8]] + [
            [list(r) for r in entry[8]], entry[9]]
    order = [name for name, _, _ in inputs()]
    known = {k: known[k] for k in sorted(known, key=lambda k: order.index(k) if k in order else len(order))}
    store.write_text(json.dumps(known, indent=1) + "\n")
    return [tuple(v[:8]) + (v[8], v[9]) for v in known.values()]


# Notes printed under an example's results.
NOTES = {
    "edpd": [
        "Press differed (194.71 +- 0.38 against 197.44 +- 0.48, z = -4.5) until gendpde's noise key",
        "stopped following `reset_timestep`: the pair noise is drawn from (seed, step, tags), and",
        "after the script's `reset_timestep 0` the second run redrew the noise of the first run's",
        "steps for the same pairs, which their positions remembered; the random virial lowered",
        "Press. The key now runs on through a reset (Clock::noise_shift, kept in restarts;",
        "tests/it/guarantees/guarantees.rs `reset_timestep_leaves_the_trajectory_alone`), and Press agrees.",
        "At step 0 with the noise separated out, Press, its diagonal and the energies agree with",
        "LAMMPS to 1e-14 (tests/it/styles/edpd.rs).",
    ],
    "multi-lucy": [
        "LAMMPS's `table.multibody` is missing upstream (an absent Git LFS blob): both programs",
        "read gendpde's SUBSTITUTE, scripts/lammps/examples/dpd-react/multi-lucy/table.multibody",
        "written by `scripts/lammps/multi_lucy_table.py` (a quadratic free energy calibrated to",
        "step 0 of LAMMPS's reference log), not LAMMPS's table. Without noise and with the same",
        "velocities both programs print the same rows. LAMMPS's reference log (its own table)",
        "at step 100: Temp 238.11, Press 2260.1, PotEng 9.869; the substitute: 238.04, 2271.0, 9.904.",
    ],
}


def write_report(path, report):
    lines = ["# LAMMPS's DPD examples, run unchanged in gendpde and in the reference LAMMPS", "",
             "Generated by `python3 scripts/lammps/examples.py` (inputs: scripts/lammps/examples/,",
             "LAMMPS's example folders verbatim). Columns: the mean of each thermo column both",
             "programs print, over the second half of the last run, +- its standard error: from",
             "5 block means with one seed set, from the spread of the runs' means with several",
             "(`--seeds K` moves the noise and velocity seeds of the input by 7919 k, nothing",
             "else); z = difference / combined error (|z| < 3: agrees). Each program uses its",
             "own random numbers, so only averages can agree. Wall times are the last serial",
             "run of each on a shared 2-core machine.", "",
             "| package | example | gendpde | LAMMPS | seed sets | wall gendpde / LAMMPS (s) | columns agreeing |",
             "|---|---|---|---|---|---|---|"]
    details = []
    for package, name, code, gerr, gwall, lcode, lerr, lwall, rows, seeds in report:
        g = "runs" if code == 0 else f"stops: `{gerr[:90]}`"
        l = "runs" if lcode == 0 else f"stops: `{lerr[:90]}`"
        judged = [r for r in rows if r[6] != "too few rows for an error"]
        ok = sum(1 for r in judged if r[6] in ("agrees", "same"))
        agree = f"{ok}/{len(judged)}" if judged else "-"
        lines.append(f"| {package} | {name} | {g} | {l} | {seeds} | {gwall:.1f} / {lwall:.1f} | {agree} |")
        if rows:
            details += ["", f"### {package}/{name}", ""] + ["    " + fmt_row(r) for r in rows]
            details += [""] + NOTES[name] if name in NOTES else []
    path.write_text("\n".join(lines + details) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    sys.exit(main())
