"""The table of a study: every run's parameters, status and collected figures, and a PNG of
the plotted figures against each swept parameter (schemas/study_outputs.md).

* `<study>.csv`: one row per run in the order of the study's combinations; columns `run`
  (its id), the parameters, `status` (`completed`, or `failed: PROGRAM exit N: MESSAGE`)
  and the collected figures (empty where a run failed or its result has no such figure).
  Numbers are written with repr(), every bit: the same study gives the same file on any
  machine and scheduler (the programs give the same bits for the same input).
* `<study>.json`: the same rows with the study's description and the parameters' units.
* `<study>_timings.csv`: what differs from run to run: the integration's wall time
  (result attribute wall_time_s), the ffrsim process's wall and CPU time and peak memory,
  and those of igaprep for the run's SIDs (built once, so shared by the runs that use them).
* `<study>_<parameter>.png` for every parameter with more than one value: each plotted
  figure against it, one line per combination of the other parameters, failed runs left out.
"""
import csv
import json
import math
import os

from study_file import value_text


def _cell(v):
    if v is None:
        return ""
    if isinstance(v, float):
        return repr(v)
    return str(v)


def status_text(summary):
    if summary["status"] == "completed":
        return "completed"
    return (f"failed: {summary.get('program', '?')} exit {summary.get('exit_code', '?')}: "
            f"{summary.get('message', '')}")


def rows(study, summaries):
    names = [p.name for p in study.parameters]
    out = []
    for s in summaries:
        figures = s.get("figures", {}) if s["status"] == "completed" else {}
        row = {"run": s["run"]}
        row.update({n: s["values"][n] for n in names})
        row["status"] = status_text(s)
        row.update({c: figures.get(c) for c in study.collect})
        out.append(row)
    return out


def _write_csv(path, header, table):
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        for r in table:
            w.writerow([_cell(r.get(h)) for h in header])
    os.replace(tmp, path)


def write_tables(study, summaries, out_dir):
    table = rows(study, summaries)
    names = [p.name for p in study.parameters]
    base = os.path.join(out_dir, study.name)
    _write_csv(base + ".csv", ["run"] + names + ["status"] + study.collect, table)
    timing_keys = ["wall_time_s", "process_wall_s", "process_cpu_s", "peak_rss_mib", "threads",
                   "igaprep_wall_s", "igaprep_cpu_s", "igaprep_peak_rss_mib"]
    _write_csv(base + "_timings.csv", ["run"] + names + timing_keys,
               [dict({"run": s["run"]}, **s["values"], **s.get("timings", {}))
                for s in summaries])
    doc = {"study": study.name, "description": study.description, "study_file": study.path,
           "parameters": [{"name": p.name, "unit": p.unit, "scene_key": p.scene_key,
                           "body_key": p.body_key,
                           "values": [value_text(v) for v in p.values]}
                          for p in study.parameters],
           "collect": study.collect, "rows": table,
           "failed": sum(1 for s in summaries if s["status"] != "completed")}
    tmp = f"{base}.json.tmp{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    os.replace(tmp, base + ".json")
    return table


def swept(study):
    """The parameters with more than one distinct value: one picture each."""
    return [p for p in study.parameters if len({value_text(v) for v in p.values}) > 1]


def _numeric(values):
    try:
        return [float(v) for v in values]
    except (TypeError, ValueError):
        return None


def plot(study, table, parameter, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    others = [p.name for p in study.parameters if p.name != parameter.name]
    groups = {}
    for r in table:
        groups.setdefault(tuple(r[o] for o in others), []).append(r)
    fig, axes = plt.subplots(len(study.plot), 1, figsize=(6.4, 3.2 * len(study.plot)),
                             squeeze=False)
    xs_all = [value_text(v) for v in parameter.values]
    numeric = _numeric(xs_all)
    log = (numeric is not None and min(numeric) > 0
           and max(numeric) / min(numeric) > 50)

    def position(x):  # a value's place on the axis: itself, or its index if not a number
        return float(x) if numeric is not None else xs_all.index(x)

    any_failed = any(r["status"] != "completed" for r in table)
    for ax, figure in zip(axes[:, 0], study.plot):
        for key, rs in groups.items():
            pts = sorted((position(r[parameter.name]), r[figure]) for r in rs
                         if r["status"] == "completed" and isinstance(r[figure], (int, float))
                         and math.isfinite(r[figure]))
            ax.plot([x for x, _ in pts], [y for _, y in pts], "o-",
                    label=", ".join(f"{o} = {k}" for o, k in zip(others, key)) or None)
            for r in rs:
                if r["status"] != "completed":
                    ax.axvline(position(r[parameter.name]), color="red", lw=0.8, ls=":")
        if log:
            ax.set_xscale("log")
        if numeric is None:
            ax.set_xticks(range(len(xs_all)))
            ax.set_xticklabels(xs_all)
        if figure.endswith("_vs_hertz"):
            ax.axhline(0.0, color="k", lw=0.8)
        ax.set_ylabel(f"{figure} (relative: 0.01 = 1 %)" if figure.endswith("_vs_hertz")
                      else figure)
        if others:  # one line per combination of the other parameters
            ax.legend(fontsize="small")
    unit = f" [{parameter.unit}]" if parameter.unit else ""
    axes[-1, 0].set_xlabel(f"{parameter.description}{unit}")
    axes[0, 0].set_title(f"{study.name}: against {parameter.name}"
                         + (" (red dotted: failed runs)" if any_failed else ""))
    fig.tight_layout()
    tmp = f"{path}.tmp{os.getpid()}.png"
    fig.savefig(tmp, dpi=110)
    plt.close(fig)
    os.replace(tmp, path)
