# The helpers the command-line test scripts share (sourced, not run):
#   fail MSG                    prints FAIL: MSG and exits 1
#   run CMD...                  stdout to ./out, stderr to ./err, status in $rc
#   refused STATUS PATTERN CMD...  CMD exits STATUS with one line on stderr matching PATTERN
#   rel GOT WANT TOL            |got/want - 1| <= tol (and got is a number)
#   json_get KEY FILE           the first number of "KEY": in a JSON text
# Expected values in the scripts are closed forms or facts about files,
# never our own earlier output.
fail() { echo "FAIL: $*"; exit 1; }
run() { "$@" >out 2>err; rc=$?; }
refused() {
  local want=$1 pat=$2; shift 2
  run "$@"
  [ "$rc" = "$want" ] || fail "$*: exit $rc, want $want: $(cat err)"
  [ "$(wc -l <err)" = 1 ] || fail "$*: want one line on stderr, got: $(cat err)"
  grep -Eq -- "$pat" err || fail "$*: message does not match '$pat': $(cat err)"
}
rel() { awk -v g="$1" -v w="$2" -v t="$3" 'BEGIN { r = (g - w) / w; if (r < 0) r = -r; exit !(r <= t && g == g) }'; }
json_get() { grep -o "\"$1\": [-+0-9.eE]*" "$2" | head -1 | sed 's/.*: //'; }
