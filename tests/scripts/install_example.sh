#!/usr/bin/env bash
# The public API as a user meets it (issue 46): cmake --install into a fresh
# prefix, then examples/trefoil.c built against the *installed* library,
# through pkg-config and through find_package(Tightrope), and run; and the
# library exports the API's names and nothing else.
#   install_example.sh BUILD_DIR SOURCE_DIR WORK_DIR
# TR_EXAMPLE_PRELOAD (a sanitizer build's runtime) is preloaded into the
# examples alone, not into the compilers.
set -euo pipefail
run() { env ${TR_EXAMPLE_PRELOAD:+LD_PRELOAD=$TR_EXAMPLE_PRELOAD} "$@"; }
build=$1 src=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null
pc=$(find "$prefix" -name tightrope.pc)
[ -n "$pc" ] || { echo "no tightrope.pc installed"; exit 1; }
export PKG_CONFIG_PATH=$(dirname "$pc")
libdir=$(cd "$(pkg-config --variable=libdir tightrope)" && pwd -P)
# (grep reads all of ldd's output: grep -q would stop early, ldd then die of
# SIGPIPE and pipefail fail the check)
# the SONAME carries the version; only tightrope_* is exported
lib=$(readlink -f "$libdir/libtightrope.so")
soname=$(readelf -d "$lib" | sed -n 's/.*SONAME.*\[\(.*\)\]/\1/p')
[ -e "$libdir/$soname" ] || { echo "SONAME $soname not installed in $libdir"; exit 1; }
other=$(nm -D --defined-only "$lib" | awk '{print $3}' | grep -v '^tightrope_' || true)
[ -z "$other" ] || { echo "exported beyond the API: $other"; exit 1; }

# pkg-config, strict C17, against the installed header and library
cc -std=c17 -Wall -Wextra -Werror -pedantic "$src/examples/trefoil.c" $(pkg-config --cflags --libs tightrope) \
   -Wl,-rpath,"$libdir" -o "$work/trefoil_pc"
ldd "$work/trefoil_pc" | grep -F "$prefix" >/dev/null || { echo "not linked against the installed library:"; ldd "$work/trefoil_pc"; exit 1; }
run "$work/trefoil_pc" 2 100

# find_package(Tightrope) -> Tightrope::tightrope
cmake -S "$src/examples" -B "$work/cmake-build" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/cmake-build" >/dev/null
ldd "$work/cmake-build/trefoil" | grep -F "$prefix" >/dev/null || { echo "find_package: not the installed library"; exit 1; }
run "$work/cmake-build/trefoil" 1 100
echo "install_example: ok"
