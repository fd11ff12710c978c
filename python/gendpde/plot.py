"""Plots of gendpde output (needs matplotlib).

    python -m gendpde.plot profile FILE [--axis x] [--bins 20] [--field density --field theta]
                                        [--start STEP] [--units lj|real|metal] [-o profile.png]

FILE is an H5MD file (`dump h5md`) or a LAMMPS text dump (`write_dump`, `dump custom`).
Each field gets one panel: its profile along the axis, averaged over the frames from step
START on, with error bars of one standard error over the frames.
"""
import argparse
import sys

import h5py

from .dump import read_dump
from .h5md import read_h5md
from .profile import profile

# unit system -> (length, temperature, velocity, energy, momentum); lj: reduced units
UNITS = {
    "lj": ("σ", "ε/k_B", "(ε/m)^½", "ε", "(mε)^½"),
    "real": ("Å", "K", "Å/fs", "kcal/mol", "g/mol Å/fs"),
    "metal": ("Å", "K", "Å/ps", "eV", "g/mol Å/ps"),
}


def label(field, units="lj", axis=None):
    """Axis label of a profile quantity (or of the position along `axis`) with its unit."""
    length, temp, vel, energy, mom = UNITS[units]
    tail = ", reduced units" if units == "lj" else ""
    if axis is not None:
        return f"{axis} [{length}{tail}]"
    names = {"density": ("number density", f"{length}⁻³"), "theta": ("particle temperature θ", temp),
             "temperature": ("particle temperature θ", temp), "u": ("internal energy u", energy),
             "internal_energy": ("internal energy u", energy), "n": ("local density n", f"{length}⁻³")}
    if field in names:
        name, unit = names[field]
    elif len(field) == 2 and field[0] in "vp" and field[1] in "xyz":
        name, unit = ("velocity " if field[0] == "v" else "momentum ") + field, vel if field[0] == "v" else mom
    else:
        return field
    return f"{name} [{unit}{tail}]"


def load_frames(path, start=None):
    """Frames of an H5MD file or a text dump, those with step >= start."""
    frames = list(read_h5md(path)) if h5py.is_hdf5(path) else read_dump(path)
    step = (lambda f: f.attrs["step"]) if frames and not hasattr(frames[0], "step") else (lambda f: f.step)
    return [f for f in frames if start is None or step(f) >= start]


def file_units(frame):
    """The unit system a frame states: a dump's ITEM: UNITS, or guessed from H5MD unit
    attributes (fs: real, ps: metal); None when it states none."""
    if not hasattr(frame, "step"):
        return frame.attrs.get("units")
    text = " ".join(frame.units.values())
    return "real" if "fs" in text else "metal" if "ps" in text else None


def profile_figure(frames, axis="x", nbins=20, fields=("density", "theta"), units="lj", title=None):
    """A matplotlib Figure with one panel per field: its profile along `axis` with error
    bars (see `gendpde.profile`)."""
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(fields), figsize=(5.5 * len(fields), 4), squeeze=False)
    for ax, field in zip(axes[0], fields):
        x, mean, err = profile(frames, axis, nbins, field)
        ax.errorbar(x, mean, yerr=err, fmt="o-", ms=3, capsize=2)
        ax.set_xlabel(label(None, units, axis))
        ax.set_ylabel(label(field, units))
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m gendpde.plot", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="command", required=True)
    p = sub.add_parser("profile", help="time-averaged profiles along an axis")
    p.add_argument("file")
    p.add_argument("--axis", choices="xyz", default="x")
    p.add_argument("--bins", type=int, default=20)
    p.add_argument("--field", action="append", help="density, theta, u, n, vx, ... (repeatable; "
                   "default: density and theta, or density alone when the file has no theta)")
    p.add_argument("--start", type=int, help="first step averaged (default: every frame)")
    p.add_argument("--units", choices=sorted(UNITS), help="unit system (default: the file's, else lj)")
    p.add_argument("-o", "--output", default="profile.png")
    args = ap.parse_args(argv)

    import matplotlib
    matplotlib.use("Agg")
    frames = load_frames(args.file, args.start)
    if not frames:
        sys.exit(f"{args.file}: no frame" + (f" at or after step {args.start}" if args.start is not None else ""))
    first, last = frames[0], frames[-1]
    dump = not hasattr(first, "step")
    units = args.units or file_units(first) or "lj"
    fields = args.field
    if not fields:
        has_theta = any(c in first for c in ("theta", "dpdTheta")) if dump else "temperature" in first
        fields = ["density", "theta"] if has_theta else ["density"]
    steps = (first.attrs["step"], last.attrs["step"]) if dump else (first.step, last.step)
    title = f"{args.file}: {len(frames)} frames, steps {steps[0]}-{steps[1]}"
    fig = profile_figure(frames, args.axis, args.bins, fields, units, title)
    fig.savefig(args.output, dpi=100)
    print(f"{args.output}: {', '.join(fields)} along {args.axis}, {len(frames)} frames")


if __name__ == "__main__":
    main()
