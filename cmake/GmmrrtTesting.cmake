# GmmrrtTesting.cmake - what every test folder needs (tests/ and tests/bench/ alike): cmocka, the
# venv's Python and pytest command line, the test data and real-data folders, and the helpers
# gmmrrt_add_unit_test / gmmrrt_add_python_test / gmmrrt_add_missing_test. Included from the top
# CMakeLists.txt, so a folder added outside tests/ (the benchmarks) registers its tests with the
# same command and environment instead of running a pytest file as a plain script.
pkg_check_modules(CMOCKA REQUIRED IMPORTED_TARGET cmocka)

set(GMMRRT_TEST_DATA_DIR ${PROJECT_SOURCE_DIR}/tests/data)
set(GMMRRT_VENV_PYTHON ${PROJECT_SOURCE_DIR}/.venv/bin/python CACHE FILEPATH "Python of the project venv")
# The generated message package and tests/common (the pytest plugin, the daemon fixture);
# gmmrrt_tools is installed in the venv (tools/pyproject.toml).
set(GMMRRT_PYTHONPATH ${CMAKE_BINARY_DIR}/python:${PROJECT_SOURCE_DIR}/tests/common)
# Every pytest run: -rs prints each skip's reason; the plugin tests/common/gmmrrt_skip_status.py
# turns a file whose tests all skipped into exit 77, which CTest reports as skipped (never passed).
set(GMMRRT_PYTEST -m pytest -q -rs -p no:cacheprovider -p gmmrrt_skip_status)
# Only two things may skip: the optional real data (../shared/data/real) and the benchmark-only
# peers. Anything the build makes (libraries, gmmrrtd, generated types, test binaries) and
# anything checked in is required: its absence fails the test.
# Real data stays outside the project; tests that use it skip with a message when absent.
if(DEFINED ENV{GMMRRT_REAL_DATA})
  set(GMMRRT_REAL_DATA_DEFAULT $ENV{GMMRRT_REAL_DATA})
else()
  set(GMMRRT_REAL_DATA_DEFAULT ${PROJECT_SOURCE_DIR}/../shared/data/real)
endif()
set(GMMRRT_REAL_DATA ${GMMRRT_REAL_DATA_DEFAULT} CACHE PATH "Folder of the real demonstrations")

# gmmrrt_add_unit_test(NAME area.module SOURCES a.c ... [LIBS lib ...]) -- label `unit`
# One cmocka executable, registered with CTest under NAME, run from the build dir with
# GMMRRT_TEST_DATA_DIR and GMMRRT_BIN_DIR in its environment.
function(gmmrrt_add_unit_test)
  cmake_parse_arguments(T "" "NAME;TIMEOUT" "SOURCES;LIBS" ${ARGN})
  string(REPLACE "." "_" exe "test_${T_NAME}")
  add_executable(${exe} ${T_SOURCES})
  set_target_properties(${exe} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  target_link_libraries(${exe} PRIVATE PkgConfig::CMOCKA ${T_LIBS})
  target_compile_definitions(${exe} PRIVATE _DEFAULT_SOURCE _POSIX_C_SOURCE=200809L)
  gmmrrt_target_defaults(${exe})
  add_test(NAME ${T_NAME} COMMAND ${exe})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  set_tests_properties(${T_NAME} PROPERTIES TIMEOUT ${T_TIMEOUT} LABELS unit ENVIRONMENT
    "GMMRRT_TEST_DATA_DIR=${GMMRRT_TEST_DATA_DIR};GMMRRT_BIN_DIR=${CMAKE_BINARY_DIR}/bin;GMMRRT_REAL_DATA=${GMMRRT_REAL_DATA}")
endfunction()

# gmmrrt_add_python_test(NAME area.what FILE tests/python/test_x.py)
# Runs one pytest file with the venv's Python, the generated messages and tools/ importable.
function(gmmrrt_add_python_test)
  cmake_parse_arguments(T "" "NAME;FILE;TIMEOUT" "" ${ARGN})
  if(NOT GMMRRT_PYTEST OR NOT T_FILE)
    message(FATAL_ERROR "gmmrrt_add_python_test(${T_NAME}): no pytest command or FILE (include GmmrrtTesting first)")
  endif()
  add_test(NAME ${T_NAME}
           COMMAND ${GMMRRT_VENV_PYTHON} ${GMMRRT_PYTEST} ${T_FILE}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 600)
  endif()
  # Label `python`: the sanitizer pass skips these (the venv's Python is not built with ASan).
  set_tests_properties(${T_NAME} PROPERTIES TIMEOUT ${T_TIMEOUT} LABELS python SKIP_RETURN_CODE 77 ENVIRONMENT
    "PYTHONPATH=${GMMRRT_PYTHONPATH};GMMRRT_BIN_DIR=${CMAKE_BINARY_DIR}/bin;GMMRRT_BUILD_DIR=${CMAKE_BINARY_DIR};GMMRRT_TEST_DATA_DIR=${GMMRRT_TEST_DATA_DIR};GMMRRT_REAL_DATA=${GMMRRT_REAL_DATA};PYTHONDONTWRITEBYTECODE=1")
endfunction()

# gmmrrt_add_missing_test(NAME what WHY text): a test that fails, saying why, in place of a test
# whose build output is missing (never a skip: a broken build must not look green).
function(gmmrrt_add_missing_test)
  cmake_parse_arguments(T "" "NAME;WHY" "" ${ARGN})
  add_test(NAME ${T_NAME} COMMAND sh -c "echo 'FAIL: ${T_WHY}' >&2; exit 1")
endfunction()

