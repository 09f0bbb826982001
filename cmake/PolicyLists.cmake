# The sizes of the policy lists, read from the headers that declare them
# (`using NAME = PolicyList<A, B, ...>;`), so that the pipeline's units and
# explicit instantiations are generated from the lists themselves
# (pipeline/CMakeLists.txt); the generated header's static_asserts check
# the reading against the C++ lists.
function(metrica_policy_list_size header name out)
  # A changed list configures again (its units and instantiations with it).
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${header}")
  file(READ "${header}" text)
  string(REGEX MATCH "using ${name} = PolicyList<([^;]*)>;" found "${text}")
  if(NOT found)
    message(FATAL_ERROR "${header}: no `using ${name} = PolicyList<...>;` to read the list from")
  endif()
  set(body "${CMAKE_MATCH_1}")
  # The arguments' own template brackets (MetricDelaunay<>) hold no list comma.
  set(before "")
  while(NOT body STREQUAL before)
    set(before "${body}")
    string(REGEX REPLACE "<[^<>]*>" "" body "${body}")
  endwhile()
  string(REGEX MATCHALL "," commas "${body}")
  list(LENGTH commas n)
  math(EXPR n "${n} + 1")
  set(${out} ${n} PARENT_SCOPE)
endfunction()
