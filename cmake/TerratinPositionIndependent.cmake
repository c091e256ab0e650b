# The libraries are built position-independent, so that one build serves the executables, a
# consumer's shared library and the Python module (a shared object). -fno-semantic-interposition
# keeps the code the executables run as it is without -fPIC: calls between the library's own
# functions may still be inlined and go direct, as no other object is allowed to replace them.
function(terratin_position_independent target)
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_compile_options(${target} PRIVATE -fno-semantic-interposition)
endfunction()
