#!/usr/bin/env bash
# Which backend each level of 'tightrope tighten --refine-to' runs on
# (engine.h device_min_n, --device-from): coarse levels below the threshold
# run on the serial reference, the final level and --device-from 0 on the
# chosen device. The JSON's "device" is the backend of the level the run
# stopped at. Usage: device_levels.sh TIGHTROPE WORK_DIR.
# Exit 0 pass, 1 fail, 77 skipped (no OpenCL device).
set -u
tr=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
"$tr" make torus 2 3 --n 72 -o "$work/s.vect" >/dev/null || fail "make"
run() { # OUT-NAME ARGS...: the JSON summary on stdout
  local name=$1; shift
  "$tr" tighten "$work/s.vect" -o "$work/$name.vect" --device opencl --quiet --json "$@" >"$work/$name.json" \
    2>"$work/$name.err"
}
if ! run probe --steps 1; then
  grep -q "no usable opencl device" "$work/probe.err" && { echo "skipped: no OpenCL device"; exit 77; }
  fail "probe: $(cat "$work/probe.err")"
fi
device() { sed -n 's/^  "device": "\([^"]*\)".*/\1/p' "$work/$1.json"; }
n_of() { sed -n 's/^  "N": \([0-9]*\).*/\1/p' "$work/$1.json"; }
# 5 steps stop the run on its coarse level (72 vertices, 144 the final):
# the --refine-to not reached is exit 1, the coarse level written
run coarse --refine-to 144 --steps 5 --device-from 1000
[ $? = 1 ] && grep -q "before reaching the requested --refine-to 144" "$work/coarse.err" ||
  fail "coarse: $(cat "$work/coarse.err")"
[ "$(n_of coarse)" = 72 ] || fail "coarse: N $(n_of coarse)"
case "$(device coarse)" in "serial reference"*) ;; *) fail "coarse level on '$(device coarse)'" ;; esac
run every --refine-to 144 --steps 5 --device-from 0
[ $? = 1 ] || fail "every: $(cat "$work/every.err")"
case "$(device every)" in OpenCL*) ;; *) fail "--device-from 0 on '$(device every)'" ;; esac
# with a time limit the coarse level takes a share and hands over (the time
# enough for the final level's kernels to build and its settle to end: past
# the limit a refinement goes back to the coarse level): the final
# level (N 144) runs on the device again
run final --refine-to 144 --time-limit 30 --device-from 1000 || fail "final: $(cat "$work/final.err")"
[ "$(n_of final)" = 144 ] || fail "final: N $(n_of final)"
case "$(device final)" in OpenCL*) ;; *) fail "final level on '$(device final)'" ;; esac
echo "coarse level: $(device coarse); every level: $(device every); final level: $(device final)"
