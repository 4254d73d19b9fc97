#!/usr/bin/env bash
# The study workflow through a real Slurm cluster: installs Debian's slurm-wlm and munge
# (as root, if missing), starts a one-node cluster on this machine (munged, slurmctld and
# slurmd on 127.0.0.1, a private configuration and private ports: an installed cluster's
# /etc/slurm and /etc/munge are not touched), runs a study once locally (snakemake -j2) and
# once through Slurm (the profile benchmarks/studies/slurm: every SID and run an sbatch
# job), and checks that
#   * the two tables are identical, byte for byte (the programs give the same bits for the
#     same input; timings are in a separate table),
#   * every run of the Slurm invocation ran inside a Slurm job (its summary names the job)
#     and none of the local one did,
#   * a second Slurm invocation has nothing to do.
# Then stops the cluster. Takes about 2 minutes after the installation.
#
#   bash benchmarks/studies/slurm_check.sh [STUDY.yaml]   (default benchmarks/studies/penalty_h3.yaml)
#
# Needs the programs built (bash .ci/build). Exit code 0 if all holds, 1 otherwise.
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
study=$(realpath "${1:-benchmarks/studies/penalty_h3.yaml}")
work=$root/build/slurm_check
snakefile=$root/benchmarks/studies/Snakefile
name=$(/usr/bin/python3 -c "import sys; sys.path.insert(0, 'benchmarks/studies')
from study_file import Study; print(Study('$study').name)")

# --- install -------------------------------------------------------------------------
need=()
for p in slurm-wlm munge snakemake; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  echo "slurm_check: installing ${need[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${need[@]}" > "$root/build/slurm_install.log"
fi
# Debian starts the packages' own daemons on installation; this check runs its own.
for unit in slurmctld slurmd munge; do
  if command -v systemctl > /dev/null && systemctl is-active -q "$unit" 2> /dev/null; then
    echo "slurm_check: note: the system's $unit is running; this check uses its own ports"
  fi
done

# --- a one-node cluster ----------------------------------------------------------------
rm -rf "$work"
mkdir -p "$work"/{munge,state,spool,log}
chmod 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
node=$(hostname -s)
cpus=$(nproc)
mem=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 - 1024 ))
cat > "$work/slurm.conf" <<EOF
ClusterName=ffriga-check
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
MinJobAge=3600
SlurmdTimeout=60
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=check Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$work/slurm.conf
export USER=${USER:-$(id -un)}   # Snakemake's Slurm executor reads it

pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2> /dev/null || true; done
  wait 2> /dev/null || true
}
trap cleanup EXIT
/usr/sbin/munged --foreground --force --key-file="$work/munge/munge.key" \
  --socket="$work/munge/munge.socket" --pid-file="$work/munge/munged.pid" \
  --seed-file="$work/munge/seed" --log-file="$work/log/munged.log" \
  > "$work/log/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 50); do [ -S "$work/munge/munge.socket" ] && break; sleep 0.1; done
/usr/sbin/slurmctld -D -f "$SLURM_CONF" > "$work/log/slurmctld.out" 2>&1 &
pids+=($!)
sleep 1
/usr/sbin/slurmd -D -f "$SLURM_CONF" -N "$node" > "$work/log/slurmd.out" 2>&1 &
pids+=($!)
state=
for _ in $(seq 60); do
  state=$(sinfo -h -N -o %t 2> /dev/null | head -n1 || true)
  [ "$state" = idle ] && break
  sleep 1
done
if [ "$state" != idle ]; then
  echo "slurm_check: the one-node cluster did not come up (node state '$state')" >&2
  tail -n 20 "$work"/log/*.log "$work"/log/*.out >&2 || true
  exit 1
fi
echo "slurm_check: cluster up: $(sinfo -h -o '%P %D node(s) %c cores %m MB %t')"

# --- the study, locally and through Slurm -----------------------------------------------
run() {  # run OUT [snakemake options]: the study into OUT, the log in OUT.log
  local out=$1 t0
  shift
  t0=$(date +%s.%N)
  snakemake -s "$snakefile" --config study="$study" out="$out" "$@" > "$out.log" 2>&1 || {
    tail -n 40 "$out.log" >&2
    echo "slurm_check: snakemake $* failed (log $out.log)" >&2
    exit 1
  }
  /usr/bin/python3 -c "print(f'{$(date +%s.%N) - $t0:.1f} s of wall time')" > "$out.time"
}
run "$work/local" -j2
echo "slurm_check: local run: $(cat "$work/local.time")"
# Status every second, not Snakemake's 30 s for Slurm: the jobs take seconds here.
slurm=(--profile "$root/benchmarks/studies/slurm" --default-resources slurm_partition=check
       --max-status-checks-per-second 1)
run "$work/slurm" "${slurm[@]}"
echo "slurm_check: Slurm run: $(cat "$work/slurm.time")"
run "$work/slurm_again" "${slurm[@]}" --config study="$study" out="$work/slurm"

/usr/bin/python3 - "$work" "$name" <<'EOF'
import glob, json, os, sys
work, name = sys.argv[1:3]
failures = []
def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    ok or failures.append(what)
local = open(f"{work}/local/{name}/{name}.csv", "rb").read()
slurm = open(f"{work}/slurm/{name}/{name}.csv", "rb").read()
rows = local.decode().strip().splitlines()[1:]
check(local == slurm, f"the tables are identical ({len(rows)} runs, {len(local)} bytes)")
for where, want in (("local", False), ("slurm", True)):
    jobs = [json.load(open(p)).get("slurm_job_id")
            for p in glob.glob(f"{work}/{where}/{name}/runs/*/summary.json")]
    check(len(jobs) == len(rows) and all((j is not None) == want for j in jobs),
          f"{where}: {len(jobs)} runs, " + (f"in Slurm jobs {sorted(set(jobs))}" if want
                                             else "none in a Slurm job"))
sids = [json.load(open(p)).get("slurm_job_id") for p in glob.glob(f"{work}/slurm/sids/*.json")]
check(sids and all(j is not None for j in sids), f"SIDs built in Slurm jobs {sids}")
# What each job asked Slurm for: the rules' resources (the SID job the Snakefile's default,
# a run 500 MB + 4 x its SID's size), one core, 60 min.
import subprocess
jobs = subprocess.run(["scontrol", "-o", "show", "job"], capture_output=True, text=True).stdout
sid_bytes = sum(json.load(open(p))["bytes"] for p in glob.glob(f"{work}/slurm/sids/*.json"))
want = {"sid": "4000M", "simulate": f"{500 + 4 * sid_bytes // 1000000}M"}
asked = []
for line in jobs.splitlines():
    f = dict(kv.split("=", 1) for kv in line.split() if "=" in kv)
    rule = next((r for r in want if f"_{r}_" in f.get("JobName", "")), None)
    if rule:
        asked.append((rule, f.get("MinMemoryNode"), f.get("TimeLimit"), f.get("NumCPUs")))
check(len(asked) == len(rows) + len(sids) and all(
          m == want[r] and t == "01:00:00" and c == "1" for r, m, t, c in asked),
      f"the jobs asked for their rules' resources: {sorted(set(asked))}")
again = open(f"{work}/slurm_again.log").read()
check("Nothing to be done" in again, "a second Slurm invocation has nothing to do")
print(local.decode())
sys.exit(1 if failures else 0)
EOF
echo "slurm_check: ok"
