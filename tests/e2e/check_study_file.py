"""Study files expanded into runs (benchmarks/studies/study_file.py), without running them:

  * ranges: linear ends and steps exact, log ranges hit the decades exactly, integer ranges;
  * product order (first parameter slowest) and zip;
  * {name} fields in the scene and body paths;
  * value_text reads back as the same float (the --set text of every value) for 10,000
    random doubles over 600 decades;
  * hashes: the same body input gives the same SID on another invocation; a body-key
    override or another igaprep version gives another SID, a scene-key override does not;
    every run has its own id, and another ffrsim version changes every id.

usage: check_study_file.py SOURCE_DIR OUT_DIR
"""
import os
import random
import sys

from result_checks import Checks

source, out = sys.argv[1:3]
os.makedirs(out, exist_ok=True)
sys.path.insert(0, os.path.join(source, "benchmarks", "studies"))
from study_file import Study, value_text  # noqa: E402

check = Checks()
configs = os.path.join(source, "configs")
V = {"igaprep": "igaprep 0.1.0 (git a)", "ffrsim": "ffrsim 0.1.0 (git a)"}


def study(name, text):
    path = os.path.join(out, f"{name}.yaml")
    with open(path, "w") as f:
        f.write(text)
    return Study(path)


head = (f"study: s\nscene: {configs}/scenes/impact2d_{{model}}.yaml\nbodies:\n"
        f"  sphere2d_{{model}}.sid.h5: {configs}/bodies/sphere2d_{{model}}.yaml\n")
s = study("ranges", head + """parameters:
  - {name: model, values: [h3, g3]}
  - {name: a, range: {start: 0.0, stop: 1.0, num: 5}}
  - {name: cp, scene_key: contacts.0.penalty_factor,
     range: {start: 1.0e15, stop: 1.0e18, num: 4, spacing: log}}
  - {name: n, range: {start: 1, stop: 10, num: 4, integer: true}}
""")
p = {q.name: q.values for q in s.parameters}
check(p["a"] == [0.0, 0.25, 0.5, 0.75, 1.0], f"linear range {p['a']}")
check(p["cp"] == [1e15, 1e16, 1e17, 1e18], f"log range {p['cp']}")
check(p["n"] == [1, 4, 7, 10] and all(isinstance(x, int) for x in p["n"]),
      f"integer range {p['n']}")
combos = s.combinations()
check(len(combos) == 2 * 5 * 4 * 4 and combos[0] == {"model": "h3", "a": 0.0, "cp": 1e15, "n": 1}
      and combos[1]["n"] == 4 and combos[-1] == {"model": "g3", "a": 1.0, "cp": 1e18, "n": 10},
      "product: every combination, the first parameter slowest")
z = study("zip", head + """combine: zip
parameters:
  - {name: model, values: [h3, g3]}
  - {name: cp, scene_key: contacts.0.penalty_factor, values: [1.0e17, 3.0e17]}
""")
check(z.combinations() == [{"model": "h3", "cp": 1e17}, {"model": "g3", "cp": 3e17}], "zip")
runs = z.runs(V)
check(runs[0].scene.endswith("impact2d_h3.yaml") and runs[1].scene.endswith("impact2d_g3.yaml")
      and list(runs[1].sids) == ["sphere2d_g3.sid.h5"]
      and runs[1].sids["sphere2d_g3.sid.h5"].body_file.endswith("sphere2d_g3.yaml"),
      "{model} in the scene, the SID name and the body file")
check(runs[1].scene_overrides == ["contacts.0.penalty_factor=3e+17"]
      and runs[1].sid_bodies == [(0, "sphere2d_g3.sid.h5"), (1, "sphere2d_g3.sid.h5")],
      f"scene overrides {runs[1].scene_overrides}, SID bodies {runs[1].sid_bodies}")

rng = random.Random(14)
xs = [rng.uniform(1, 10) * 10.0 ** rng.randint(-300, 300) * rng.choice((1, -1))
      for _ in range(10000)]
check(all(float(value_text(x)) == x for x in xs), "value_text reads back bit for bit")
check([value_text(x) for x in (1e15, 3e17, 0.3, 2.11e11, 100.0, 7850)] ==
      ["1e+15", "3e+17", "0.3", "2.11e+11", "100.0", "7850"], "value_text is short")

body = f"""study: h
scene: {configs}/scenes/impact2d_h3.yaml
bodies:
  sphere2d_h3.sid.h5: {configs}/bodies/sphere2d_h3.yaml
parameters:
  - {{name: cp, scene_key: contacts.0.penalty_factor, values: [1.0e17, 3.0e17]}}
  - {{name: rho, body_key: material.density, values: [7850, 3925]}}
"""
r1, r2 = study("hash1", body).runs(V), study("hash2", body).runs(V)
sid = [list(r.sids.values())[0].hash for r in r1]
check([list(r.sids.values())[0].hash for r in r2] == sid, "the same body input, the same SID")
check(sid[0] == sid[2] and sid[1] == sid[3] and sid[0] != sid[1],
      "a body-key override changes the SID, a scene-key override does not")
check(len({r.id for r in r1}) == 4 and [r.id for r in r1] == [r.id for r in r2],
      "every run its own id, the same on another invocation")
other = study("hash3", body).runs({"igaprep": "igaprep 0.1.0 (git b)", "ffrsim": V["ffrsim"]})
check(all(list(a.sids.values())[0].hash != list(b.sids.values())[0].hash and a.id != b.id
          for a, b in zip(r1, other)), "another igaprep: other SIDs, so other runs")
other = study("hash4", body).runs({"igaprep": V["igaprep"], "ffrsim": "ffrsim 0.1.0 (git b)"})
check(all(list(a.sids.values())[0].hash == list(b.sids.values())[0].hash and a.id != b.id
          for a, b in zip(r1, other)), "another ffrsim: the same SIDs, other runs")
check.exit()
