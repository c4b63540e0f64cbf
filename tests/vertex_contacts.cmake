# bench/vertex_contacts against closed forms (included by tests/CMakeLists.txt): the regular
# 100-gon on a circle of radius 10 has e = 20 sin(pi/100), K = ceil(pi/e) = 6, MinRad =
# e / (2 tan(pi/100)), and its closest vertices K apart lie 20 sin(6 pi/100) apart, which is
# the thickness (dmin / 2 < MinRad), so the vertex ropelength is 100 e / (10 sin(6 pi/100)).
# A file that is no curve is exit 2.
add_test(NAME cli_vertex_contacts_polygon
  COMMAND ${CMAKE_COMMAND} -E env sh -c "set -e
    f=\$(mktemp --suffix=.txt)
    awk 'BEGIN { p = atan2(0, -1); for (i = 0; i < 100; i++) printf \"%.17g %.17g 0\\n\", 10 * cos(2 * p * i / 100), 10 * sin(2 * p * i / 100) }' > \$f
    out=\$('$<TARGET_FILE:vertex_contacts>' \$f); rm -f \$f; echo \"\$out\"
    echo \"\$out\" | awk '{ p = atan2(0, -1); e = 20 * sin(p / 100); d = 20 * sin(6 * p / 100)
      ok = \$2 == 100 && \$4 == 6 && (\$6 - 100 * e)^2 < 1e-20 && (\$11 - e / (2 * sin(p / 100) / cos(p / 100)))^2 < 1e-20 &&
           (\$14 - d)^2 < 1e-20 && (\$17 - 100 * e / (d / 2))^2 < 1e-18
      exit !ok }'")
add_test(NAME cli_vertex_contacts_bad
  COMMAND ${CMAKE_COMMAND} -E env sh -c "printf 'not a curve\\n' > vc_bad.txt; '$<TARGET_FILE:vertex_contacts>' vc_bad.txt; test $? -eq 2")
# tightrope measure --contacts vertex (oracle/vertex_thickness.h), scale free, on the regular
# 100-gon of circumradius 7: at R = MinRad = 7 cos(pi/100), K = ceil(pi / (2 tan(pi/100))) = 50,
# the vertices 50 apart are 14 apart (> 2R), so the thickness is MinRad and the ropelength
# 200 tan(pi/100); the JSON says which model. --kkt with it, or another model, is exit 2 with one line.
add_test(NAME cli_measure_contacts_vertex
  COMMAND ${CMAKE_COMMAND} -E env sh -c "set -e
    f=\$(mktemp --suffix=.txt)
    awk 'BEGIN { p = atan2(0, -1); for (i = 0; i < 100; i++) printf \"%.17g %.17g 0\\n\", 7 * cos(2 * p * i / 100), 7 * sin(2 * p * i / 100) }' > \$f
    out=\$('$<TARGET_FILE:tightrope>' measure --contacts vertex \$f); js=\$('$<TARGET_FILE:tightrope>' measure --json --contacts vertex \$f); rm -f \$f
    echo \"\$out\"; echo \"\$js\" | grep -q '\"contacts\": \"vertex\", \"vertex_contacts\": {\"edge\": [0-9.e-]*, \"exclusion\": 50, '
    echo \"\$out\" | grep -q '^contacts vertex (SP-FEM'
    echo \"\$out\" | awk '\$1 == \"vertex\" { p = atan2(0, -1); n++
      ok = \$3 == 50 && (\$5 - 14)^2 < 1e-24 && (\$6 - 7 * cos(p / 100))^2 < 1e-20 && (\$7 - 200 * sin(p / 100) / cos(p / 100))^2 < 1e-20 }
      END { exit !(n == 1 && ok) }'")
add_test(NAME cli_measure_contacts_vertex_kkt
  COMMAND ${CMAKE_COMMAND} -E env sh -c "printf '0 0 0\\n1 0 0\\n0 1 0\\n' > mcv.txt
    '$<TARGET_FILE:tightrope>' measure --contacts vertex --kkt mcv.txt > mcv.out 2> mcv.err; rc=\$?
    test \$rc -eq 2 && test ! -s mcv.out && test \$(wc -l < mcv.err) -eq 1 || exit 1
    '$<TARGET_FILE:tightrope>' measure --contacts edge mcv.txt 2> mcv.err; test \$? -eq 2 && test \$(wc -l < mcv.err) -eq 1")
# tightrope tighten --contacts vertex (host/tighten/vertex_route.c), judged by measure --contacts vertex
# on the written file. The unknot: a wobbled 32-gon of radius 1.6 goes to the regular 32-gon with
# MinRad 1 (edges e = 2 tan(pi/32)), the shortest closed 32-gon with MinRad >= 1; its vertices
# K = ceil(pi/e) = 16 apart lie 2 / cos(pi/32) > 2 apart, so the vertex model's optimum is the
# same: ropelength 64 tan(pi/32), and the comments say the model with that K.
add_test(NAME cli_tighten_contacts_vertex_unknot
  COMMAND ${CMAKE_COMMAND} -E env sh -c "set -e
    d=\$(mktemp -d)
    awk 'BEGIN { p = atan2(0, -1); for (i = 0; i < 32; i++) printf \"%.17g %.17g %.17g\\n\", 1.6 * cos(2 * p * i / 32), 1.6 * sin(2 * p * i / 32), 0.08 * sin(6 * p * i / 32) }' > \$d/u.txt
    '$<TARGET_FILE:tightrope>' tighten --contacts vertex --quiet \$d/u.txt -o \$d/u.vect > \$d/sum
    cat \$d/sum; grep -q '^  contacts: vertex (SP-FEM), K = 16[^0-9]' \$d/sum
    grep -q '^# contacts: vertex (SP-FEM), K = 16:' \$d/u.vect; grep -q '^# knot type kept' \$d/u.vect
    out=\$('$<TARGET_FILE:tightrope>' measure --contacts vertex \$d/u.vect); rm -rf \$d; echo \"\$out\"
    echo \"\$out\" | awk '\$1 == \"vertex\" { p = atan2(0, -1); w = 64 * sin(p / 32) / cos(p / 32); n++
      ok = \$3 == 16 && (\$6 - 1)^2 < 1e-18 && ((\$7 - w) / w)^2 < 1e-16 }
      END { exit !(n == 1 && ok) }'")
# The trefoil from the Rawdon-tight N = 1600 polygon (bench/data): the vertex model holds vertices,
# not edges, 2 apart, so where two strands touch an edge dips into the other's tube by the sag of a
# chord of length e on the unit-curvature contact arc, e^2/8 (docs/physics.md): the written curve
# is at the model's thickness 1 (vertex_dmin 2), its closest segments 2 - e^2/8 apart (Rawdon's
# measure, within 5 % of the sag), and it is shorter in the model than the start in Rawdon's.
add_test(NAME cli_tighten_contacts_vertex_trefoil
  COMMAND ${CMAKE_COMMAND} -E env sh -c "set -e
    d=\$(mktemp -d); f='${CMAKE_SOURCE_DIR}/bench/data/trefoil_1600.vect'
    '$<TARGET_FILE:tightrope>' tighten --contacts vertex --quiet \$f -o \$d/t.vect
    grep -q '^# knot type kept' \$d/t.vect
    raw=\$('$<TARGET_FILE:tightrope>' measure \$f | awk '\$1 == \"curve\" { print \$7 }')
    out=\$('$<TARGET_FILE:tightrope>' measure --contacts vertex \$d/t.vect); rm -rf \$d; echo \"\$out\"; echo \"start (Rawdon) \$raw\"
    echo \"\$out\" | awk -v raw=\$raw '\$1 == \"curve\" { dcsd = \$5 } \$1 == \"vertex\" { e = \$2; dmin = \$5; th = \$6; rl = \$7; n++ }
      END { sag = e * e / 8; d = (2 - dcsd) - sag; if (d < 0) d = -d
        exit !(n == 1 && (th - 1)^2 < 1e-18 && (dmin - 2)^2 < 1e-17 && rl < raw - 1e-4 && d < 0.05 * sag) }'")
# The time limit holds, within a second as the hostile_limits tests ask (the solve at N = 4800 from
# the N = 2400 file resampled takes longer), and the
# run says where it stopped; an open rope (the clasp), options of Rawdon's route and a bad model are
# refused with one line, exit 2, nothing written.
add_test(NAME cli_tighten_contacts_vertex_time
  COMMAND ${CMAKE_COMMAND} -E env sh -c "set -e
    d=\$(mktemp -d)
    t0=\$(date +%s.%N)
    '$<TARGET_FILE:tightrope>' tighten --contacts vertex --quiet --n 4800 --time-limit 5 '${CMAKE_SOURCE_DIR}/bench/data/trefoil_2400.vect' -o \$d/t.vect
    t1=\$(date +%s.%N); grep '^# stop\\|^# newton\\|^# ropelength' \$d/t.vect
    grep -q '^# stop time-limit' \$d/t.vect; grep -q '^# knot type kept' \$d/t.vect
    grep -q '^# contacts: vertex (SP-FEM)' \$d/t.vect; rm -rf \$d
    s=1; [ -n \"\${ASAN_OPTIONS:-}\" ] && s=10
    awk -v a=\$t0 -v b=\$t1 -v s=\$s 'BEGIN { print b - a, \"s\"; exit !(b - a <= 5 + s) }'")
# A limit that ends before the solver's first step (its start measure or
# first strut list; under a sanitizer at 5 s, a CI run): the start is written
# at the model's thickness 1 with where it stopped, exit 0, as the Rawdon
# route writes a start its bound stopped (the start is measured at 0.05 s
# here, the solver's first list takes longer than what is left of 0.2 s).
add_test(NAME cli_tighten_contacts_vertex_time_first_step
  COMMAND ${CMAKE_COMMAND} -E env sh -c "set -e
    d=\$(mktemp -d); t=0.2; [ -n \"\${ASAN_OPTIONS:-}\" ] && t=2
    '$<TARGET_FILE:tightrope>' tighten --contacts vertex --quiet --n 4800 --time-limit \$t '${CMAKE_SOURCE_DIR}/bench/data/trefoil_2400.vect' -o \$d/t.vect 2> \$d/err
    cat \$d/err; grep '^# stop\\|^# newton' \$d/t.vect
    grep -q '^# stop time-limit' \$d/t.vect; grep -q '^# knot type kept' \$d/t.vect
    out=\$('$<TARGET_FILE:tightrope>' measure --contacts vertex \$d/t.vect); rm -rf \$d; echo \"\$out\"
    echo \"\$out\" | awk '\$1 == \"vertex\" { th = \$6; n++ } END { exit !(n == 1 && (th - 1)^2 < 1e-18) }'")
add_test(NAME cli_tighten_contacts_vertex_refused
  COMMAND ${CMAKE_COMMAND} -E env sh -c "set -e
    d=\$(mktemp -d); tr='$<TARGET_FILE:tightrope>'; f='${CMAKE_SOURCE_DIR}/bench/data/trefoil_1600.vect'
    \$tr make clasp --n 40 -o \$d/clasp.vect > /dev/null
    refused() { if \"\$@\" > \$d/out 2> \$d/err; then rc=0; else rc=\$?; fi; cat \$d/err
      test \$rc -eq 2 && test \$(wc -l < \$d/err) -eq 1 && test ! -e \$d/o.vect; }
    refused \$tr tighten --contacts vertex \$d/clasp.vect -o \$d/o.vect
    grep -q 'closed components' \$d/err
    for opt in '--refine-to 3200' '--tries 2' '--kkt' '--device reference' '--target 30' '--residual 1e-3' '--no-newton' '--checkpoint '\$d/c.ckpt; do
      refused \$tr tighten --contacts vertex \$opt \$f -o \$d/o.vect; grep -q 'contacts vertex' \$d/err; done
    refused \$tr tighten --contacts vertex --resume \$d/c.ckpt -o \$d/o.vect
    refused \$tr tighten --contacts edge \$f -o \$d/o.vect; grep -q 'segment or vertex' \$d/err
    rm -rf \$d")
