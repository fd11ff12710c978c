"""Time-averaged profiles along a box axis."""
import warnings

import numpy as np
import pandas as pd

# field -> (H5MD element, text-dump columns), the first present is used
_ALIASES = {
    "theta": ("temperature", ("theta", "dpdTheta")),
    "temperature": ("temperature", ("theta", "dpdTheta")),
    "u": ("internal_energy", ("u",)),
    "internal_energy": ("internal_energy", ("u",)),
    "n": ("density", ("n", "rho")),
}
# bin positions within 1e-9 bin widths below an edge count in the upper bin, so that
# lattice planes lying on bin edges fall on one side
_EDGE = 1e-9


def _vector(frame, name, k):
    """Component k of the per-particle vector `name` (velocity/momentum) of an H5MD frame."""
    return np.asarray(frame[name])[:, k]


def _values(frame, field):
    """Per-particle values of `field` in one frame (H5MD Frame or dump DataFrame)."""
    dump = isinstance(frame, pd.DataFrame)
    if field in _ALIASES:
        element, columns = _ALIASES[field]
        if dump:
            for c in columns:
                if c in frame:
                    return frame[c].to_numpy(float)
            if field in ("u", "internal_energy") and {"uCond", "uMech"} <= set(frame.columns):
                return (frame["uCond"] + frame["uMech"]).to_numpy(float)
        elif element in frame:
            return np.asarray(frame[element], dtype=float)
        raise KeyError(f"field {field!r}: the frame has no {element if not dump else ' or '.join(columns)}")
    if len(field) == 2 and field[0] in "vp" and field[1] in "xyz":
        k = "xyz".index(field[1])
        if dump:
            if field in frame:
                return frame[field].to_numpy(float)
            other = ("p" if field[0] == "v" else "v") + field[1]
            if other in frame and "mass" in frame:
                m = frame["mass"].to_numpy(float)
                return frame[other].to_numpy(float) * (1 / m if field[0] == "v" else m)
        else:
            own, other = ("velocity", "momentum") if field[0] == "v" else ("momentum", "velocity")
            if own in frame:
                return _vector(frame, own, k)
            if other in frame and "mass" in frame:
                m = np.asarray(frame["mass"], dtype=float).reshape(-1)
                return _vector(frame, other, k) * (1 / m if field[0] == "v" else m)
        raise KeyError(f"field {field!r}: the frame has neither {field} nor the other of velocity/momentum with mass")
    if field in frame:
        v = np.asarray(frame[field], dtype=float)
        if v.ndim == 1:
            return v
    raise KeyError(f"field {field!r}: no such per-particle scalar in the frame")


def _geometry(frame, d):
    """(positions along axis d, box origin, box edge lengths [3]) of one frame."""
    if isinstance(frame, pd.DataFrame):
        box, lo = np.asarray(frame.attrs["box"], dtype=float), np.asarray(frame.attrs["offset"], dtype=float)
        c = "xyz"[d]
        for name, scaled in ((c, False), (c + "u", False), (c + "s", True), (c + "su", True)):
            if name in frame:
                x = frame[name].to_numpy(float)
                return (lo[d] + x * box[d] if scaled else x), lo, box
        raise KeyError(f"the dump has no {c}, {c}u, {c}s or {c}su column")
    box = np.asarray(frame.box, dtype=float)
    if box.ndim == 2:
        box = np.diag(box)
    return np.asarray(frame["position"])[:, d], np.asarray(frame.offset, dtype=float), box


def profile(frames, axis="x", nbins=50, field="density"):
    """Time-averaged profile of `field` along `axis` over `frames` (H5MD frames from
    `read_h5md` or DataFrames from `read_dump`).

    The box is cut into `nbins` slabs of equal width along the axis; positions are wrapped
    into the box (periodic). field "density": particles per slab volume; any other field
    (theta/temperature, u/internal_energy, n (local density), vx vy vz, px py pz, or a
    per-particle scalar element or column): its mean over the particles in the slab.
    Each frame gives one profile; returns (bin centres, mean over frames, standard error
    of that mean = std over frames / sqrt(frames), which takes the frames as independent:
    space them beyond the correlation time), numpy arrays of length nbins. Bins
    empty in a frame leave it out of their average; an error with fewer than two frames
    is NaN.
    """
    d = "xyz".index(axis)
    per_frame, lengths, origins = [], [], []
    for frame in frames:
        x, lo, box = _geometry(frame, d)
        s = np.mod((x - lo[d]) / box[d], 1.0) * nbins
        b = np.minimum(np.floor(s + _EDGE).astype(np.int64), nbins) % nbins
        counts = np.bincount(b, minlength=nbins).astype(float)
        if field == "density":
            p = counts / (box[d] / nbins * np.prod(np.delete(box, d)))
        else:
            sums = np.bincount(b, weights=_values(frame, field), minlength=nbins)
            with np.errstate(invalid="ignore", divide="ignore"):
                p = np.where(counts > 0, sums / counts, np.nan)
        per_frame.append(p)
        lengths.append(box[d])
        origins.append(lo[d])
    if not per_frame:
        raise ValueError("profile: no frames")
    a = np.array(per_frame)
    centres = np.mean(origins) + (np.arange(nbins) + 0.5) * np.mean(lengths) / nbins
    valid = np.isfinite(a).sum(axis=0)
    with warnings.catch_warnings():  # all-NaN bins: NaN, quietly
        warnings.simplefilter("ignore", RuntimeWarning)
        mean = np.nanmean(a, axis=0)
        err = np.nanstd(a, axis=0, ddof=1) / np.sqrt(valid)
    err[valid < 2] = np.nan
    return centres, mean, err
