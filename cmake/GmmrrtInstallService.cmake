# Install-time script (install(CODE) in GmmrrtInstall.cmake): writes the systemd unit and the
# example INI of tools/systemd/ with the paths of the prefix being installed to, which is only
# known now (cmake --install --prefix P). In: CMAKE_INSTALL_PREFIX, GMMRRT_SOURCE_DIR,
# GMMRRT_BINDIR, GMMRRT_DOCDIR; DESTDIR from the environment (CPack, staged installs).
#   P/lib/systemd/system/gmmrrtd.service  ExecStart=P/bin/gmmrrtd --config ETC/gmmrrt/gmmrrtd.ini
#   ETC/gmmrrt/gmmrrtd.ini                 models at ETC/gmmrrt/models/{avoid,approach}.gmm
# ETC is /etc for the prefix /usr (as GNUInstallDirs has it), else P/etc.
set(p "${CMAKE_INSTALL_PREFIX}")
if(p STREQUAL "/usr")
  set(etc "/etc")
  set(unitdir "/lib/systemd/system")
else()
  set(etc "${p}/etc")
  set(unitdir "${p}/lib/systemd/system")
endif()

# gmmrrt_rewrite(SRC TEXT DST OLD NEW [OLD NEW...]): TEXT (read from SRC) with each OLD replaced, into DST;
# every OLD must occur (a changed source file stops the install instead of installing wrong paths).
function(gmmrrt_rewrite src text dst)
  set(pairs ${ARGN})
  list(LENGTH pairs n)
  math(EXPR last "${n} - 1")
  foreach(i RANGE 0 ${last} 2)
    math(EXPR j "${i} + 1")
    list(GET pairs ${i} old)
    list(GET pairs ${j} new)
    string(FIND "${text}" "${old}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "${src} no longer holds '${old}': update cmake/GmmrrtInstallService.cmake")
    endif()
    string(REPLACE "${old}" "${new}" text "${text}")
  endforeach()
  set(out "$ENV{DESTDIR}${dst}")
  get_filename_component(dir "${out}" DIRECTORY)
  file(MAKE_DIRECTORY "${dir}")
  # Written beside, then renamed: an interrupted install leaves no half-written file.
  file(WRITE "${out}.tmp" "${text}")
  file(RENAME "${out}.tmp" "${out}")
  message(STATUS "Installing: ${out}")
  list(APPEND CMAKE_INSTALL_MANIFEST_FILES "${out}")
  set(CMAKE_INSTALL_MANIFEST_FILES "${CMAKE_INSTALL_MANIFEST_FILES}" PARENT_SCOPE)
endfunction()

# The source unit's leading comment is for installing by hand from the checkout; drop it.
set(unit_src "${GMMRRT_SOURCE_DIR}/tools/systemd/gmmrrtd.service")
file(READ "${unit_src}" unit)
string(FIND "${unit}" "[Unit]" at)
string(SUBSTRING "${unit}" ${at} -1 unit)
string(CONCAT unit
  "# gmmrrtd, installed under ${p} (docs/install.md, docs/daemon.md \"Install as a service\").\n"
  "# Put the models at ${etc}/gmmrrt/models/{avoid,approach}.gmm, then:\n"
  "#   systemctl link ${unitdir}/gmmrrtd.service   (unless ${unitdir} is searched by systemd)\n"
  "#   systemctl daemon-reload && systemctl enable --now gmmrrtd\n"
  "${unit}")
gmmrrt_rewrite("${unit_src}" "${unit}" "${unitdir}/gmmrrtd.service"
  "/usr/local/bin/gmmrrtd" "${p}/${GMMRRT_BINDIR}/gmmrrtd"
  "--config /etc/gmmrrt/gmmrrtd.ini" "--config ${etc}/gmmrrt/gmmrrtd.ini"
  "file:///usr/local/share/doc/gmmrrt/" "file://${p}/${GMMRRT_DOCDIR}/")
set(ini_src "${GMMRRT_SOURCE_DIR}/tools/systemd/gmmrrtd.ini")
file(READ "${ini_src}" ini)
gmmrrt_rewrite("${ini_src}" "${ini}" "${etc}/gmmrrt/gmmrrtd.ini"
  "avoid = /etc/gmmrrt/models/" "avoid = ${etc}/gmmrrt/models/"
  "approach = /etc/gmmrrt/models/" "approach = ${etc}/gmmrrt/models/")
file(MAKE_DIRECTORY "$ENV{DESTDIR}${etc}/gmmrrt/models")
