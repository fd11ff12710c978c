#!/usr/bin/env python3
"""Reads a gendpde H5MD snapshot file and plots, for one frame, the density profile along
an axis and the histogram of the particle temperature theta (PNG).

    pip install ./python
    python3 scripts/h5md_profile.py run.h5 --frame -1 --axis x --bins 50 --out profile.png

Time-averaged profiles with error bars: `python -m gendpde.plot profile run.h5`.
The file layout is H5MD 1.1 (h5md.nongnu.org): /particles/all/{position, temperature,
internal_energy, momentum, ...}/{value, step, time} and /particles/all/box/edges.
"""
import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))  # the gendpde package
import gendpde  # noqa: E402
from gendpde.plot import label  # noqa: E402


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

    try:
        frames = gendpde.read_h5md(args.file)
    except (OSError, ValueError) as e:
        sys.exit(f"{args.file}: {e}")
    with frames:
        if len(frames) == 0:
            sys.exit(f"{args.file}: no complete frame")
        try:
            frame = frames[args.frame]
        except IndexError:
            sys.exit(f"{args.file}: frame {args.frame} outside 0..{len(frames) - 1}")
    theta = frame["temperature"] if "temperature" in frame else None
    centres, density, _ = gendpde.profile([frame], args.axis, args.bins, "density")

    fig, axes = plt.subplots(1, 2 if theta is not None else 1, figsize=(10, 4), squeeze=False)
    axes[0, 0].plot(centres, density, drawstyle="steps-mid")
    axes[0, 0].set_xlabel(label(None, axis=args.axis))
    axes[0, 0].set_ylabel(label("density"))
    axes[0, 0].set_title(f"step {frame.step}, t = {frame.time:g}")
    if theta is not None:
        axes[0, 1].hist(theta, bins=args.bins, density=True)
        axes[0, 1].set_xlabel(label("theta"))
        axes[0, 1].set_ylabel("probability density [k_B/ε, reduced units]")
        axes[0, 1].set_title(f"<theta> = {theta.mean():.5g}")
    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    print(f"{args.out}: frame at step {frame.step}, {len(frame['position'])} particles")


if __name__ == "__main__":
    main()
