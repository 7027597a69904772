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
set(CPACK_PACKAGE_DESCRIPTION
  "gmmrrt learns how a teleoperator drives around people as Gaussian mixtures and plans\n"
  "paths that move the same way with an RRT* whose samples and costs come from those\n"
  "mixtures. This package holds the planner daemon gmmrrtd (LCM in and out, a systemd\n"
  "unit), the command-line tools gmmrrt-plan and gmmrrt-learn, and the planner library\n"
  "with its headers, pkg-config and CMake files.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Run-time dependencies come from the binaries (dpkg-shlibdeps); LCM is linked in statically.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS_POLICY ">=")
# Building C or C++ programs against the installed library (pkg-config, find_package).
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "pkg-config, libfcl-dev, libglib2.0-dev")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "cmake")
# /etc/gmmrrt/gmmrrtd.ini is the administrator's: kept across upgrades.
file(WRITE ${CMAKE_BINARY_DIR}/debian/conffiles "/etc/gmmrrt/gmmrrtd.ini\n")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${CMAKE_BINARY_DIR}/debian/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_STRIP_FILES ON)
set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR}/package)
set(CPACK_OUTPUT_CONFIG_FILE ${CMAKE_BINARY_DIR}/CPackConfig.cmake)
include(CPack)
