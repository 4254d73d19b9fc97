"""Same input, same bits across two builds: runs igaprep and ffrsim of an old build (e.g. the
commit before a refactor) and of a new one on the paper's examples and compares every SID
and result file bit for bit (same_bits.py: every dataset and attribute, except times, the
git revision and the files' paths), and the XDMF files beside the results as text.

usage: compare_builds.py OLD_BIN NEW_BIN SOURCE_DIR OUT_DIR [--paper] [--reuse-old]
                         [--allow ITEM]...

OLD_BIN, NEW_BIN: folders holding igaprep and ffrsim (e.g. a worktree's build/bin).
--paper adds the paper-scale 3D model sphere3d_h3 and its impact (about 1 min each build)
and the flexible double pendulums of Sect. 7 (about 40 s each build).
--reuse-old keeps the old build's files from an earlier invocation into the same OUT_DIR.
--allow ITEM: an item that may differ (a path as the differences name it, e.g.
"/@format_version" for a new result format version), left out of the comparison and
named in the output.

Exit code 0 when every pair is equal. Build an old revision beside the checkout with
  git worktree add /tmp/old REV && cmake -S /tmp/old -B /tmp/old/build && cmake --build /tmp/old/build
"""
import argparse
import os
import re
import subprocess
import sys

from result_checks import Checks
from same_bits import differences

QUICK_BODIES = ["sphere2d_h3", "sphere2d_h4", "sphere2d_h5", "sphere2d_h6", "sphere2d_g3",
                "sphere2d_g4", "sphere2d_g5", "sphere2d_g6", "sphere3d_coarse", "rod",
                "rod_modal", "pendulum_sphere"]
QUICK_SCENES = ["impact2d_h3", "impact2d_h4", "impact2d_h5", "impact2d_h6", "impact2d_g3",
                "impact2d_g4", "impact2d_g5", "impact2d_g6", "impact3d_coarse",
                "pendulum_flexible", "pendulums_rigid"]
PAPER_BODIES = ["sphere3d_h3"]
PAPER_SCENES = ["impact3d_h3", "pendulums"]

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("old_bin")
parser.add_argument("new_bin")
parser.add_argument("source")
parser.add_argument("out")
parser.add_argument("--paper", action="store_true")
parser.add_argument("--reuse-old", action="store_true")
parser.add_argument("--allow", action="append", default=[])
args = parser.parse_args()
check = Checks()
bodies = QUICK_BODIES + (PAPER_BODIES if args.paper else [])
scenes = QUICK_SCENES + (PAPER_SCENES if args.paper else [])


def produce(build, bin_dir):
    """The SIDs and results of one build in OUT/BUILD; an existing file is kept with
    --reuse-old for the old build."""
    folder = os.path.join(args.out, build)
    os.makedirs(folder, exist_ok=True)
    keep = args.reuse_old and build == "old"
    for stem in bodies:
        sid = os.path.join(folder, stem + ".sid.h5")
        if keep and os.path.exists(sid):
            continue
        body = os.path.join(args.source, "configs", "bodies", stem + ".yaml")
        check.run([os.path.join(bin_dir, "igaprep"), "-q", body, "-o", sid])
    for stem in scenes:
        result = os.path.join(folder, stem + ".h5")
        if keep and os.path.exists(result):
            continue
        scene = os.path.join(args.source, "configs", "scenes", stem + ".yaml")
        check.run([os.path.join(bin_dir, "ffrsim"), "-q", scene, "--sid-path", folder, "-o",
                   result])
    return folder


old = produce("old", args.old_bin)
new = produce("new", args.new_bin)
for name in [b + ".sid.h5" for b in bodies] + [s + ".h5" for s in scenes]:
    n, differ = differences(os.path.join(old, name), os.path.join(new, name), builds=True,
                            ignore=args.allow)
    check(not differ and n > 0, f"{name}: {n} datasets and attributes equal bit for bit"
          + (f" (allowed to differ: {', '.join(args.allow)})" if args.allow else "")
          + (f"; differ: {', '.join(differ[:8])}" if differ else ""))
    xdmf = [os.path.join(d, name[:-3] + ".xdmf") for d in (old, new)]
    if any(os.path.exists(x) for x in xdmf):
        texts = []
        for x in xdmf:
            with open(x) as f:
                texts.append(re.sub(r"(old|new)/", "", f.read()))
        check(texts[0] == texts[1], f"{os.path.basename(xdmf[0])}: the same text")
check.exit()
