"""The two jobs of a study: build one cached SID (igaprep), run one scene (ffrsim); their
records are specified in schemas/study_outputs.md.

Each job leaves a small JSON record beside its output, the thing the workflow tracks:

* SID record `SIDS/<stem>.json`: status `built` or `failed` (igaprep's exit code and its
  error line), the body file, the overrides, igaprep's version, the SID's size and SHA-256,
  wall and CPU time and peak memory of the igaprep process.
* Run summary `RUNS/<id>/summary.json`: the parameter values, status `completed` or
  `failed` (with the failing program's exit code and message, e.g. a bad parameter value,
  exit code 2), the collected figures read from the result file's attributes (`sid:NAME`:
  the root attribute NAME of the run's first SID, e.g. sid:ndof), and the timings of
  ffrsim and of building the run's SIDs.

A run whose inputs are bad, or that fails while computing, is a result of the study: its
summary says so and the job succeeds, so that the other runs go on and the table marks
it. A run that was stopped (SIGTERM from a scheduler's time limit, SIGKILL, out of memory)
is not a result: the job fails, the workflow reports it, and the next invocation continues
the run from its result file with `ffrsim --restart`.

Records are written to a temporary name and renamed: a killed job leaves none behind.
"""
import hashlib
import json
import os
import subprocess
import tempfile
import time

import h5py

from study_file import value_text


def program_versions(bin_dir):
    """The programs' --version lines; part of every SID and run hash."""
    out = {}
    for prog in ("igaprep", "ffrsim"):
        exe = os.path.join(bin_dir, prog)
        try:
            p = subprocess.run([exe, "--version"], capture_output=True, text=True, check=True)
        except (OSError, subprocess.CalledProcessError) as e:
            raise RuntimeError(f"cannot run '{exe} --version' ({e}): build the programs first "
                               f"(bash .ci/build) or give config bin=FOLDER")
        out[prog] = p.stdout.strip()
    return out


def write_json(path, data):
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(data, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(tmp, path)


def _timed(cmd):
    """Runs cmd; returns (exit code, stderr text, wall s, CPU s, peak RSS MiB) of that one
    process (os.wait4: its own resource usage, not that of earlier children)."""
    with tempfile.TemporaryFile(mode="w+") as err:
        t0 = time.monotonic()
        p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(p.pid, 0)
        wall = time.monotonic() - t0
        p.returncode = os.waitstatus_to_exitcode(status)
        err.seek(0)
        return (p.returncode, err.read(), wall, usage.ru_utime + usage.ru_stime,
                usage.ru_maxrss / 1024.0)


def _error_line(stderr):
    lines = [l for l in stderr.strip().splitlines() if l.strip()]
    errors = [l for l in lines if ": error:" in l]
    return (errors or lines or ["(no message)"])[-1].strip()


def _sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def build_sid(bin_dir, sid, sid_dir, threads, version):
    """igaprep BODY --set ... -o SIDS/<stem>.sid.h5; writes and returns the SID record."""
    os.makedirs(sid_dir, exist_ok=True)
    out = os.path.join(sid_dir, sid.stem + ".sid.h5")
    cmd = [os.path.join(bin_dir, "igaprep"), "-q", sid.body_file, "-o", out,
           "--threads", str(threads)]
    for s in sid.overrides:
        cmd += ["--set", s]
    code, stderr, wall, cpu, rss = _timed(cmd)
    record = {"sid": os.path.basename(out), "body_file": sid.body_file,
              "overrides": sid.overrides, "igaprep_version": version, "hash": sid.hash,
              "exit_code": code, "wall_s": wall, "cpu_s": cpu, "peak_rss_mib": rss,
              "threads": threads, "slurm_job_id": os.environ.get("SLURM_JOB_ID")}
    if code == 0:
        record.update(status="built", bytes=os.path.getsize(out), sha256=_sha256(out),
                      attributes=_sid_attributes(out))
    elif code in (1, 2):
        record.update(status="failed", message=_error_line(stderr))
    else:  # killed: not an answer about this body
        raise RuntimeError(f"igaprep stopped by signal {-code}: {' '.join(cmd)}")
    write_json(os.path.join(sid_dir, sid.stem + ".json"), record)
    return record


def _scalar(v):
    """An HDF5 attribute as a Python value: numpy scalars as int or float, bytes as str."""
    if hasattr(v, "item") and getattr(v, "size", 1) == 1:
        v = v.item()
    return v.decode() if isinstance(v, bytes) else v


def _sid_attributes(path):
    """The SID's scalar root attributes (ndof, nq, n_interface_control_points, ...), for the
    table's sid:NAME columns; not the copied body file."""
    with h5py.File(path, "r") as f:
        values = {k: _scalar(v) for k, v in f.attrs.items()}
    return {k: v for k, v in values.items()
            if isinstance(v, (int, float)) or (isinstance(v, str) and "\n" not in v)}


def _status(result):
    try:
        with h5py.File(result, "r") as f:
            return str(f.attrs.get("status", "")), "restart" in f
    except OSError:
        return "", False


def _figure(f, name):
    """A root attribute, or /GROUP@ATTRIBUTE; None where the result has none."""
    group, attr = (name[:name.index("@")], name[name.index("@") + 1:]) if "@" in name \
        else ("/", name)
    if group not in f or attr not in f[group].attrs:
        return None
    return _scalar(f[group].attrs[attr])


def _ffrsim_command(bin_dir, run, sid_dir, result, threads):
    status, restartable = _status(result) if os.path.exists(result) else ("", False)
    if status.startswith("interrupted") or (status == "running" and restartable):
        # Stopped by a signal or killed: continue where the file ends (e2e.restart).
        return [os.path.join(bin_dir, "ffrsim"), "-q", "--restart", result,
                "--threads", str(threads)], True
    cmd = [os.path.join(bin_dir, "ffrsim"), "-q", run.scene, "-o", result,
           "--threads", str(threads)]
    for s in run.ffrsim_sets(sid_dir):
        cmd += ["--set", s]
    return cmd, False


def run_scene(bin_dir, study, run, sid_dir, run_dir, threads):
    """ffrsim for one run; writes and returns its summary (see the module comment)."""
    os.makedirs(run_dir, exist_ok=True)
    summary = {"run": run.id, "study": study.name,
               "values": {k: value_text(v) for k, v in run.values.items()},
               "scene": run.scene, "scene_overrides": run.scene_overrides,
               "sids": {n: s.stem + ".sid.h5" for n, s in run.sids.items()},
               "slurm_job_id": os.environ.get("SLURM_JOB_ID")}
    records = {}
    for name, sid in run.sids.items():
        with open(os.path.join(sid_dir, sid.stem + ".json"), encoding="utf-8") as f:
            records[name] = record = json.load(f)
        if record["status"] != "built":
            summary.update(status="failed", exit_code=record["exit_code"], program="igaprep",
                           message=f"SID {name}: {record['message']}")
            write_json(os.path.join(run_dir, "summary.json"), summary)
            return summary
    result = os.path.join(run_dir, "result.h5")
    cmd, restarted = _ffrsim_command(bin_dir, run, sid_dir, result, threads)
    code, stderr, wall, cpu, rss = _timed(cmd)
    status, _ = _status(result)
    if code < 0 or status.startswith("interrupted") or status == "running":
        raise RuntimeError(f"ffrsim was stopped (exit code {code}, status '{status}'); run "
                           f"the workflow again to continue it from {result}: "
                           f"{_error_line(stderr)}")
    summary.update(exit_code=code, program="ffrsim", restarted=restarted,
                   timings={"process_wall_s": wall, "process_cpu_s": cpu,
                            "peak_rss_mib": rss, "threads": threads,
                            "igaprep_wall_s": sum(r["wall_s"] for r in records.values()),
                            "igaprep_cpu_s": sum(r["cpu_s"] for r in records.values()),
                            "igaprep_peak_rss_mib": max(
                                [r["peak_rss_mib"] for r in records.values()], default=0)})
    if code == 0:
        summary["status"] = "completed"
    else:  # 2: bad input (e.g. a parameter value the schema refuses), 1: failed computing
        summary.update(status="failed", message=_error_line(stderr))
    if os.path.exists(result) and code != 2:
        summary["result"] = result
        summary["result_status"] = status
        with h5py.File(result, "r") as f:
            summary["timings"]["wall_time_s"] = _figure(f, "wall_time_s")
            if code == 0:
                first = next(iter(records.values()), {}).get("attributes", {})
                summary["figures"] = {c: first.get(c[4:]) if c.startswith("sid:")
                                      else _figure(f, c) for c in study.collect}
    write_json(os.path.join(run_dir, "summary.json"), summary)
    return summary
