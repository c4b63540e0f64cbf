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
