#!/usr/bin/python3
"""What writing the result file costs (issue 33): the Sect. 5 flagship run (sphere2d_h3,
impact2d_h3 with its visualisation frames) of two builds side by side, A B A B ..., with
the default flushes (every 100 rows) and with a flush after every row (the worst case of
SWMR's ordered metadata writes and of the disk reservation before each flush). Whole-process
figures per run: wall and CPU time (user + sys of the child), peak memory, result size;
medians over the runs and the ratios NEW/OLD pair by pair.

usage: benchmarks/result_io.py OLD_BIN NEW_BIN [-n RUNS] [-o OUT.txt]
  OLD_BIN, NEW_BIN: folders with igaprep and ffrsim (e.g. a worktree's build/bin and build/bin)
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run_once(ffrsim, scene, sid_dir, out):
    """One run's wall time, CPU time and peak memory (the process's own rusage)."""
    t0 = time.perf_counter()
    proc = subprocess.Popen([ffrsim, "-q", scene, "--sid-path", sid_dir, "-o", out])
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        sys.exit(f"{ffrsim} {scene}: exit {proc.returncode}")
    return {"wall": wall, "cpu": usage.ru_utime + usage.ru_stime, "rss": usage.ru_maxrss / 1024.0,
            "size": os.path.getsize(out) / 2**20}


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("old_bin")
    p.add_argument("new_bin")
    p.add_argument("-n", type=int, default=5)
    p.add_argument("-o", "--out")
    args = p.parse_args()
    work = tempfile.mkdtemp(prefix="result_io_")
    sid_dir = work
    subprocess.run([os.path.join(args.new_bin, "igaprep"), "-q",
                    os.path.join(SOURCE, "configs", "bodies", "sphere2d_h3.yaml"), "-o",
                    os.path.join(sid_dir, "sphere2d_h3.sid.h5")], check=True)
    with open(os.path.join(SOURCE, "configs", "scenes", "impact2d_h3.yaml")) as f:
        text = f.read()
    assert "flush_rows: 100" in text
    scenes = {"flush every 100 rows": os.path.join(SOURCE, "configs", "scenes", "impact2d_h3.yaml")}
    every = os.path.join(work, "every_row.yaml")
    with open(every, "w") as f:
        f.write(text.replace("flush_rows: 100", "flush_rows: 1\n  flush_interval: 1.0e-9"))
    scenes["flush after every row"] = every
    lines = [f"result_io.py: {args.n} runs per build and variant, alternating; "
             f"old {args.old_bin}, new {args.new_bin}", ""]
    for name, scene in scenes.items():
        runs = {"old": [], "new": []}
        for k in range(args.n + 1):  # the first pair warms the caches, not counted
            for build, bin_dir in (("old", args.old_bin), ("new", args.new_bin)):
                r = run_once(os.path.join(bin_dir, "ffrsim"), scene, sid_dir,
                             os.path.join(work, f"{build}.h5"))
                if k > 0:
                    runs[build].append(r)
        lines.append(f"{name} (1001 rows, 51 frames):")
        for key, unit in (("wall", "s"), ("cpu", "s"), ("rss", "MiB"), ("size", "MiB")):
            old = [r[key] for r in runs["old"]]
            new = [r[key] for r in runs["new"]]
            ratio = [b / a for a, b in zip(old, new)]
            lines.append(f"  {key:5s} old {statistics.median(old):8.3f} {unit:3s}  new "
                         f"{statistics.median(new):8.3f} {unit:3s}  new/old median "
                         f"{statistics.median(ratio):.3f} (min {min(ratio):.3f}, max "
                         f"{max(ratio):.3f})")
        lines.append("")
    print("\n".join(lines))
    if args.out:
        with open(args.out, "w") as f:
            f.write("\n".join(lines))


if __name__ == "__main__":
    main()
