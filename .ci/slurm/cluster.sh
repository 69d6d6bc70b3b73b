#!/usr/bin/env bash
# Starts or stops a single-node SLURM cluster (munged, slurmctld, slurmd) on localhost, all
# of its state under one directory. Needs root and Debian's slurm-wlm and munge packages.
#   .ci/slurm/cluster.sh start DIR   # prints `export SLURM_CONF=DIR/slurm.conf`
#   .ci/slurm/cluster.sh stop DIR    # stops the daemons it started (by their pid files)
set -euo pipefail
cmd=${1:?usage: cluster.sh start|stop DIR}
dir=${2:?usage: cluster.sh start|stop DIR}
here="$(cd "$(dirname "$0")" && pwd)"

stop() {
  for pid in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
    if [ -s "$pid" ]; then
      kill "$(cat "$pid")" 2>/dev/null || true
    fi
  done
  # Wait (bounded) for them to exit, so the ports are free for the next cluster.
  for _ in $(seq 50); do
    alive=0
    for pid in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
      [ -s "$pid" ] && kill -0 "$(cat "$pid")" 2>/dev/null && alive=1
    done
    [ $alive = 0 ] && return 0
    sleep 0.1
  done
}

case "$cmd" in
  start)
    mkdir -p "$dir/munge" "$dir/state" "$dir/spool"
    chmod 0755 "$dir" "$dir/munge"
    # munged: its own key, socket, pid, log and seed files.
    dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
    chmod 0400 "$dir/munge/munge.key"
    munged --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
      --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
      --seed-file="$dir/munge/munged.seed" --force
    # Free ports, so that a second cluster (or a stale one) does not collide.
    ports=$(python3 -c 'import socket
s=[socket.socket() for _ in range(2)]
[x.bind(("127.0.0.1",0)) for x in s]
print(" ".join(str(x.getsockname()[1]) for x in s))')
    set -- $ports
    sed -e "s|@DIR@|$dir|g" -e "s|@MUNGE_SOCKET@|$dir/munge/munge.socket|g" -e "s|@USER@|$(id -un)|g" \
      -e "s|@CTLD_PORT@|$1|g" -e "s|@SLURMD_PORT@|$2|g" "$here/slurm.conf.in" > "$dir/slurm.conf"
    export SLURM_CONF="$dir/slurm.conf"
    slurmctld -f "$SLURM_CONF"
    slurmd -f "$SLURM_CONF" -N localhost
    # Ready when the node is idle.
    for _ in $(seq 100); do
      if sinfo -h -o "%t" 2>/dev/null | grep -q idle; then
        echo "export SLURM_CONF=$SLURM_CONF"
        exit 0
      fi
      sleep 0.2
    done
    echo "cluster.sh: the SLURM node did not become idle; logs in $dir" >&2
    tail -n 20 "$dir"/slurmctld.log "$dir"/slurmd.log >&2 || true
    stop
    exit 1
    ;;
  stop)
    stop
    ;;
  *)
    echo "usage: cluster.sh start|stop DIR" >&2
    exit 2
    ;;
esac
