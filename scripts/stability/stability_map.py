#!/usr/bin/env python3
"""Stability map of gendpde for the van der Waals and the Lennard-Jones particle EOS.

Runs small scenes (N ~ 500, gamma = 4.5, kappa = 1, heat model `original`) around a base
point (dt = 0.01, C_V = 60, rho = 0.5, T = 1.5, rc = 2), varying one axis at a time (dt,
C_V, rho, T, rc, and a flash heating to T = 50), classifies each run as stable / drifting /
stopped, reruns the stopped ones with `fix shardlow ... reject yes`, and writes
docs/STABILITY.md and docs/stability.png (results are kept in results.json next to this
script, so `--report-only` redraws without running).

    python3 scripts/stability/stability_map.py            # full map (about 15 min on 2 free cores)
    python3 scripts/stability/stability_map.py --quick    # 1000-step smoke version
    python3 scripts/stability/stability_map.py --binary PATH --jobs 2

Standard library + numpy + matplotlib.
"""
import argparse
import concurrent.futures as cf
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SCENE = os.path.join(HERE, "in.scene")
IN_RUN = os.path.join(HERE, "in.stability")
IN_FLASH = os.path.join(HERE, "in.flash")

DRIFT_TOL = 1e-4
SKIN = 0.3
BASE = dict(dt=0.01, cv=60.0, rho=0.5, T=1.5, rc=2.0)
EOS = {
    "vdw": dict(label="van der Waals (eos/vdw CV 2.4682 1.4142 excess)",
                fix=lambda cv: f"eos/vdw {cv:g} 2.4682 1.4142 excess",
                rho=[0.01, 0.1, 0.3, 0.5, 0.6, 0.65]),
    "lj": dict(label="Lennard-Jones (eos/lj CV, Kolafa-Nezbeda)",
               fix=lambda cv: f"eos/lj {cv:g}",
               rho=[0.01, 0.1, 0.3, 0.5, 0.65, 0.8]),
}
AXES = {
    "dt": [0.001, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2],
    "cv": [1.5, 3.0, 10.0, 60.0, 1000.0],
    "T": [0.1, 0.5, 1.5, 3.0, 10.0],
    "rc": [1.5, 2.0, 3.0],
}
AXIS_NAMES = {"dt": "dt", "cv": "C_V", "rho": "rho", "T": "T", "rc": "rc", "flash": "flash"}


def lattice_cells(rho, rc, nmin=8):
    """sc cells per side: N >= nmin^3 and box >= 4 cells of side rc + skin."""
    a = rho ** (-1.0 / 3.0)
    need = 4.0 * (rc + SKIN)
    return max(nmin, math.ceil(need / a - 1e-9))


def plan(steps_vdw, steps_lj):
    """Every run: one dict of parameters, keyed by (eos, axis, value)."""
    runs = []
    for eos, spec in EOS.items():
        steps = steps_vdw if eos == "vdw" else steps_lj
        axes = dict(AXES, rho=spec["rho"])
        for axis, values in axes.items():
            for v in values:
                p = dict(BASE, **{axis: v})
                runs.append(dict(eos=eos, axis=axis, value=v, steps=steps, flash=False, **p))
        runs.append(dict(eos=eos, axis="flash", value=50.0, steps=steps // 2, flash=True, **BASE))
    for r in runs:
        r["n"] = lattice_cells(r["rho"], r["rc"])
        r["N"] = r["n"] ** 3
    return runs


def key(r):
    return f"{r['eos']}:{r['axis']}:{r['value']:g}:{'reject' if r.get('reject') else 'sub4'}"


THERMO = re.compile(r"^\s*(\d+)\s+([-+0-9.eEinfa]+)\s+([-+0-9.eEinfa]+)\s+([-+0-9.eEinfa]+)\s+"
                    r"([-+0-9.eEinfa]+)\s+([-+0-9.eEinfa]+)\s*$")
GUARD = re.compile(r"split into half steps \(theta -> 0 guard\) = (\d+), left out = (\d+)")
STOP = re.compile(r"run stopped: (particle (\d+) after step (\d+): .*)")


def run_one(r, binary, timeout):
    """Run one scene in a scratch directory; return the record with the outcome."""
    guard = "substeps 4 reject yes" if r.get("reject") else "substeps 4 reject no"
    script = IN_FLASH if r["flash"] else IN_RUN
    cmd = [binary, "run", script, "-var", "scene", SCENE, "-var", "steps", str(r["steps"]),
           "-var", "n", str(r["n"]), "-var", "rho", f"{r['rho']:g}", "-var", "T", f"{r['T']:g}",
           "-var", "rc", f"{r['rc']:g}", "-var", "dt", f"{r['dt']:g}", "-var", "cv", f"{r['cv']:g}",
           "-var", "eos", EOS[r["eos"]]["fix"](r["cv"]), "-var", "guard", guard, "-log", "none"]
    if r["flash"]:
        cmd[3:3] = ["-var", "Tflash", f"{r['value']:g}"]
    work = tempfile.mkdtemp(prefix="gendpde-stab-")
    t0 = time.monotonic()
    try:
        with open(os.path.join(work, "out"), "w") as out, open(os.path.join(work, "err"), "w") as err:
            p = subprocess.Popen(cmd, cwd=work, stdout=out, stderr=err)
            timer = threading.Timer(timeout, p.kill)
            timer.start()
            _, status, ru = os.wait4(p.pid, 0)
            timer.cancel()
            p.returncode = os.waitstatus_to_exitcode(status)
        wall = time.monotonic() - t0
        stdout = open(os.path.join(work, "out")).read()
        stderr = open(os.path.join(work, "err")).read()
    finally:
        shutil.rmtree(work, ignore_errors=True)
    rows = [tuple(float(x) for x in m.groups()) for m in map(THERMO.match, stdout.splitlines()) if m]
    res = dict(r, wall=round(wall, 2), cpu=round(ru.ru_utime + ru.ru_stime, 2), rc_exit=p.returncode,
               cmd=" ".join(cmd[1:]), thermo=rows)
    g = GUARD.findall(stdout)
    res["split"] = sum(int(a) for a, _ in g)
    res["left_out"] = sum(int(b) for _, b in g)
    # energy drift: edrift of the last line; for the flash, relative to the first line of the
    # second run (the heating itself changes E, and edrift refers to the first run's E0)
    drift = None
    if rows:
        if r["flash"]:
            start = [row for row in rows if row[0] == r["steps"]]
            e0 = start[-1][4] if start else rows[0][4]
            drift = (rows[-1][4] - e0) / abs(e0)
        else:
            drift = rows[-1][5]
    res["edrift"] = drift
    res["last_step"] = int(rows[-1][0]) if rows else None
    res["tint"] = rows[-1][2] if rows else None
    res["temp"] = rows[-1][1] if rows else None
    if p.returncode != 0:
        m = STOP.search(stderr)
        res["outcome"] = "stopped"
        res["edrift_last"], res["edrift"] = drift, None
        if m:
            res["fail_step"] = int(m.group(3))
            msg = m.group(1)
            res["message"] = re.sub(r"; the last good state.*?h5 \(", " (", msg).split("; a smaller")[0]
        elif p.returncode < 0:
            res["message"] = f"killed after {timeout:.0f} s (time limit)"
            res["outcome"] = "timeout"
        else:
            res["message"] = (stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1][:300]
    else:
        res["outcome"] = "stable" if drift is not None and abs(drift) <= DRIFT_TOL else "drifting"
    return res


def run_all(runs, binary, jobs, timeout, done, save=lambda: None):
    todo = [r for r in runs if key(r) not in done]
    # longest first: LJ is ~7x dearer per step than vdW, cost ~ N * neighbours * steps
    todo.sort(key=lambda r: -(r["N"] * r["rho"] * r["rc"] ** 3 * r["steps"] * (2 if r["flash"] else 1)
                              * (7 if r["eos"] == "lj" else 1)))
    with cf.ThreadPoolExecutor(max_workers=jobs) as ex:
        futs = {ex.submit(run_one, r, binary, timeout): r for r in todo}
        for f in cf.as_completed(futs):
            res = f.result()
            done[key(res)] = res
            save()
            d = res["edrift"]
            print(f"[{len(done):3d}] {key(res):28s} {res['outcome']:8s} edrift={d if d is None else f'{d:.2e}'}"
                  f" wall={res['wall']:.1f}s {res.get('message', '')[:90]}", flush=True)
    return done


# ---------------------------------------------------------------------------- report

def fmt_drift(d):
    return "-" if d is None else f"{d:+.1e}"


def fmt_value(axis, v):
    return "50 (flash)" if axis == "flash" else f"{v:g}"


def guard_counts(r):
    # `run` prints the counts only at the end of a finished run
    return "n/a" if r["outcome"] in ("stopped", "timeout") else f"{r['split']} / {r['left_out']}"


def table(results, eos, axes_order):
    out = ["| axis | value | N | outcome | final edrift | guard: split / left out | failure (step: message) | "
           "`reject yes` rerun | wall s |", "|---|---|---|---|---|---|---|---|---|"]
    for axis in axes_order:
        rows = [r for r in results.values() if r["eos"] == eos and r["axis"] == axis and not r.get("reject")]
        for r in sorted(rows, key=lambda r: r["value"]):
            fail = ""
            if r["outcome"] in ("stopped", "timeout"):
                fail = f"{r.get('fail_step', '?')}: {r.get('message', '')}"
            rej = ""
            rr = results.get(key(dict(r, reject=True)))
            if rr:
                rej = rr["outcome"]
                if rr["outcome"] in ("stopped", "timeout"):
                    rej += f" at step {rr.get('fail_step', '?')}"
                else:
                    rej += f", edrift {fmt_drift(rr['edrift'])}"
                    rej += f" (left out {rr['left_out']})"
            base = all(r[a] == BASE[a] for a in BASE) and not r["flash"]
            val = fmt_value(axis, r["value"]) + (" (base)" if base else "")
            out.append(f"| {AXIS_NAMES[axis]} | {val} | {r['N']} | **{r['outcome']}** | {fmt_drift(r['edrift'])} | "
                       f"{guard_counts(r)} | {fail} | {rej} | {r['wall']:.1f} |")
    return "\n".join(out)


def headline(results):
    lines = []
    for eos in EOS:
        dts = sorted((r["value"], r) for r in results.values()
                     if r["eos"] == eos and r["axis"] == "dt" and not r.get("reject"))
        ok = [v for v, r in dts if r["outcome"] == "stable"]
        fin = [v for v, r in dts if r["outcome"] in ("stable", "drifting")]
        cvs = sorted((r["value"], r) for r in results.values()
                     if r["eos"] == eos and r["axis"] == "cv" and not r.get("reject"))
        cv_ok = [v for v, r in cvs if r["outcome"] == "stable"]
        cv_fin = [v for v, r in cvs if r["outcome"] in ("stable", "drifting")]
        lines.append(f"- **{eos}**: largest stable dt at the base point = {max(ok) if ok else 'none'}"
                     f" (largest dt that finishes = {max(fin) if fin else 'none'}); smallest stable C_V = "
                     f"{min(cv_ok) if cv_ok else 'none'} (smallest that finishes = {min(cv_fin) if cv_fin else 'none'}).")
    return "\n".join(lines)


def figure(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    fig, axs = plt.subplots(1, 2, figsize=(9.0, 4.8), dpi=90, gridspec_kw=dict(width_ratios=[1.0, 1.25]))
    ax = axs[0]
    colors = {"vdw": "tab:blue", "lj": "tab:red"}
    for eos in EOS:
        rows = sorted((r for r in results.values() if r["eos"] == eos and r["axis"] == "dt" and not r.get("reject")),
                      key=lambda r: r["value"])
        x = [r["value"] for r in rows if r["edrift"] is not None and r["outcome"] != "stopped"]
        y = [max(abs(r["edrift"]), 1e-10) for r in rows if r["edrift"] is not None and r["outcome"] != "stopped"]
        ax.loglog(x, y, "o-", color=colors[eos], label=eos)
        for r in rows:
            if r["outcome"] in ("stopped", "timeout"):
                ax.plot(r["value"], 1.0, "x", color=colors[eos], ms=9, mew=2)
    ax.axhline(DRIFT_TOL, color="k", lw=0.8, ls="--")
    ax.text(0.0011, DRIFT_TOL * 1.6, "1e-4", fontsize=7)
    ax.set_xlabel("dt")
    ax.set_ylabel("|edrift| at the end (x: stopped)")
    ax.set_title("energy drift vs dt (base point)", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3, which="both", lw=0.4)

    ax = axs[1]
    mark = {"stable": ("o", "tab:green"), "drifting": ("s", "tab:orange"),
            "stopped": ("X", "tab:red"), "timeout": ("X", "tab:gray")}
    rowlabels = []
    yy = 0
    for eos in EOS:
        for axis in ["dt", "cv", "rho", "T", "rc", "flash"]:
            rows = sorted((r for r in results.values() if r["eos"] == eos and r["axis"] == axis
                           and not r.get("reject")), key=lambda r: r["value"])
            if not rows:
                continue
            for i, r in enumerate(rows):
                m, c = mark[r["outcome"]]
                ax.plot(i, yy, m, color=c, ms=8)
                ax.annotate(fmt_value(axis, r["value"]).replace(" (flash)", ""), (i, yy), xytext=(0, 5),
                            textcoords="offset points", ha="center", fontsize=6)
                rr = results.get(key(dict(r, reject=True)))
                if rr and rr["outcome"] != r["outcome"]:
                    m2, c2 = mark[rr["outcome"]]
                    ax.plot(i + 0.28, yy, m2, color=c2, ms=5, mec="k", mew=0.5)
            rowlabels.append((yy, f"{eos}: {AXIS_NAMES[axis]}"))
            yy -= 1
    ax.set_yticks([y for y, _ in rowlabels])
    ax.set_yticklabels([l for _, l in rowlabels], fontsize=7)
    ax.set_xticks([])
    ax.set_xlim(-0.6, 7.0)
    ax.set_ylim(yy + 0.4, 0.7)
    for name, (m, c) in mark.items():
        if name != "timeout":
            ax.plot([], [], m, color=c, label=name)
    ax.plot([], [], "o", color="w", mec="k", ms=5, label="small: with reject yes")
    ax.legend(fontsize=6, loc="lower right", ncol=2)
    ax.set_title("outcome per axis value (others at base)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def report(results, meta, md_path, png_path):
    figure(results, png_path)
    reading_file = os.path.join(HERE, "reading.md")
    reading = open(reading_file).read().strip() if os.path.exists(reading_file) else "(no reading written)"
    steps = meta["steps"]
    total_wall = meta.get("total_wall")
    doc = f"""# Stability map

Where gendpde's GenDPDE integrator (reversible velocity-Verlet step with the work split, then
the eSSA Shardlow sweep) keeps energy, drifts, or stops, for the van der Waals and the
Lennard-Jones particle EOS. Generated by `scripts/stability/stability_map.py`; the data are
in `scripts/stability/results.json`.

![stability map](stability.png)

## What was run

- Scene (`scripts/stability/in.scene`): sc lattice at density rho, N = n^3 particles with
  n = max(8, smallest n whose box holds 4 cells of side rc + skin), skin 0.3;
  `pair_style gendpde rc` (quadratic weight), `pair_coeff * * 4.5 1.0 rc rc` (gamma = 4.5,
  kappa = 1, the same rc for density, friction and heat), `fix nve/gendpde`,
  `fix shardlow heat original substeps 4` (the 2019 heat model, the default; substeps 4 is
  the default Brownian-bridge splitting of a pair update that would send theta <= 0),
  momenta and theta drawn at T, thermo every 1000 steps
  (`thermo_style custom step temp tint press etotal edrift`).
- EOS: `fix eos/vdw C_V 2.4682 1.4142 excess` (argon, 2019 paper) and `fix eos/lj C_V`
  (Lennard-Jones, Kolafa-Nezbeda).
- Base point: dt = 0.01, C_V = 60, rho = 0.5, T = 1.5, rc = 2 (N = 512). One axis varied at
  a time: dt in {{0.001 ... 0.2}}, C_V in {{1.5, 3, 10, 60, 1000}}, rho from 0.01 (isolated
  particles: lattice spacing 4.6 > rc) to 0.65 (vdW, cap 1/b = 0.707) or 0.8 (LJ),
  T in {{0.1 ... 10}}, rc in {{1.5, 2, 3}} (rc = 3 needs a 13.2 box: N = 1331 at rho = 0.5).
  Flash (`scripts/stability/in.flash`): half the steps at T = 1.5, then
  `velocity all create 50 ...` + `set group all theta 50`, and the other half; its drift is
  measured from the first thermo line after the heating (edrift refers to the first run's E0).
- Steps: **{steps['vdw']} for vdW, {steps['lj']} for LJ** (`eos/lj` costs about 6-9x more per step than
  `eos/vdw`{'' if steps['lj'] >= steps['vdw'] else ', so the LJ rows were shortened to fit the time budget'}; the flash rows
  run {steps['vdw'] // 2} + {steps['vdw'] // 2} and {steps['lj'] // 2} + {steps['lj'] // 2}).
- Classification: **stable** = finished with |edrift| <= 1e-4 at the end; **drifting** = finished with
  |edrift| > 1e-4; **stopped** = non-zero exit (step and message from stderr). Every stopped
  row was run once more with `fix shardlow ... substeps 4 reject yes` (column `reject yes` rerun).
  "guard: split / left out" counts the pair updates split into half steps by the theta -> 0
  guard and those left out by `reject yes` (printed by `run`).
- Binary: the release build of this commit ({meta.get('binary_note', meta.get('binary'))}). Two runs at a time on the 2-core machine
  {meta.get('load_note', '')}; total wall time of the map {f'{total_wall / 60:.1f} min' if total_wall else '-'}.
- Regenerate: `python3 scripts/stability/stability_map.py` (add `--binary PATH` for another build,
  `--quick` for a 1000-step smoke version, `--report-only` to redraw from results.json).

## Headline

{headline(results)}

## van der Waals EOS

{table(results, 'vdw', ['dt', 'cv', 'rho', 'T', 'rc', 'flash'])}

## Lennard-Jones EOS

{table(results, 'lj', ['dt', 'cv', 'rho', 'T', 'rc', 'flash'])}

## Reading the map

{reading}
"""
    with open(md_path, "w") as f:
        f.write(doc)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--binary", default=os.path.join(ROOT, "target", "release", "gendpde"))
    ap.add_argument("--quick", action="store_true", help="1000 steps per run (smoke test); writes to a temp dir")
    ap.add_argument("--steps", type=int, default=5000, help="steps per vdW run (default 5000)")
    ap.add_argument("--lj-steps", type=int, default=2000, help="steps per LJ run (default 2000)")
    ap.add_argument("--jobs", type=int, default=2, help="simulations at once (default 2)")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds before a run is killed")
    ap.add_argument("--out", default=None, help="directory for STABILITY.md, stability.png (default docs/)")
    ap.add_argument("--report-only", action="store_true", help="redraw the report from results.json")
    ap.add_argument("--no-reject", action="store_true", help="skip the reject-yes reruns")
    a = ap.parse_args()

    if a.quick:
        a.steps = a.lj_steps = 1000
    out = a.out or (tempfile.mkdtemp(prefix="gendpde-stab-quick-") if a.quick else os.path.join(ROOT, "docs"))
    os.makedirs(out, exist_ok=True)
    store = os.path.join(out if a.quick else HERE, "results.json")
    binary = os.path.abspath(a.binary)

    data = json.load(open(store)) if os.path.exists(store) else {"meta": {}, "results": {}}
    if not a.report_only:
        if not os.access(binary, os.X_OK):
            sys.exit(f"no gendpde binary at {binary} (build with cargo build --release, or pass --binary)")
        meta = dict(steps={"vdw": a.steps, "lj": a.lj_steps}, binary=binary)
        if data.get("meta", {}).get("steps") != meta["steps"]:
            data = {"meta": meta, "results": {}}   # other step counts: start afresh
        data["meta"].update(meta)
        done = data["results"]
        t0 = time.monotonic()
        runs = plan(a.steps, a.lj_steps)
        def save():
            json.dump(data, open(store, "w"), indent=1)
        run_all(runs, binary, a.jobs, a.timeout, done, save)
        if not a.no_reject:
            again = [dict({k: v for k, v in r.items() if k in runs[0]}, reject=True)
                     for r in list(done.values()) if r["outcome"] in ("stopped", "timeout") and not r.get("reject")]
            run_all(again, binary, a.jobs, a.timeout, done, save)
        data["meta"]["total_wall"] = data["meta"].get("total_wall_prev", 0) + time.monotonic() - t0
        data["meta"]["total_wall_prev"] = data["meta"]["total_wall"]
        json.dump(data, open(store, "w"), indent=1)
    report(data["results"], data["meta"], os.path.join(out, "STABILITY.md"), os.path.join(out, "stability.png"))
    print(f"wrote {os.path.join(out, 'STABILITY.md')}, {os.path.join(out, 'stability.png')}, {store}")


if __name__ == "__main__":
    main()
