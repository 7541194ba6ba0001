# A program's shared libraries, checked once it is linked:
#
#   mallet_refuse_needed(TARGET prefix...)
#
# reads the linked TARGET's dynamic section (readelf -d) after every link and fails the build,
# naming the library and the prefix, when one of its NEEDED entries starts with a prefix
# ("libjack" refuses libjack.so.0), and removes the refused program so that the next build
# links it again. What the program loads through another library (Debian's
# PortAudio and FluidSynth need libjack themselves) is that library's, not the program's.
if(NOT CMAKE_READELF)
  find_program(CMAKE_READELF readelf REQUIRED)
endif()

function(mallet_refuse_needed target)
  add_custom_command(TARGET ${target} POST_BUILD
    COMMAND ${CMAKE_COMMAND} -DREADELF=${CMAKE_READELF} -DBINARY=$<TARGET_FILE:${target}>
            "-DREFUSED=${ARGN}" -DREMOVE_REFUSED=ON -P ${PROJECT_SOURCE_DIR}/cmake/check_needed.cmake
    COMMENT "${target}: needs none of ${ARGN}"
    VERBATIM)
endfunction()
