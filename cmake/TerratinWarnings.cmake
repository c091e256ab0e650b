# Warning flags applied per target (never through the global CMAKE_CXX_FLAGS).
# -Wnull-dereference is left out: GCC 12 reports it for std::vector inside Boost and the
# standard library at -O2, with no way to act on it in our code.
function(terratin_set_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
    -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual)
endfunction()
