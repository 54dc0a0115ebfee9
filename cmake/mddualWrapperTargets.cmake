# INTERFACE wrappers for the two dependencies of the planning layer that give
# variables, not targets: urdfdom (urdfdom_INCLUDE_DIRS, urdfdom_LIBRARIES,
# console_bridge included) and OMPL 1.5 (OMPL_INCLUDE_DIRS, OMPL_LIBRARIES,
# Boost included). The build (planners/CMakeLists.txt) and the installed
# package config (mddualConfig.cmake, next to which this file is installed)
# both make them with these functions, each right after its find_package(), so
# an installed mddual links the urdfdom and OMPL that the consumer's own
# find_package() finds, wrapped exactly as in the build. They are IMPORTED
# targets: the exported mddual targets name them (mddual::urdfdom,
# mddual::ompl) instead of copying the paths of the machine that built mddual.
# Extra arguments (GLOBAL) go to add_library.

function(mddual_wrap_urdfdom)
  if(NOT TARGET mddual::urdfdom)
    add_library(mddual::urdfdom INTERFACE IMPORTED ${ARGN})
    target_include_directories(mddual::urdfdom SYSTEM INTERFACE ${urdfdom_INCLUDE_DIRS})
    target_link_libraries(mddual::urdfdom INTERFACE ${urdfdom_LIBRARIES})
  endif()
endfunction()

function(mddual_wrap_ompl)
  if(NOT TARGET mddual::ompl)
    add_library(mddual::ompl INTERFACE IMPORTED ${ARGN})
    target_include_directories(mddual::ompl SYSTEM INTERFACE ${OMPL_INCLUDE_DIRS})
    target_link_libraries(mddual::ompl INTERFACE ${OMPL_LIBRARIES})
  endif()
endfunction()
