# TERRATIN_SANITIZE: "" (none), "address;undefined" (dev preset) or "thread" (tsan preset).
# Applied to every terratin target through terratin_apply_sanitizers(), not to global flags.
set(TERRATIN_SANITIZE "" CACHE STRING "Sanitizers to build with: address;undefined or thread")

function(terratin_apply_sanitizers target)
  if(NOT TERRATIN_SANITIZE)
    return()
  endif()
  list(JOIN TERRATIN_SANITIZE "," _sanitizers)
  # -g1: line tables are all a sanitizer's stack trace needs, and full debug information
  # doubled the suite's compile time (docs/testing.md).
  target_compile_options(${target} PRIVATE -fsanitize=${_sanitizers} -fno-omit-frame-pointer -g1)
  get_target_property(_type ${target} TYPE)
  if(_type STREQUAL "STATIC_LIBRARY")
    # Instrumented objects need the sanitizer runtimes wherever the archive is linked: in
    # this build, and in a consumer of the installed package (the link option is exported).
    target_link_options(${target} INTERFACE -fsanitize=${_sanitizers})
  else()
    target_link_options(${target} PRIVATE -fsanitize=${_sanitizers})
  endif()
endfunction()
