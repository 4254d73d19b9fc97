#!/usr/bin/python3
"""Parameter studies of ffriga: the commands behind the Snakemake workflow (Snakefile here).

  study.py check STUDY.yaml                     check the study file (exit 2 if bad) and
                                                list its runs and the SIDs they need
  study.py sid STUDY.yaml STEM [options]        build one cached SID (workflow rule 'sid')
  study.py run STUDY.yaml RUN [options]         run one scene (workflow rule 'run')
  study.py collect STUDY.yaml [options]         the table and pictures (rule 'collect')

options: --bin FOLDER (igaprep and ffrsim, default build/bin), --out FOLDER (default
build/studies: SIDs in OUT/sids, runs and tables in OUT/<study>), --threads N.

Study files: schemas/study.schema.json; the SID and run records: study_jobs.py; the
table: study_table.py. Exit codes: 0 success, 2 bad study file or usage, 1 failure.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from study_file import ROOT, Study, StudyError, value_text  # noqa: E402
import study_jobs  # noqa: E402
import study_table  # noqa: E402


def paths(out, study):
    return os.path.join(out, "sids"), os.path.join(out, study.name)


def find(items, key, what, study):
    if key not in items:
        raise StudyError(f"{study.file}: no {what} '{key}' in this study (it has "
                         f"{', '.join(sorted(items)) or 'none'}): the study file changed?")
    return items[key]


def cmd_check(a, study, runs):
    sids = {s.stem: s for r in runs for s in r.sids.values()}
    print(f"{study.file}: study '{study.name}', {len(runs)} runs, {len(sids)} SIDs")
    for s in sids.values():
        extra = f" with {' '.join(s.overrides)}" if s.overrides else ""
        print(f"  SID {s.stem}.sid.h5 from {os.path.relpath(s.body_file)}{extra}")
    for r in runs:
        values = ", ".join(f"{k} = {value_text(v)}" for k, v in r.values.items())
        print(f"  run {r.id}: {values}")
    return 0


def cmd_sid(a, study, runs):
    sids = {s.stem: s for r in runs for s in r.sids.values()}
    sid = find(sids, a.item, "SID", study)
    record = study_jobs.build_sid(a.bin, sid, paths(a.out, study)[0], a.threads,
                                  a.versions["igaprep"])
    print(f"SID {sid.stem}: {record['status']}"
          + (f" ({record['message']})" if record["status"] != "built" else
             f" in {record['wall_s']:.1f} s"))
    return 0


def cmd_run(a, study, runs):
    run = find({r.id: r for r in runs}, a.item, "run", study)
    sid_dir, study_dir = paths(a.out, study)
    s = study_jobs.run_scene(a.bin, study, run, sid_dir, os.path.join(study_dir, "runs", run.id),
                             a.threads)
    print(f"run {run.id} ({', '.join(f'{k} = {v}' for k, v in s['values'].items())}): "
          f"{study_table.status_text(s)}")
    return 0


def cmd_collect(a, study, runs):
    _, study_dir = paths(a.out, study)
    summaries = []
    for r in runs:
        path = os.path.join(study_dir, "runs", r.id, "summary.json")
        if not os.path.exists(path):
            raise RuntimeError(f"run {r.id} has no summary ({path}): run the workflow "
                               f"(benchmarks/studies/Snakefile), not collect alone")
        with open(path, encoding="utf-8") as f:
            summaries.append(json.load(f))
    table = study_table.write_tables(study, summaries, study_dir)
    for p in study_table.swept(study):
        study_table.plot(study, table, p, os.path.join(study_dir, f"{study.name}_{p.name}.png"))
    failed = [r for r in table if r["status"] != "completed"]
    print(f"study {study.name}: {len(table) - len(failed)} of {len(table)} runs completed; "
          f"table {os.path.join(study_dir, study.name)}.csv")
    for r in failed:
        values = ", ".join(f"{p.name} = {r[p.name]}" for p in study.parameters)
        print(f"  run {r['run']} ({values}): {r['status']}")
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(prog="study.py", description=__doc__.split("\n")[0])
    ap.add_argument("command", choices=["check", "sid", "run", "collect"])
    ap.add_argument("study")
    ap.add_argument("item", nargs="?", help="the SID stem (sid) or run id (run)")
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "studies"))
    ap.add_argument("--threads", type=int, default=1)
    a = ap.parse_args(argv)
    if a.command in ("sid", "run") and not a.item:
        ap.error(f"{a.command} needs the {'SID stem' if a.command == 'sid' else 'run id'}")
    try:
        a.versions = study_jobs.program_versions(a.bin)
        study = Study(a.study)
        runs = study.runs(a.versions)
        return {"check": cmd_check, "sid": cmd_sid, "run": cmd_run,
                "collect": cmd_collect}[a.command](a, study, runs)
    except StudyError as e:
        print(f"study: error: {e}", file=sys.stderr)
        return 2
    except RuntimeError as e:
        print(f"study: error: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
