"""The ParaView output of a real run opens in real ParaView (issue 12): igaprep and ffrsim run
the flagship scene (impact2d_h3, which asks for visualisation frames), then Debian's
pvpython, on a virtual X display (Xvfb, started here: xvfb-run's wait for the server
raced under load in CI, "bad X server connection"), opens RESULT.xdmf, goes to the frame nearest the force
peak, colours the bodies by von Mises stress and saves a PNG (tests/e2e/render_frame.py).
Checked: ParaView read every frame time, point and cell; its bounds and von Mises range are
the result file's; the frames put each body where /bodies says (rigid motion plus the
magnified elastic displacement); the PNG is not blank. Then the same scene with the
axisymmetric bodies revolved (outputs.visualisation.revolve): ParaView reads hexahedra
filling the spheres' full extent in x and z.

usage: check_paraview.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import contextlib
import json
import os
import shutil
import signal
import subprocess
import sys
import time

import h5py
import matplotlib.image
import numpy as np

from result_checks import Checks, rotation

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
check = Checks()


for tool in ("pvpython", "Xvfb"):
    if shutil.which(tool) is None:
        check(False, f"{tool} not found (apt-get install paraview python3-paraview xvfb: "
                     f".ci/install-deps)")
        check.exit()


@contextlib.contextmanager
def virtual_display():
    """An Xvfb server on a free display number; yields its DISPLAY once it accepts
    connections and stops it afterwards. Readiness by the X server's own protocol (Xserver(1):
    started with SIGUSR1 ignored, it sends SIGUSR1 to its parent when it is ready), not by
    its socket appearing: under load a client that came between the two was refused."""
    number = next(n for n in range(99, 400)
                  if not os.path.exists(f"/tmp/.X{n}-lock")
                  and not os.path.exists(f"/tmp/.X11-unix/X{n}"))
    ready = []
    previous = signal.signal(signal.SIGUSR1, lambda *_: ready.append(True))

    def ignore_usr1():
        signal.signal(signal.SIGUSR1, signal.SIG_IGN)

    # -noreset: no reset (and no second SIGUSR1) when the last client leaves.
    server = subprocess.Popen(["Xvfb", f":{number}", "-screen", "0", "1024x768x24", "-nolisten",
                               "tcp", "-noreset"], stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, preexec_fn=ignore_usr1)
    try:
        for _ in range(600):  # 30 s
            if ready or server.poll() is not None:
                break
            time.sleep(0.05)
        if not ready:
            check(False, f"Xvfb :{number} did not get ready (exit {server.poll()})")
            check.exit()
        yield f":{number}"
    finally:
        server.terminate()
        server.wait()
        signal.signal(signal.SIGUSR1, previous)  # only now: no signal can come any more


def render(xdmf_file, t, png, info):
    """pvpython render_frame.py on a virtual display."""
    with virtual_display() as display:
        check.run(["pvpython", os.path.join(source, "tests", "e2e", "render_frame.py"), xdmf_file,
                   repr(t), png, info], env=dict(os.environ, DISPLAY=display))

sid = os.path.join(out, "sphere2d_h3.sid.h5")
result = os.path.join(out, "impact2d_h3.h5")
xdmf = os.path.join(out, "impact2d_h3.xdmf")
check.run([igaprep, "-q", os.path.join(source, "configs", "bodies", "sphere2d_h3.yaml"), "-o",
           sid])
for stale in (result, xdmf):
    if os.path.exists(stale):
        os.remove(stale)
check.run([ffrsim, "-q", os.path.join(source, "configs", "scenes", "impact2d_h3.yaml"),
           "--sid-path", out, "-o", result])
check(os.path.exists(xdmf), f"ffrsim wrote {os.path.basename(xdmf)} beside the result")

with h5py.File(result, "r") as f, h5py.File(sid, "r") as s:
    frames = f["visualisation/time"][:]
    k = int(np.argmin(np.abs(frames - f.attrs["max_contact_force_time_s"])))
    t = float(frames[k])
    m = f["visualisation"].attrs["magnification"]
    row = int(np.argmin(np.abs(f["time"][:] - t)))
    check(f["time"][row] == t, f"frame {k} at t = {t:.3e} s (nearest the force peak) is output "
                               f"row {row}")
    points, cells, vm, where = 0, 0, [], []
    x0 = s["visualisation/points"][:]
    for b in ("lower", "upper"):
        g = f["visualisation"][b]
        P = g["points"][k].astype(float)
        U = g["displacement"][k].astype(float)
        points += P.shape[0]
        cells += g["cells"].shape[0]
        vm.append(g["von_mises"][k])
        # Where /bodies says: r + R (x0 + m u), R of the unit quaternion orientation.
        r = f["bodies"][b]["position"][row]
        R = rotation(f["bodies"][b]["orientation"][row])
        X0 = np.column_stack([x0, np.zeros(len(x0))])
        expected = r + X0 @ R.T + m * U
        # Single precision frames: 6e-8 relative of 2 cm.
        err = np.abs(P - expected).max()
        check(err < 5e-9, f"{b}: frame points = position + R x0 + {m:g} u to {err:.1e} m")
        where.append(P)
    allP = np.vstack(where)
    vm = np.concatenate(vm)

png, info_json = os.path.join(out, "peak.png"), os.path.join(out, "peak.json")
render(xdmf, t, png, info_json)
with open(info_json) as fi:
    info = json.load(fi)
check(len(info["times"]) == len(frames) and np.allclose(info["times"], frames, rtol=1e-12, atol=0),
      f"ParaView sees {len(info['times'])} frame times, the result has {len(frames)}")
check(info["points"] == points and info["cells"] == cells,
      f"ParaView read {info['points']} points and {info['cells']} cells (result: {points}, {cells})")
lo, hi = allP.min(axis=0), allP.max(axis=0)
bounds = np.array(info["bounds"]).reshape(3, 2)
check(np.allclose(bounds[:, 0], lo, atol=1e-9) and np.allclose(bounds[:, 1], hi, atol=1e-9),
      f"ParaView's bounds {np.round(bounds.ravel(), 6).tolist()} are the frame's")
check(np.isclose(info["von_mises_range"][0], vm.min(), rtol=1e-6)
      and np.isclose(info["von_mises_range"][1], vm.max(), rtol=1e-6),
      f"ParaView's von Mises range {info['von_mises_range'][0]:.4g} .. "
      f"{info['von_mises_range'][1]:.4g} Pa is the frame's")
image = matplotlib.image.imread(png)[:, :, :3]
background = np.all(image > 0.99, axis=2)
colours = len(np.unique((image[~background] * 255).astype(int).reshape(-1, 3), axis=0))
check(background.mean() < 0.95 and colours >= 10,
      f"{os.path.basename(png)}: {100 * (1 - background.mean()):.1f} % of the pixels drawn, "
      f"{colours} colours")
# The two bodies: drawn above and below the contact point (the middle row of the image).
rows = np.where(~background.all(axis=1))[0]
check(rows.size > 0 and rows.min() < image.shape[0] * 0.3 and rows.max() > image.shape[0] * 0.7,
      "both bodies are in the picture (above and below the contact)")

# Revolved: 16 segments, a frame every 50 us.
segments = 16
with open(os.path.join(source, "configs", "scenes", "impact2d_h3.yaml")) as fs:
    text = fs.read()
assert "interval: 2.0e-6" in text
text = text.replace("interval: 2.0e-6", f"interval: 5.0e-5\n    revolve: {segments}")
revolved_scene = os.path.join(out, "impact2d_h3_revolved.yaml")
with open(revolved_scene, "w") as fs:
    fs.write(text)
revolved = os.path.join(out, "impact2d_h3_revolved.h5")
check.run([ffrsim, "-q", revolved_scene, "--sid-path", out, "-o", revolved])
render(revolved[:-3] + ".xdmf", 5e-05, os.path.join(out, "revolved.png"),
       os.path.join(out, "revolved.json"))
with open(os.path.join(out, "revolved.json")) as fi:
    rinfo = json.load(fi)
rb = np.array(rinfo["bounds"]).reshape(3, 2)
r = 0.01
check(rinfo["points"] == segments * points and rinfo["cells"] == segments * cells,
      f"revolved: ParaView read {rinfo['cells']} cells = {segments} x {cells} quadrilaterals")
check(np.allclose(rb[0], [-r, r], rtol=1e-3) and np.allclose(rb[2], [-r, r], rtol=1e-3),
      f"revolved: x and z extents {np.round(rb[0], 5).tolist()}, {np.round(rb[2], 5).tolist()} "
      f"are the spheres' (r = {r} m; 0.1 % for the magnified deformation)")
check.exit()
