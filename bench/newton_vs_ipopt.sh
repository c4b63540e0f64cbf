#!/bin/bash
# bench/newton_vs_ipopt.sh: Tightrope's second-order route and the IPOPT peer
# (../shared/peers/ipopt/anchor.sh) on the same start and N, run alternately
# ROUNDS times on this machine, each result judged by `tightrope measure`
# (Rawdon ropelength of the written file). Ours is the command a user runs:
# `tightrope tighten START --n N --newton` (the spline resampling and the
# solver before the engine's settle), or without --n when N is the start's.
# Usage: bench/newton_vs_ipopt.sh START.vect N [ROUNDS] [BUILD_DIR]
# N = 0 keeps the start's vertex count.
set -u
start=$1; n=$2; rounds=${3:-2}; build=${4:-build}
peer=${PEER_DIR:-$(dirname "$0")/../../shared/peers/ipopt}
nv=$(awk 'NR>1 && !/^#/{print $2; exit}' "$start")
[[ $n = 0 ]] && n=$nv
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
resample=(); [[ $n != "$nv" ]] && resample=(--n "$n")
for r in $(seq "$rounds"); do
  t0=$(date +%s%N)
  "$build/tightrope" tighten "$start" "${resample[@]}" --newton --time-limit 600 -o "$tmp/ours.vect" \
    > "$tmp/ours.log" 2>&1
  ts=$(awk -v a="$t0" -v b="$(date +%s%N)" 'BEGIN { printf "%.1f", (b - a) / 1e9 }')
  rl=$("$build/tightrope" measure "$tmp/ours.vect" | awk '$1=="curve"{print $7}')
  echo "round $r tightrope N=$n ropelength $rl seconds $ts ($(grep -E 'newton|stopped' "$tmp/ours.log" | sed 's/^ *//' | tr '\n' ';'))"
  line=$("$peer/anchor.sh" "$start" "$n" "$tmp/peer.vect" 600 | tail -1)
  echo "round $r $line"
done
