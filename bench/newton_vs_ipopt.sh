#!/bin/bash
# bench/newton_vs_ipopt.sh: the second-order solver (bench/newton_run) and the
# IPOPT peer (../shared/peers/ipopt/anchor.sh) on the same start and N, run
# alternately ROUNDS times on this machine, each result judged by
# `tightrope measure` (Rawdon ropelength of the written file).
# Usage: bench/newton_vs_ipopt.sh START.vect N [ROUNDS] [BUILD_DIR]
# N = 0 keeps the start's vertex count for newton_run (the peer needs N).
set -u
start=$1; n=$2; rounds=${3:-2}; build=${4:-build}
peer=${PEER_DIR:-$(dirname "$0")/../../shared/peers/ipopt}
nv=$(awk 'NR>1 && !/^#/{print $2; exit}' "$start")
[[ $n = 0 ]] && n=$nv
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for r in $(seq "$rounds"); do
  SECONDS=0
  nn=$n; [[ $n = "$nv" ]] && nn=0
  "$build/newton_run" "$start" "$tmp/newton.vect" "$nn" 600 > "$tmp/newton.log" 2>&1
  ts=$SECONDS
  rl=$("$build/tightrope" measure "$tmp/newton.vect" | awk '$1=="curve"{print $7}')
  echo "round $r tightrope-newton N=$n ropelength $rl seconds $ts ($(tail -1 "$tmp/newton.log" | sed 's/.*-> [0-9.]*, //; s/ (eval.*//'))"
  line=$("$peer/anchor.sh" "$start" "$n" "$tmp/peer.vect" 600 | tail -1)
  echo "round $r $line"
done
