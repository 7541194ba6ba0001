# cmake -DREADELF=... -DBINARY=... -DREFUSED="prefix;..." [-DREMOVE_REFUSED=ON] -P check_needed.cmake
# (MalletNeeded.cmake): fails when BINARY's dynamic section needs a library named REFUSED*.
# REMOVE_REFUSED (the build's own check): the refused binary is removed too, so that the next
# build links it again (ninja would otherwise take the refused file for up to date).
execute_process(COMMAND ${READELF} -d ${BINARY} OUTPUT_VARIABLE dynamic RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${BINARY}: readelf -d failed (${status})")
endif()
string(REGEX MATCHALL "\\(NEEDED\\)[^\n]*\\[[^]\n]+\\]" entries "${dynamic}")
set(needed "")
foreach(entry IN LISTS entries)
  string(REGEX REPLACE ".*\\[([^]]+)\\]$" "\\1" library "${entry}")
  list(APPEND needed ${library})
endforeach()
if(needed STREQUAL "")
  message(FATAL_ERROR "${BINARY}: no NEEDED entries read (readelf -d printed nothing this check understands)")
endif()
foreach(library IN LISTS needed)
  foreach(prefix IN LISTS REFUSED)
    string(FIND "${library}" "${prefix}" at)
    if(at EQUAL 0)
      if(REMOVE_REFUSED)
        file(REMOVE ${BINARY})
      endif()
      message(FATAL_ERROR "${BINARY} needs ${library}: this program may not link ${prefix}* "
                          "(only the benchmarks' program, mallet-bench, does)")
    endif()
  endforeach()
endforeach()
