"""H5MD 1.1 trajectories (h5md.nongnu.org) as gendpde's `dump h5md` writes them."""
import h5py
import numpy as np
import pandas as pd


def open_h5(path):
    """h5py.File of `path` for reading; a file whose writer was killed (still marked open
    for writing) opens in SWMR-read mode."""
    try:
        return h5py.File(path, "r")
    except OSError:
        return h5py.File(path, "r", swmr=True)


class Frame:
    """One frame: `step`, `time`, `box` (edge lengths [3], or [3, 3] edge vectors for a
    triclinic box), `offset` (box origin [3]; zeros when the file has none) and one numpy
    array per particle element, as attributes and items: vectors [N, 3] (position,
    velocity, momentum, image), scalars [N] (id, species, mass, internal_energy,
    temperature, density), rows in the file's order (gendpde: sorted by particle id).
    gendpde wraps positions into the box at neighbour-list builds, so a position may lie
    slightly outside it (`image` counts the wraps)."""

    def __init__(self, step, time, box, offset, elements, units=None):
        self.step, self.time, self.box, self.offset = step, time, box, offset
        self.elements = elements
        self.units = units or {}

    def __getitem__(self, name):
        return self.elements[name]

    def __getattr__(self, name):
        try:
            return self.__dict__["elements"][name]
        except KeyError:
            raise AttributeError(name) from None

    def __contains__(self, name):
        return name in self.elements

    def keys(self):
        return self.elements.keys()

    def __repr__(self):
        shapes = ", ".join(f"{k}{list(v.shape)}" for k, v in self.elements.items())
        return f"Frame(step={self.step}, time={self.time:g}, box={np.asarray(self.box).tolist()}, {shapes})"


class _Element:
    """A time-dependent element (group value/step/time) or a time-independent dataset."""

    def __init__(self, obj):
        if isinstance(obj, h5py.Dataset):
            self.value, self.steps, self.times = obj, None, None
        else:
            self.value = obj["value"]
            self.steps = np.asarray(obj["step"][()]).reshape(-1)
            # frames are counted by completed steps: a value or time beyond them is a frame
            # whose writer was killed
            self.times = np.asarray(obj["time"][()]).reshape(-1)[: len(self.steps)] if "time" in obj else None
        self.unit = self.value.attrs.get("unit")
        if isinstance(self.unit, bytes):
            self.unit = self.unit.decode()

    def at(self, step):
        """Value at `step`: the frame with that step, else the last one before it."""
        if self.steps is None:
            return self.value[()]
        k = int(np.searchsorted(self.steps, step, side="right")) - 1
        if k < 0:
            return None
        return self.value[k]


class H5md:
    """The frames of an H5MD file, read lazily: len(), indexing (negative and slices
    too), iteration; `array(name)` reads one element over all frames at once.

    Frames are the steps of the `position` element (else of the first element); an
    element stored at other steps gives its last value at or before the frame's step, a
    time-independent element (a plain dataset) the same value in every frame. The box
    `edges` may be a fixed dataset or a time-dependent element (value/step/time).
    `observables()` reads the /observables group as a DataFrame.
    """

    def __init__(self, path, group="all"):
        self.path = str(path)
        self.file = open_h5(path)
        if "h5md" not in self.file or f"particles/{group}" not in self.file:
            self.file.close()
            raise ValueError(f"{path}: not an H5MD file (no /h5md or /particles/{group})")
        part = self.file[f"particles/{group}"]
        self.elements = {k: _Element(v) for k, v in part.items() if k != "box"}
        box = part["box"] if "box" in part else {}
        self._edges = _Element(box["edges"]) if "edges" in box else None
        self._offset = _Element(box["offset"]) if "offset" in box else None
        self.boundary = [b.decode() if isinstance(b, bytes) else str(b) for b in box.attrs.get("boundary", [])] if box else []
        timed = [e for e in self.elements.values() if e.steps is not None]
        ref = self.elements.get("position")
        ref = ref if ref is not None and ref.steps is not None else (timed[0] if timed else None)
        self.steps = ref.steps if ref is not None else np.zeros(0, dtype=np.int64)
        self.times = ref.times if ref is not None and ref.times is not None else self.steps.astype(float)
        self.units = {k: e.unit for k, e in self.elements.items() if e.unit}

    def __len__(self):
        return len(self.steps)

    def __iter__(self):
        return (self[k] for k in range(len(self)))

    def __getitem__(self, k):
        if isinstance(k, slice):
            return [self[i] for i in range(*k.indices(len(self)))]
        n = len(self)
        if not -n <= k < n:
            raise IndexError(f"frame {k} outside 0..{n - 1}")
        k %= n
        step = int(self.steps[k])
        elements = {}
        for name, e in self.elements.items():
            v = e.at(step)
            if v is not None:
                elements[name] = np.asarray(v)
        box = np.asarray(self._edges.at(step), dtype=float) if self._edges is not None else None
        offset = np.asarray(self._offset.at(step), dtype=float) if self._offset is not None else np.zeros(3)
        return Frame(step, float(self.times[k]), box, offset, elements, self.units)

    def array(self, name):
        """[frames, N, ...] values of one time-dependent element (its complete frames)."""
        e = self.elements[name]
        if e.steps is None:
            return e.value[()]
        return e.value[: len(e.steps)]

    def observables(self):
        """/observables/<name>/{value,step,time} as a DataFrame indexed by step (empty
        when the file has none); vector observables give one column per component."""
        cols = {}
        obs = self.file.get("observables")
        if obs is None:
            return pd.DataFrame()
        for name, g in obs.items():
            if not isinstance(g, h5py.Group) or "value" not in g:
                continue
            steps = np.asarray(g["step"][()]).reshape(-1)
            v = np.asarray(g["value"][: len(steps)])
            if v.ndim == 1:
                cols[name] = pd.Series(v, index=steps)
            else:
                for j in range(v.shape[1]):
                    cols[f"{name}[{j}]"] = pd.Series(v[:, j], index=steps)
        df = pd.DataFrame(cols)
        df.index.name = "step"
        return df

    def close(self):
        self.file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def read_h5md(path, group="all"):
    """The frames of the H5MD file at `path` (an `H5md`: lazy, indexable, iterable; use it
    as a context manager or call close())."""
    return H5md(path, group)
