"""Drive gendpde runs and read their output: thermo logs, H5MD trajectories, text dumps,
and time-averaged profiles.

    import gendpde
    r = gendpde.run("in.script", vars={"steps": 1000})       # r.logs, r.outputs
    df = gendpde.read_log("log.gendpde")[-1]                  # thermo of the last run
    frames = gendpde.read_h5md("traj.h5")                     # frames[k].position ...
    x, theta, err = gendpde.profile(frames, "x", 20, "theta")
"""
from .dump import read_dump
from .h5md import Frame, H5md, read_h5md
from .log import parse_log, read_log
from .profile import profile
from .runner import GendpdeError, Run, find_binary, run

__all__ = ["read_log", "parse_log", "read_h5md", "H5md", "Frame", "read_dump", "profile", "run", "Run",
           "GendpdeError", "find_binary"]
__version__ = "0.1.0"
