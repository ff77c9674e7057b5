#!/usr/bin/env bash
# tools/slurm-local.sh: it starts in a folder below one only its owner may enter (a clone in root's
# home folder, mode 700 on a fresh machine); a cluster that died (daemons killed, a job step
# orphaned) does not break the next start, and stop leaves no process behind. Run by ctest as root.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
LOCAL=$ROOT/tools/slurm-local.sh
PARENT=$(mktemp -d /tmp/streyes-slurm-local-XXXXXX)  # mode 700, as root's home folder
chmod 700 "$PARENT"
DIR=$PARENT/home/cluster
export SLURM_CONF=$DIR/slurm.conf
fail() { echo "FAIL: $*" >&2; exit 1; }
cleanup() { "$LOCAL" stop "$DIR" >/dev/null 2>&1 || true; rm -rf "$PARENT"; }
trap cleanup EXIT

alive() { [ -n "$1" ] && [ -d "/proc/$1" ] && ! grep -q '^[0-9]* ([^)]*) Z' "/proc/$1/stat" 2>/dev/null; }

"$LOCAL" start "$DIR" 2>"$PARENT/start.log" || { cat "$PARENT/start.log" >&2; fail "start failed below a mode-700 folder"; }
[ "$(sinfo -h -o %t)" = idle ] || fail "the node is not idle after start"
[ "$(stat -c %a "$PARENT")" = 700 ] || fail "start opened the private folder above the cluster to others"
first_ctld=$(cat "$DIR/slurmctld.pid")

# A job whose step outlives its cluster: a marker process that sleeps.
marker="streyes-slurm-local-test-$$"
printf '#!/bin/bash\nexec -a %s sleep 300\n' "$marker" >"$DIR/job.sh"
job=$(sbatch --parsable -o /dev/null "$DIR/job.sh")
for _ in $(seq 1 100); do pgrep -f "^$marker" >/dev/null && break; sleep 0.1; done
pgrep -f "^$marker" >/dev/null || fail "job $job never started"

# The cluster dies: controller and node daemon killed outright.
kill -KILL "$(cat "$DIR/slurmctld.pid")" "$(cat "$DIR/slurmd.pid")"
sleep 0.5

# The next start clears it: the orphaned step is gone, the new cluster takes jobs.
"$LOCAL" start "$DIR" 2>/dev/null
[ "$(sinfo -h -o %t)" = idle ] || fail "the node is not idle after the second start"
pgrep -f "^$marker" >/dev/null && fail "the dead cluster's job still runs"
[ "$(cat "$DIR/slurmctld.pid")" != "$first_ctld" ] || fail "slurmctld was not started again"
[ -z "$(squeue -h -o %i)" ] || fail "the new cluster holds the dead one's jobs: $(squeue -h)"
job=$(sbatch --parsable -o "$DIR/out.txt" --wrap "echo done")
for _ in $(seq 1 200); do [ -z "$(squeue -h -j "$job" -o %i 2>/dev/null)" ] && break; sleep 0.1; done
[ "$(cat "$DIR/out.txt" 2>/dev/null)" = done ] || fail "a job on the restarted cluster did not run"

# stop: every daemon gone.
pids="$(cat "$DIR/slurmctld.pid") $(cat "$DIR/slurmd.pid") $(cat "$DIR/munge/munged.pid")"
"$LOCAL" stop "$DIR" 2>/dev/null
for p in $pids; do alive "$p" && fail "process $p still runs after stop"; done
socket=$(sed -n 's/^AuthInfo=socket=//p' "$DIR/slurm.conf")
[ -e "$socket" ] && fail "stop left munge's socket $socket"
echo "PASS: a dead cluster is cleared by the next start; stop leaves nothing running"
