# Warnings, warnings-as-errors and sanitizers applied per target with gmmrrt_target_defaults().
include_guard(GLOBAL)

function(gmmrrt_target_defaults target)
  target_compile_options(${target} PRIVATE
    $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes -Wmissing-prototypes -Wconversion -Wno-sign-conversion>
    $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wshadow>)
  if(GMMRRT_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# Sanitizers apply to everything built in this tree, generated code included.
if(GMMRRT_SANITIZE)
  # float-cast-overflow is not part of gcc's `undefined` group: a double too large for an int
  # is UB all the same (it was reachable from the wire, see docs/hardening.md).
  add_compile_options(-fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined,float-cast-overflow)
  add_link_options(-fsanitize=address,undefined,float-cast-overflow)
endif()

# gmmrrt_ctypes_library(target): a shared library that the Python tools load with ctypes into
# the venv's interpreter, which is not built with the sanitizers: such a library is compiled
# and linked without them in every build, so a sanitizer build's tests can still load it.
function(gmmrrt_ctypes_library target)
  gmmrrt_target_defaults(${target})
  if(GMMRRT_SANITIZE)
    target_compile_options(${target} PRIVATE -fno-sanitize=all)
    target_link_options(${target} PRIVATE -fno-sanitize=all)
  endif()
endfunction()
