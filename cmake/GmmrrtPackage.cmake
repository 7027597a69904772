# Debian package of everything `cmake --install` puts under /usr: the daemon, gmmrrt-plan,
# gmmrrt-learn, libgmmrrt (shared and static), gmmrrt_io, the message types, headers, CMake and
# pkg-config files, the systemd unit, /etc/gmmrrt/gmmrrtd.ini and the docs.
# Built by `tools/run package` (cpack -G DEB in build/), which also runs dpkg-deb and lintian.
include_guard(GLOBAL)

set(GMMRRT_PACKAGE_CONTACT "gmmrrt maintainers <maintainers@users.noreply.github.com>"
    CACHE STRING "Maintainer field of the Debian package")

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME gmmrrt)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "${GMMRRT_PACKAGE_CONTACT}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "social navigation planner for mobile robots (GMM-RRT*)")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
  "gmmrrt learns how a teleoperator drives around people as Gaussian\n"
  "mixtures and plans paths that move the same way with an RRT* whose\n"
  "samples and costs come from those mixtures. This package holds the\n"
  "planner daemon gmmrrtd (LCM in and out, a systemd unit), the tools\n"
  "gmmrrt-plan and gmmrrt-learn, and the planner library with its\n"
  "headers, pkg-config and CMake files.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Run-time dependencies come from the binaries (dpkg-shlibdeps); LCM is linked in statically.
# python3: the generated message package in dist-packages.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3")
# Building C or C++ programs against the installed library (pkg-config, find_package);
# python3-matplotlib: `gmmrrt-learn plot` draws its images with it (nothing else needs it).
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "pkg-config, libfcl-dev, libglib2.0-dev, python3-matplotlib")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "cmake")
# Control files: /etc/gmmrrt/gmmrrtd.ini is the administrator's (kept across upgrades); the
# shared library's shlibs entry, an ldconfig trigger, and maintainer scripts that only reload systemd.
set(deb ${CMAKE_BINARY_DIR}/debian)
file(WRITE ${deb}/conffiles "/etc/gmmrrt/gmmrrtd.ini\n")
file(WRITE ${deb}/shlibs
  "libgmmrrt ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR} gmmrrt (>= ${PROJECT_VERSION})\n")
file(WRITE ${deb}/triggers "activate-noawait ldconfig\n")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${deb}/conffiles ${deb}/shlibs ${deb}/triggers
    ${PROJECT_SOURCE_DIR}/cmake/debian/postinst ${PROJECT_SOURCE_DIR}/cmake/debian/postrm)
# What Debian wants in every package: copyright, a changelog, and the lintian overrides with
# their reasons (cmake/debian/). Installed for any prefix; harmless outside /usr.
string(TIMESTAMP GMMRRT_CHANGELOG_DATE "%a, %d %b %Y %H:%M:%S +0000" UTC)
configure_file(${PROJECT_SOURCE_DIR}/cmake/debian/changelog.in ${deb}/changelog @ONLY)
find_program(GZIP_EXECUTABLE gzip REQUIRED)
add_custom_command(OUTPUT ${deb}/changelog.gz
  COMMAND ${GZIP_EXECUTABLE} -9nc ${deb}/changelog > ${deb}/changelog.gz
  DEPENDS ${deb}/changelog VERBATIM)
add_custom_target(gmmrrt_deb_changelog ALL DEPENDS ${deb}/changelog.gz)
install(FILES ${PROJECT_SOURCE_DIR}/cmake/debian/copyright ${deb}/changelog.gz
        DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${PROJECT_SOURCE_DIR}/cmake/debian/gmmrrt.lintian-overrides
        DESTINATION ${CMAKE_INSTALL_DATADIR}/lintian/overrides RENAME gmmrrt)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_STRIP_FILES ON)
set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR}/package)
set(CPACK_OUTPUT_CONFIG_FILE ${CMAKE_BINARY_DIR}/CPackConfig.cmake)
include(CPack)
