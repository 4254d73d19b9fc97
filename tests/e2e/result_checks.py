"""Shared pieces of the end-to-end checks: a check list that prints ok / FAIL per item and
the exit code, and the result file's status as text (h5py may return bytes)."""
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

    def exit(self):
        sys.exit(1 if self.failures else 0)
