# The layers of src/: a library may link libraries of its own layer and of the layers below
# it, never one above (the pure model below the devices, the devices below the products).
#
#   mallet_check_layers(LAYER core-targets... LAYER next-layer-targets... ...)
#
# lists the layers lowest first. A layer opened with APART instead of LAYER holds siblings
# (the products): each may link the layers below, never another of its own layer. Every
# listed target's link libraries (what it links, and what it hands on to its users) are
# checked once all of them are defined; a lower layer's target that links a higher one, or a
# sibling that links a sibling, stops the configure with one line naming both.
function(mallet_check_layers)
  set(layer -1)
  set(known "")
  foreach(token IN LISTS ARGN)
    if(token STREQUAL "LAYER" OR token STREQUAL "APART")
      math(EXPR layer "${layer} + 1")
      if(token STREQUAL "APART")
        set(apart_${layer} ON)
      else()
        set(apart_${layer} OFF)
      endif()
    elseif(layer LESS 0)
      message(FATAL_ERROR "mallet_check_layers: \"${token}\" comes before the first LAYER")
    else()
      set(layer_of_${token} ${layer})
      list(APPEND known ${token})
    endif()
  endforeach()
  foreach(target IN LISTS known)
    if(NOT TARGET ${target})
      message(FATAL_ERROR "mallet_check_layers: ${target} is not a target")
    endif()
    get_target_property(linked ${target} LINK_LIBRARIES)
    get_target_property(handed ${target} INTERFACE_LINK_LIBRARIES)
    foreach(item IN LISTS linked handed)
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" item "${item}")
      if(DEFINED layer_of_${item} AND layer_of_${item} GREATER layer_of_${target})
        message(FATAL_ERROR "layers: ${target} (layer ${layer_of_${target}}) links ${item} (layer "
                            "${layer_of_${item}}): a lower layer may not link a higher one")
      endif()
      set(own ${layer_of_${target}})
      if(DEFINED layer_of_${item} AND NOT item STREQUAL target AND layer_of_${item} EQUAL own AND apart_${own})
        message(FATAL_ERROR "layers: ${target} links ${item}, a sibling of its own layer (${own}): "
                            "siblings may link only the layers below")
      endif()
    endforeach()
  endforeach()
endfunction()
