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
