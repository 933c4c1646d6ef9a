# mrsim_room_library(<target> PUBLIC <libs>... PRIVATE <libs>...): one room
# of a folder split by role (sim_core/physics, optimizer/search, ...) as its
# own static library from the room's *.cc, with its own include root (see
# include_roots.cmake), installed with its headers under
# include/mrsim/<the room's path>. Rooms link only downward, so an include
# against the arrows does not compile.
function(mrsim_room_library t)
  cmake_parse_arguments(arg "" "" "PUBLIC;PRIVATE" ${ARGN})
  file(GLOB srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  add_library(${t} ${srcs})
  target_include_directories(${t} PUBLIC
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/mrsim>)
  target_link_libraries(${t} PUBLIC ${arg_PUBLIC} PRIVATE ${arg_PRIVATE}
    mrsim_warnings)
  install(TARGETS ${t} EXPORT mrsimTargets ${MRSIM_DEV_INSTALL})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/mrsim/${folder}
    ${MRSIM_DEV_INSTALL} FILES_MATCHING PATTERN "*.h")
endfunction()
