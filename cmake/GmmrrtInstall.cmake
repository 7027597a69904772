# Install rules beyond each target's own: a relocatable install for any prefix P
# (cmake --install build --prefix P; docs/install.md).
#   P/lib/cmake/gmmrrt/   CMake package: find_package(gmmrrt CONFIG) -> gmmrrt::gmmrrt (shared core),
#                         gmmrrt::gmmrrt_static, gmmrrt::io, gmmrrt::lcmtypes, gmmrrt::lcmtypes_cpp
#   P/lib/pkgconfig/gmmrrt.pc   prefix taken from the file's own place (${pcfiledir})
#   P/lib/gmmrrt/liblcm.a, P/include/gmmrrt/third_party/lcm/   LCM's archive and headers, for
#                         programs that use gmmrrt::lcmtypes (the executables have it linked in)
#   P/lib/systemd/system/gmmrrtd.service, P/etc/gmmrrt/gmmrrtd.ini   pointing at P's paths
#   P/share/doc/gmmrrt/   the docs the unit's Documentation= names, and LCM's licence
include_guard(GLOBAL)
include(CMakePackageConfigHelpers)

set(GMMRRT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/gmmrrt)

# --- LCM's static archive and headers (a private copy: Debian's LCM is too old, and this keeps
# a system LCM's files apart).
set(lcm_archive "")
foreach(cfg RELEASE RELWITHDEBINFO NOCONFIG DEBUG)
  get_target_property(loc lcm-static IMPORTED_LOCATION_${cfg})
  if(loc)
    set(lcm_archive ${loc})
    break()
  endif()
endforeach()
get_target_property(lcm_include lcm-static INTERFACE_INCLUDE_DIRECTORIES)
if(NOT lcm_archive OR NOT EXISTS ${lcm_include}/lcm/lcm.h)
  message(FATAL_ERROR "LCM's static archive or headers not found (lcm-static: '${lcm_archive}', '${lcm_include}'); "
                      "reinstall LCM into the venv: tools/run setup")
endif()
install(FILES ${lcm_archive} DESTINATION ${CMAKE_INSTALL_LIBDIR}/gmmrrt)
install(DIRECTORY ${lcm_include}/lcm DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/gmmrrt/third_party
        FILES_MATCHING PATTERN "*.h" PATTERN "*.hpp")
get_filename_component(lcm_site ${lcm_archive} DIRECTORY)   # .../site-packages/lib
file(GLOB lcm_licence ${lcm_site}/../lcm-*.dist-info/licenses/COPYING)
if(lcm_licence)
  install(FILES ${lcm_licence} DESTINATION ${CMAKE_INSTALL_DOCDIR} RENAME LCM-COPYING)
endif()

# --- CMake package.
install(EXPORT gmmrrtTargets NAMESPACE gmmrrt:: DESTINATION ${GMMRRT_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/gmmrrtConfig.cmake.in
  ${CMAKE_BINARY_DIR}/gmmrrtConfig.cmake INSTALL_DESTINATION ${GMMRRT_CMAKE_DIR})
# Before 1.0 a minor release may change the API: only the same MAJOR.MINOR is compatible.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/gmmrrtConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/gmmrrtConfig.cmake ${CMAKE_BINARY_DIR}/gmmrrtConfigVersion.cmake
        DESTINATION ${GMMRRT_CMAKE_DIR})

# --- pkg-config. Cflags are the C flags only (FCL's -std=c++11 must not reach a C compile);
# Libs.private lists what a static link of the core adds: FCL (and what FCL needs) and the C++
# runtime of the FCL adapter.
pkg_check_modules(GMMRRT_FCL_PC QUIET fcl)
set(GMMRRT_PC_LIBS_PRIVATE "")
foreach(l ${GMMRRT_FCL_PC_STATIC_LIBRARIES})
  string(APPEND GMMRRT_PC_LIBS_PRIVATE " -l${l}")
endforeach()
if(NOT GMMRRT_PC_LIBS_PRIVATE)
  set(GMMRRT_PC_LIBS_PRIVATE " -lfcl")
endif()
string(APPEND GMMRRT_PC_LIBS_PRIVATE " -lstdc++")
# From P/LIBDIR/pkgconfig back to P: one ".." per component of LIBDIR, plus one for pkgconfig/.
file(RELATIVE_PATH GMMRRT_PC_UP /x/${CMAKE_INSTALL_LIBDIR}/pkgconfig /x)
string(REGEX REPLACE "/$" "" GMMRRT_PC_UP "${GMMRRT_PC_UP}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/gmmrrt.pc.in ${CMAKE_BINARY_DIR}/gmmrrt.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/gmmrrt.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# --- systemd unit, example INI and docs. Written at install time, because only then is the
# prefix known (cmake --install --prefix P overrides the configured one).
file(GLOB GMMRRT_DOCS ${PROJECT_SOURCE_DIR}/docs/*.md)
install(FILES ${GMMRRT_DOCS} ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(CODE "
  set(GMMRRT_SOURCE_DIR \"${PROJECT_SOURCE_DIR}\")
  set(GMMRRT_BINDIR \"${CMAKE_INSTALL_BINDIR}\")
  set(GMMRRT_DOCDIR \"${CMAKE_INSTALL_DOCDIR}\")
  include(\"${PROJECT_SOURCE_DIR}/cmake/GmmrrtInstallService.cmake\")")
