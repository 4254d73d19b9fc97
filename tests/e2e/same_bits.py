"""Bit-for-bit comparison of HDF5 files (SID and result files): every dataset's bytes and
every attribute, by HDF5 path, except what measures the machine (times, memory), describes
the run rather than its results (threads, the XDMF file's name), or, with `builds=True`,
names the build or the files' places (git revision, the SIDs' SHA-256 and paths): two
builds of the same source behaviour then compare equal.

Used by check_reproducible.py (same build, same bits) and compare_builds.py (a refactor
against the commit before it)."""
import h5py
import numpy as np

# Attributes that are measurements of the machine, not results.
TIMING = ("wall_time_s", "cpu_time_s", "preprocessing_time_s", "peak_memory")  # and stage times

# Attributes that describe the run, not its results: the thread count (provenance) and the
# name of the XDMF file beside the result (named after the result file).
RUN = ("threads", "xdmf")

# Attributes that name the build or where the files lie: the git revision (also inside
# each SID, so the SIDs' SHA-256 differ too), the paths of the body file, the scene and the
# SIDs (another checkout has other absolute paths).
BUILD = ("git_revision", "sid_sha256", "sid_file", "sid_files", "scene_path", "input_path")


def ignored(path, name, builds):
    if any(t in name for t in TIMING) or name.endswith("_wall_s") or "stage_times" in path:
        return True
    if name in RUN:
        return True
    return builds and name in BUILD


def contents(path, builds=False):
    """Every dataset's bytes and every attribute not ignored, by HDF5 path."""
    items = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            for k, v in obj.attrs.items():
                if not ignored(name, k, builds):
                    items[f"{name}@{k}"] = np.asarray(v).tobytes()
            if isinstance(obj, h5py.Dataset):
                items[name] = (obj.dtype.str, obj.shape, np.asarray(obj[()]).tobytes())
        visit("/", f)
        f.visititems(visit)
    return items


def differences(a, b, ignore=(), builds=False):
    """(number of items compared, sorted list of the paths that differ)."""
    ca, cb = contents(a, builds), contents(b, builds)
    for k in ignore:
        ca.pop(k, None), cb.pop(k, None)
    return len(ca), sorted(k for k in set(ca) | set(cb) if ca.get(k) != cb.get(k))
