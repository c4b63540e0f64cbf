# The shared library libtightrope.so (the public C API, include/tightrope/
# tightrope.h, over the static layers), its pkg-config file and its CMake
# package, installed by cmake --install; and, in a Python build
# (scikit-build-core sets SKBUILD), the library alone inside the package.
#
# Only the API's functions are exported: every layer is compiled with hidden
# visibility (host/CMakeLists.txt tr_layer) and the header marks the public
# declarations TIGHTROPE_API (visibility default).
#
# SOVERSION: while the major version is 0 every minor version may change
# the ABI (its structs included), so the SONAME carries both:
# libtightrope.so.0.1; from 1.0 on, the major alone.
include(GNUInstallDirs)
if(PROJECT_VERSION_MAJOR EQUAL 0)
  set(TIGHTROPE_SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
else()
  set(TIGHTROPE_SOVERSION ${PROJECT_VERSION_MAJOR})
endif()

# The library needs one source of its own; everything else comes whole from
# tr_api (nothing in the library calls the API, so a plain link would take
# none of it) and, as the API needs them, from the layers below.
add_library(tightrope_shared SHARED ${CMAKE_SOURCE_DIR}/cmake/shared_library.c)
target_link_libraries(tightrope_shared PRIVATE "$<LINK_LIBRARY:WHOLE_ARCHIVE,tr_api>")
target_include_directories(tightrope_shared PUBLIC
  $<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
set_target_properties(tightrope_shared PROPERTIES
  OUTPUT_NAME tightrope EXPORT_NAME tightrope
  VERSION ${PROJECT_VERSION} SOVERSION ${TIGHTROPE_SOVERSION}
  C_VISIBILITY_PRESET hidden)
# every symbol resolved at link time (appended: the sanitizers' link options
# stay; --exclude-libs would hide the API too, its objects come from an archive)
target_link_options(tightrope_shared PRIVATE "LINKER:--no-undefined")
add_library(Tightrope::tightrope ALIAS tightrope_shared)

if(SKBUILD)
  # The wheel: the library's file under the package's name, loaded by path
  # (python/src/tightrope/_lib.py); symbolic links do not survive a wheel.
  install(FILES $<TARGET_FILE:tightrope_shared> DESTINATION tightrope RENAME libtightrope.so COMPONENT python)
  return()
endif()

install(TARGETS tightrope_shared EXPORT TightropeTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES ${CMAKE_SOURCE_DIR}/include/tightrope/tightrope.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tightrope)

# pkg-config: relocatable (prefix found from the file's own place), so
# cmake --install --prefix P works wherever P is.
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(TIGHTROPE_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH _up "/p/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/p")
  string(REGEX REPLACE "/$" "" _up "${_up}")
  set(TIGHTROPE_PC_PREFIX "\${pcfiledir}/${_up}")
endif()
configure_file(${CMAKE_SOURCE_DIR}/cmake/tightrope.pc.in ${CMAKE_BINARY_DIR}/tightrope.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/tightrope.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# find_package(Tightrope) -> Tightrope::tightrope
include(CMakePackageConfigHelpers)
set(TIGHTROPE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Tightrope)
install(EXPORT TightropeTargets NAMESPACE Tightrope:: DESTINATION ${TIGHTROPE_CMAKE_DIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/TightropeConfig.cmake.in
  ${CMAKE_BINARY_DIR}/TightropeConfig.cmake INSTALL_DESTINATION ${TIGHTROPE_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/TightropeConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion) # the SONAME's rule: 0.x minors differ in ABI
install(FILES ${CMAKE_BINARY_DIR}/TightropeConfig.cmake ${CMAKE_BINARY_DIR}/TightropeConfigVersion.cmake
  DESTINATION ${TIGHTROPE_CMAKE_DIR})
