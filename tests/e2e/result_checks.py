"""Shared pieces of the end-to-end checks: a check list that prints ok / FAIL per item and
the exit code, commands that must succeed, and the result file's status as text (h5py may
return bytes)."""
import subprocess
import sys


class Checks:
    def __init__(self):
        self.failures = []

    def __call__(self, ok, what):
        print(("ok   " if ok else "FAIL ") + what)
        if not ok:
            self.failures.append(what)

    def status_completed(self, f):
        status = f.attrs["status"]
        status = status.decode() if isinstance(status, bytes) else status
        self(status == "completed", f"status {status}")

    def run(self, cmd, **kwargs):
        """Runs `cmd` (a list); if it exits non-zero, prints its output, records the failure
        and exits. Returns the finished process (output captured as text)."""
        r = subprocess.run(cmd, capture_output=True, text=True, **kwargs)
        if r.returncode != 0:
            print(r.stdout + r.stderr)
            self(False, f"{' '.join(cmd)} exited with {r.returncode}")
            self.exit()
        return r

    def exit(self):
        sys.exit(1 if self.failures else 0)


def signal_at_fraction(cmd, end_time, fraction, sig):
    """Runs `cmd` (an ffrsim run with -v, so that it prints progress lines), sends `sig` as
    soon as the run has passed `fraction` of `end_time` (a random moment of the run on any
    machine, loaded or not) and waits for it. Returns the exit code and the progress as
    (arrival time, simulated time) pairs, the moment of the signal as (time, None)."""
    import re
    import subprocess
    import threading
    import time

    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    lines = []

    def read():
        sent = False
        for line in proc.stderr:
            m = re.match(r"ffrsim: t = ([0-9.e+-]+) s", line)
            if not m:
                continue
            lines.append((time.monotonic(), float(m.group(1))))
            if not sent and float(m.group(1)) >= fraction * end_time:
                lines.append((time.monotonic(), None))
                proc.send_signal(sig)
                sent = True

    reader = threading.Thread(target=read)
    reader.start()
    rc = proc.wait()
    reader.join()
    return rc, lines


def slow_impact_scene(source, out, flush_interval, progress_interval):
    """The Sect. 5 impact (impact2d_h3 on sphere2d_h3 in OUT) as a ~10 s run: steps limited
    to 6 ns, the result flushed by wall time only (every `flush_interval` s; flush_rows too
    large to matter), progress lines every `progress_interval` s. Returns the scene's path."""
    import os
    with open(os.path.join(source, "configs", "scenes", "impact2d_h3.yaml")) as f:
        text = f.read()
    for old, new in (("  rtol: 1.0e-6", "  rtol: 1.0e-6\n  max_step: 6.0e-9"),
                     ("  flush_rows: 100", f"  flush_rows: 1000000\n  flush_interval: {flush_interval}\n"
                      f"  progress_interval: {progress_interval}")):
        assert old in text, old
        text = text.replace(old, new)
    scene = os.path.join(out, "long.yaml")
    with open(scene, "w") as f:
        f.write(text)
    return scene
