#!/usr/bin/env bash
# Runs one program under Oclgrind and fails on anything Oclgrind reports.
#   scripts/oclgrind_run.sh PROGRAM [ARGS...]
# Oclgrind exits with the program's own status whatever it finds, so what it
# says is read instead: its log (--log: invalid accesses, data races,
# uninitialised values, anything its plugins report) must be empty, and its
# lines on stderr (API errors, fatal errors, all of which name Oclgrind)
# must be only the OpenCL errors the program announced it provokes on
# purpose ("oclgrind-expect: FUNCTION ERROR" on its stdout, see
# tests/testlib.h), each exactly as often as announced. A status other than
# 0 fails too, 77 ("skipped": no OpenCL device found, nothing checked)
# included. Only Oclgrind's platform is visible: its runtime is preloaded
# and the ICD loader is pointed at an empty vendor directory.
# Every kernel location in a report gets a FILE:LINE:COLUMN line, and the
# source line shown is read from that file (Oclgrind quotes the line of
# that number in the program the sources are concatenated into). The first
# five reports are printed whole, then their count.
# TIGHTROPE_OCLGRIND_FLAGS replaces the checks (default: --check-api --data-races).
# Not --uninitialized: Oclgrind 21.10's plugin for it dies (SIGSEGV) on the
# first shufflevector with an undefined lane, which clang emits for every
# double3 load and store (Uninitialized.cpp compares the mask element with
# Value::UndefValueVal, not -1; upstream fixed it for LLVM 21 only).
set -uo pipefail
if [ $# -lt 1 ]; then
  echo "usage: $0 PROGRAM [ARGS...]" >&2
  exit 2
fi
command -v oclgrind >/dev/null || { echo "oclgrind_run: oclgrind is not installed" >&2; exit 1; }
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/oclgrind_run.XXXXXX") || exit 1
trap 'rm -rf "$work"' EXIT
read -r -a flags <<< "${TIGHTROPE_OCLGRIND_FLAGS:---check-api --data-races}"
mkdir "$work/no-vendors"
: > "$work/log"
# TIGHTROPE_CL_BUILD_STDERR=keep: Tightrope leaves stderr to the runtime while
# a program builds (it otherwise keeps a compiler's chatter off the user's
# terminal), so Oclgrind's report of a failed clBuildProgram reaches $work/err
TIGHTROPE_CL_BUILD_STDERR=keep OCL_ICD_VENDORS="$work/no-vendors" oclgrind "${flags[@]}" --log "$work/log" "$@" \
  > "$work/out" 2> "$work/err"
rc=$?
cat "$work/out"
cat "$work/err" >&2
# awk reads the announcements (stdout), then stderr, then the log. On stderr
# an API error is a paragraph:
#   Oclgrind - OpenCL runtime error detected
#   <tab>Function: clFinish
#   <tab>Error:    CL_INVALID_COMMAND_QUEUE
#   <tab>(more detail)
# Any other line of Oclgrind's there ("Oclgrind...", "OCLGRIND FATAL ERROR",
# "[Oclgrind]...") is a problem; the program's own
# lines are not. Every line of the log belongs to a problem.
verdict=$(awk -v root="$root" '
  function flush_api() {
    if (!api) return
    api = 0
    if (want[fn " " er] > 0) { want[fn " " er]--; return }
    bad++
    printf "oclgrind_run: unannounced OpenCL API error:\n%s", text
  }
  function source_line(file, n,    path, l, i) {
    path = file
    if (path !~ /^\//) path = root "/" path
    for (i = 1; (getline l < path) > 0; i++)
      if (i == n) { close(path); sub(/^[ \t]+/, "", l); return l }
    close(path)
    return ""
  }
  FILENAME == ARGV[1] { if ($1 == "oclgrind-expect:") want[$2 " " $3]++; next }
  FILENAME == ARGV[2] {
    if (api && /^\t/) {
      text = text $0 "\n"
      if ($1 == "Function:") fn = $2
      if ($1 == "Error:") er = $2
      next
    }
    flush_api()
    if (/^Oclgrind - OpenCL runtime error detected/) {
      api = 1; fn = ""; er = ""; text = $0 "\n"; next
    }
    if (/^(\[?Oclgrind|OCLGRIND|Loading Oclgrind)/) { bad++; print "oclgrind_run: Oclgrind says: " $0 }
    next
  }
  {
    flush_api()
    if (/^[ \t]*$/) { quote = 0; next }
    if (!logged++) print "oclgrind_run: Oclgrind reports:"
    logbad = 1
    if (/^[^ \t]/) reports++
    if (reports > 5) next # the first five in full, then a count
    if (match($0, /At line [0-9]+ \(column [0-9]+\) of .*:$/)) {
      split($0, w, /[ ()]+/)
      for (i = 1; w[i] != "line"; i++);
      n = w[i + 1]; c = w[i + 3]
      f = $0; sub(/.* of /, "", f); sub(/:$/, "", f)
      print f ":" n ":" c ": " kind
      print
      s = source_line(f, n)
      if (s != "") { print "\t  " s; quote = 1 }
      next
    }
    if (quote) { quote = 0; next } # the quoted line of the concatenated program
    if (/^[A-Z]/) kind = $0
    print
  }
  END {
    flush_api()
    bad += logbad
    if (reports > 5) printf "oclgrind_run: %d reports in all, the first 5 shown\n", reports
    for (k in want) if (want[k] > 0) {
      bad++
      printf "oclgrind_run: announced error not reported: %s (%d more expected)\n", k, want[k]
    }
    print bad ? "FAIL" : "OK"
  }
' "$work/out" "$work/err" "$work/log")
status=0
if [ "${verdict##*$'\n'}" != OK ]; then
  [ "$verdict" = FAIL ] || printf '%s\n' "${verdict%$'\n'*}" >&2
  echo "oclgrind_run: FAILED: Oclgrind found problems running $*" >&2
  status=1
fi
if [ "$rc" -ne 0 ]; then
  echo "oclgrind_run: FAILED: $* exited with status $rc under Oclgrind" >&2
  status=1
fi
[ $status -eq 0 ] && echo "oclgrind_run: clean ($*)"
exit $status
