#!/usr/bin/env python3
"""Reads a gendpde H5MD snapshot file and plots, for one frame, the density profile along
an axis and the histogram of the particle temperature theta (PNG).

    pip install -r scripts/requirements.txt
    python3 scripts/h5md_profile.py run.h5 --frame -1 --axis x --bins 50 --out profile.png

The file layout is H5MD 1.1 (h5md.nongnu.org): /particles/all/{position, temperature,
internal_energy, momentum, ...}/{value, step, time} and /particles/all/box/edges/value.
"""
import argparse
import sys

import h5py
import numpy as np


def open_h5md(path):
    """Opens the file; a file whose writer was killed is still marked open for writing
    and opens in SWMR-read mode (or run `h5clear -s -i` on it)."""
    try:
        return h5py.File(path, "r")
    except OSError:
        return h5py.File(path, "r", swmr=True)


def load(path, frame):
    """Positions, theta (None when not dumped), box edges, step and time of one frame."""
    with open_h5md(path) as f:
        if "h5md" not in f or "particles/all" not in f:
            sys.exit(f"{path}: not an H5MD file (no /h5md or /particles/all)")
        part = f["particles/all"]
        pos = part["position"]
        nframes = len(pos["step"])  # frames counted by completed steps
        if nframes == 0:
            sys.exit(f"{path}: no complete frame")
        k = frame if frame >= 0 else nframes + frame
        if not 0 <= k < nframes:
            sys.exit(f"{path}: frame {frame} outside 0..{nframes - 1}")
        edges = part["box/edges"]  # a time-dependent element (older files: a dataset)
        edges = np.asarray(edges["value"][k] if hasattr(edges, "keys") else edges)
        r = np.asarray(pos["value"][k])
        theta = np.asarray(part["temperature/value"][k]) if "temperature" in part else None
        return r, theta, edges, int(pos["step"][k]), float(pos["time"][k])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("file")
    ap.add_argument("--frame", type=int, default=-1, help="frame index (negative: from the end)")
    ap.add_argument("--axis", choices="xyz", default="x")
    ap.add_argument("--bins", type=int, default=50)
    ap.add_argument("--out", default="profile.png")
    args = ap.parse_args()

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    r, theta, edges, step, time = load(args.file, args.frame)
    d = "xyz".index(args.axis)
    length = edges[d]
    x = np.mod(r[:, d], length)  # positions folded into one box length
    counts, bounds = np.histogram(x, bins=args.bins, range=(0.0, length))
    slab = length / args.bins * np.prod([edges[k] for k in range(3) if k != d])
    centres = 0.5 * (bounds[1:] + bounds[:-1])

    fig, axes = plt.subplots(1, 2 if theta is not None else 1, figsize=(10, 4), squeeze=False)
    axes[0, 0].plot(centres, counts / slab, drawstyle="steps-mid")
    axes[0, 0].set_xlabel(args.axis)
    axes[0, 0].set_ylabel("number density")
    axes[0, 0].set_title(f"step {step}, t = {time:g}")
    if theta is not None:
        axes[0, 1].hist(theta, bins=args.bins, density=True)
        axes[0, 1].set_xlabel("particle temperature theta")
        axes[0, 1].set_ylabel("probability density")
        axes[0, 1].set_title(f"<theta> = {theta.mean():.5g}")
    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    print(f"{args.out}: frame at step {step}, {len(r)} particles")


if __name__ == "__main__":
    main()
