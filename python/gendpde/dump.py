"""LAMMPS text dumps (`write_dump`/`dump custom`, `dump atom`)."""
import io

import numpy as np
import pandas as pd


def read_dump(path):
    """The frames of a LAMMPS text dump, one DataFrame per frame with one column per
    `ITEM: ATOMS` keyword (rows in the file's order).

    df.attrs: step, time (when the dump has `ITEM: TIME`, else None), units (`ITEM: UNITS`,
    else None), natoms, bounds ([3, 2] lo/hi as written; for a triclinic box LAMMPS's
    bounding box), tilt ([xy, xz, yz], zeros for an orthogonal box), boundary (e.g.
    ["pp", "pp", "pp"]), box (edge lengths [3]: hi - lo, less the tilt for triclinic) and
    offset (the box origin [3]).
    """
    with open(path, encoding="utf-8", errors="replace") as f:
        lines = f.read().splitlines()
    frames, i, attrs = [], 0, {"time": None, "units": None}
    while i < len(lines):
        line = lines[i].strip()
        i += 1
        if not line.startswith("ITEM:"):
            continue
        item = line[5:].strip()
        if item == "TIMESTEP":
            attrs["step"] = int(lines[i].split()[0])
            i += 1
        elif item == "TIME":
            attrs["time"] = float(lines[i].split()[0])
            i += 1
        elif item == "UNITS":
            attrs["units"] = lines[i].strip()
            i += 1
        elif item == "NUMBER OF ATOMS":
            attrs["natoms"] = int(lines[i].split()[0])
            i += 1
        elif item.startswith("BOX BOUNDS"):
            flags = item.split()[2:]
            rows = np.array([[float(w) for w in lines[i + d].split()] for d in range(3)])
            i += 3
            triclinic = flags[:3] == ["xy", "xz", "yz"]
            tilt = rows[:, 2] if triclinic else np.zeros(3)
            bounds = rows[:, :2]
            lo, hi = bounds[:, 0].copy(), bounds[:, 1].copy()
            if triclinic:  # LAMMPS writes the bounding box: remove the tilts
                xy, xz, yz = tilt
                lo[0] -= min(0.0, xy, xz, xy + xz)
                hi[0] -= max(0.0, xy, xz, xy + xz)
                lo[1] -= min(0.0, yz)
                hi[1] -= max(0.0, yz)
            attrs.update(bounds=bounds, tilt=tilt, boundary=flags[3:] if triclinic else flags,
                         box=hi - lo, offset=lo)
        elif item.startswith("ATOMS"):
            columns = item.split()[1:]
            n = attrs.get("natoms", 0)
            body = "\n".join(lines[i:i + n])
            i += n
            if n:
                df = pd.read_csv(io.StringIO(body), sep=r"\s+", header=None, names=columns)
            else:
                df = pd.DataFrame(columns=columns)
            if len(df) != n or (n and df.iloc[-1].isna().any()):
                break  # a frame cut off by a killed writer
            df.attrs.update(attrs)
            frames.append(df)
            attrs = {"time": None, "units": attrs["units"]}  # ITEM: TIME comes before TIMESTEP
    return frames
