#!/usr/bin/env bash
# farm.slurm_cluster: `glint farm slurm` on a one-node Slurm cluster of its own, on loopback.
#   usage: slurm_cluster.sh GLINT PROJECT WORK_DIR
# Starts munged (its own key and socket), slurmctld -D and slurmd -D as root from a temporary
# folder (stopped by their PIDs at the end, also on failure), then:
#  1. a 4-part farm render (in a folder named with a space, quotes and %j%a: the logs must be
#     at the literal path); its merge must match a single render of the same samples
#     (mean absolute relative error of glint render's --log at most 1e-5: float rounding, see
#     tests/gl/render_parts_test.cpp);
#  2. a second run with one part cancelled (scancel): `glint merge` must refuse the set and
#     name the missing samples, `glint farm status` must list the part as missing, and
#     `glint farm slurm --resume` must complete it to the same file as the first run.
# Exit 77 (ctest: skipped) only where Slurm or munge is not installed.
set -euo pipefail
GLINT=$(realpath "$1")
PROJECT=$(realpath "$2")
WORK=$3
SPP=16
PARTS=4
WIDTH=24

for tool in munged mungekey slurmctld slurmd sbatch squeue scancel sinfo; do
  if ! command -v "$tool" >/dev/null 2>&1 && [ ! -x "/usr/sbin/$tool" ]; then
    echo "SKIP: $tool is not installed (scripts/setup.sh installs slurmctld, slurmd, slurm-client and munge)"
    exit 77
  fi
done
export PATH="$PATH:/usr/sbin"
if [ "$(id -u)" -ne 0 ]; then
  echo "FAIL: the test cluster runs its daemons as root (SlurmUser=root); run the test as root"
  exit 1
fi

rm -rf "$WORK"
mkdir -p "$WORK"
WORK=$(realpath "$WORK")
C="$WORK/cluster"
mkdir -p "$C/state" "$C/spool" "$C/munge"
chmod 700 "$C/munge"
pids=()
cleanup() {
  local status=$?
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  if [ $status -ne 0 ]; then
    echo "--- logs (the test failed) ---"
    for log in "$C"/*.log "$WORK"/run*/out.farm/logs/*.log; do
      [ -f "$log" ] && { echo "== $log"; tail -n 20 "$log"; }
    done
  fi
  exit $status
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; exit 1; }

free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }

# munge: its own key, socket, pid and seed files.
mungekey --create --keyfile="$C/munge/munge.key" >/dev/null
chmod 600 "$C/munge/munge.key"
munged --foreground --force --socket="$C/munge/munge.sock" --key-file="$C/munge/munge.key" \
  --pid-file="$C/munge/munged.pid" --seed-file="$C/munge/munged.seed" \
  --log-file="$C/munged.log" >"$C/munged.out" 2>&1 &
pids+=($!)

host=$(hostname -s)
cat > "$C/slurm.conf" <<CONF
ClusterName=glinttest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$C/munge/munge.sock
StateSaveLocation=$C/state
SlurmdSpoolDir=$C/spool
SlurmctldPidFile=$C/slurmctld.pid
SlurmdPidFile=$C/slurmd.pid
SlurmctldLogFile=$C/slurmctld.log
SlurmdLogFile=$C/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
MinJobAge=1
# One CPU: the parts run one after another, so a part can be cancelled before it starts.
NodeName=glintnode NodeAddr=127.0.0.1 NodeHostname=$host CPUs=1 State=UNKNOWN
PartitionName=glint Nodes=glintnode Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$C/slurm.conf"
for i in $(seq 50); do [ -S "$C/munge/munge.sock" ] && break; sleep 0.1; done
[ -S "$C/munge/munge.sock" ] || fail "munged did not start"
slurmctld -D -i -f "$SLURM_CONF" >"$C/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N glintnode -f "$SLURM_CONF" >"$C/slurmd.out" 2>&1 &
pids+=($!)
for i in $(seq 120); do
  state=$(sinfo -h -n glintnode -o %t 2>/dev/null || true)
  [ "$state" = "idle" ] && break
  sleep 0.5
done
[ "$state" = "idle" ] || fail "the node did not come up (sinfo: '$state')"
echo "cluster up: slurmctld, slurmd and munged (PIDs ${pids[*]})"

export XDG_CACHE_HOME="$WORK/cache"  # the back-end choice, timed once by the first render
export LP_NUM_THREADS=1

# Waits until Slurm has none of this cluster's jobs left but those that can never run.
wait_for_jobs() {
  for i in $(seq 600); do
    local left
    left=$(squeue -h -o '%T %r' | grep -v DependencyNeverSatisfied || true)
    [ -z "$left" ] && return 0
    sleep 0.5
  done
  squeue
  fail "jobs still queued after 300 s"
}

# A single render of all the samples, the reference for the merge.
"$GLINT" render "$PROJECT" --spp $SPP --width $WIDTH -o "$WORK/single.exr"

# 1. A farm render in four parts, in a folder whose name has a space, quotes and Slurm's
# filename patterns: the logs must land at the literal path.
RUN1="$WORK/run 1 'q\"%j%a"
mkdir -p "$RUN1"
"$GLINT" farm slurm "$PROJECT" --spp $SPP --parts $PARTS --width $WIDTH -o "$RUN1/out.exr"
wait_for_jobs
[ -f "$RUN1/out.exr" ] || fail "the merge job wrote no run1/out.exr"
for log in part-0 part-3 merge; do
  [ -f "$RUN1/out.farm/logs/$log.log" ] || fail "no log $RUN1/out.farm/logs/$log.log: $(ls "$RUN1/out.farm/logs")"
done
"$GLINT" farm status -o "$RUN1/out.exr" || fail "glint farm status: not every part done"
# The single render measured against the merge: its last --log row (16 spp) is the same
# samples, so the error is float rounding only.
"$GLINT" render "$PROJECT" --spp $SPP --width $WIDTH -o "$WORK/single-again.exr" \
  --reference "$RUN1/out.exr" --log "$WORK/single-vs-merge.csv"
last=$(tail -n 1 "$WORK/single-vs-merge.csv")
echo "single render against the merge (spp,seconds,gpu_seconds,relmse,relmse_trimmed,mape,mean_bias,nonfinite): $last"
awk -F, -v spp=$SPP '$1 != spp || $6 > 1e-5 { exit 1 }' <<<"$last" ||
  fail "the merge differs from the single render by more than float rounding: $last"

# 2. The same render with part 2 cancelled before it ran.
mkdir -p "$WORK/run2"
"$GLINT" farm slurm "$PROJECT" --spp $SPP --parts $PARTS --width $WIDTH -o "$WORK/run2/out.exr" 2>"$WORK/run2/submit.txt"
cat "$WORK/run2/submit.txt"
job=$(sed -n 's/.*(job \([0-9]*\), array.*/\1/p' "$WORK/run2/submit.txt")
[ -n "$job" ] || fail "no job id in glint farm's output"
scancel "${job}_2"
wait_for_jobs
[ ! -e "$WORK/run2/out.farm/parts/part-0002.exr" ] || fail "part 2 ran before it could be cancelled"
[ ! -e "$WORK/run2/out.exr" ] || fail "the merge ran although a part was cancelled"
set +e
"$GLINT" merge --spp $SPP "$WORK"/run2/out.farm/parts/part-*.exr -o "$WORK/run2/incomplete.exr" >"$WORK/run2/merge.txt" 2>&1
rc=$?
set -e
cat "$WORK/run2/merge.txt"
[ $rc -eq 1 ] || fail "glint merge of an incomplete set exited $rc, not 1"
grep -q "samples 8:12 are missing" "$WORK/run2/merge.txt" || fail "glint merge did not name the missing samples 8:12"
[ ! -e "$WORK/run2/incomplete.exr" ] || fail "glint merge wrote a file for an incomplete set"
set +e
"$GLINT" farm status -o "$WORK/run2/out.exr" >"$WORK/run2/status.txt"
rc=$?
set -e
cat "$WORK/run2/status.txt"
[ $rc -eq 1 ] || fail "glint farm status exited $rc with a part missing, not 1"
grep -q "^part 2  samples 8:12 *missing" "$WORK/run2/status.txt" || fail "status does not list part 2 as missing"
"$GLINT" farm slurm -o "$WORK/run2/out.exr" --resume 2>"$WORK/run2/resume.txt"
cat "$WORK/run2/resume.txt"
grep -q "submitted 1 part (job [0-9]*, array 2)" "$WORK/run2/resume.txt" || fail "--resume did not resubmit exactly part 2"
wait_for_jobs
[ -f "$WORK/run2/out.exr" ] || fail "the resumed farm wrote no run2/out.exr"
cmp "$RUN1/out.exr" "$WORK/run2/out.exr" || fail "the resumed render differs from the uninterrupted one"
echo "PASS: the 4-part farm render matches the single render (mape $(cut -d, -f6 <<<"$last")); the cancelled part: refused by merge, completed by --resume to the same file"
