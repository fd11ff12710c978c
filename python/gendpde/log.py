"""Thermo tables of gendpde's log.gendpde / stdout, and of LAMMPS's log.lammps."""
import re

import numpy as np
import pandas as pd

_LOOP = re.compile(r"Loop time of\s+(\S+)\s+on\s+(\d+)\s+procs?\s+for\s+(\d+)\s+steps\s+with\s+(\d+)\s+atoms")
_SETUP = re.compile(r"Setting up \S+ run:\s*(\d+) particles, timestep\s+(\S+)")
_PERF = re.compile(r"([-+0-9.eE]+)\s+([^,]+)")
_INTEGER = {"Step", "Elapsed", "Elaplong", "Atoms", "Nbuild", "Ndanger"}  # integer keywords
_HEADER = re.compile(r"[A-Za-z_][^\s:'\"]*(\s+[A-Za-z_][^\s:'\"]*)*")
_STAT = re.compile(r"^\s*([A-Za-z][^=:]*?)\s*=\s*([-+0-9.eE]+)(?:\s|$)")


def read_log(path):
    """One DataFrame per run of the log file at `path` (see `parse_log`)."""
    with open(path, encoding="utf-8", errors="replace") as f:
        return parse_log(f.read())


def _number(word):
    try:
        return float(word)
    except ValueError:
        return None


def _frame(header, rows):
    columns = {}
    for k, name in enumerate(header):
        words = [r[k] for r in rows]
        if name in _INTEGER and all(re.fullmatch(r"[-+]?\d+", w) for w in words):
            columns[name] = np.array([int(w) for w in words], dtype=np.int64)
        else:
            columns[name] = np.array([float(w) for w in words], dtype=float)
    if len(set(header)) < len(header):  # a dict would drop repeated keywords
        return pd.DataFrame(np.column_stack(list(columns.values())) if rows else None, columns=header)
    return pd.DataFrame(columns, columns=header)


def parse_log(text):
    """Thermo tables of a LAMMPS-style log or stdout, one DataFrame per run.

    A table starts at a header row holding the keyword `Step` and ends at its `Loop time`
    line; rows are the lines with one number per column (warnings and other lines between
    them are skipped). Step, Elapsed, Atoms ... are int64, the others float64. A run cut
    off before its `Loop time` line (a killed run) is kept with attrs["complete"] False.

    df.attrs: run (index), complete, keywords (the header), first_step, last_step, units
    and timestep (the last `units` and `timestep` commands echoed before the run, or the
    "Setting up" line), natoms, and from the lines after the run: loop_time (s), nprocs,
    steps, atom_steps_per_s, performance ({unit: value} of the "Performance:" line) and
    stats ({name: value} of "name = value" lines such as "Neighbor list builds = 42").
    """
    runs, settings = [], {}
    header, rows, attrs, last = None, [], {}, None

    def close(complete):
        nonlocal header, rows, attrs, last
        df = _frame(header, rows)
        df.attrs.update(attrs)
        df.attrs.update(run=len(runs), complete=complete, keywords=list(header),
                        first_step=int(df["Step"].iloc[0]) if rows else None,
                        last_step=int(df["Step"].iloc[-1]) if rows else None)
        runs.append(df)
        last = df
        header, rows, attrs = None, [], {}

    for line in text.splitlines():
        words = line.split()
        if not words:
            continue
        if "Step" in words and all(_number(w) is None for w in words) and _HEADER.fullmatch(line.strip()):
            if header is not None and rows:
                close(False)
            header, rows, attrs, last = words, [], dict(settings), None
            continue
        if header is not None:
            if len(words) == len(header) and all(_number(w) is not None for w in words):
                rows.append(words)
                continue
            m = _LOOP.match(line.strip())
            if m:
                t, procs, steps, atoms = m.groups()
                attrs.update(loop_time=float(t), nprocs=int(procs), steps=int(steps), natoms=int(atoms))
                if float(t) > 0:
                    attrs["atom_steps_per_s"] = int(atoms) * int(steps) / float(t)
                close(True)
            continue
        # outside a table: the run's settings before it, its statistics after it
        if words[0] == "units" and len(words) >= 2:
            settings["units"] = words[1]
        elif words[0] == "timestep" and len(words) >= 2 and _number(words[1]) is not None:
            settings["timestep"] = float(words[1])
        elif words[0] == "thermo_style":
            settings["thermo_style"] = " ".join(words[1:])
        elif line.startswith("Setting up"):
            m = _SETUP.match(line)
            if m:
                settings.update(natoms=int(m.group(1)), timestep=float(m.group(2)))
        elif last is not None and words[0] == "Performance:":
            last.attrs["performance"] = {u.strip(): float(v) for v, u in _PERF.findall(line.split(":", 1)[1])}
        elif last is not None:
            m = _STAT.match(line)
            if m:
                last.attrs.setdefault("stats", {})[m.group(1)] = float(m.group(2))
    if header is not None and rows:
        close(False)
    return runs
