# Layering enforced by the build. Sources include project headers by their
# path from the repository root ("sim_core/scenario/scenario.h"), but the repository
# root is on no target's include path. Instead each source folder has its
# own include root in the build tree,
#   <build>/include_roots/<folder, / as +>/<folder>/<header>.h
# holding a symbolic link to each header of that folder (not of its
# subfolders: sim_core/sim_process is another library than sim_core).
# Every target sees its own folder's root; a library publishes it to the
# targets that link it. So "sim_core/scenario/scenario.h" compiles only in a target
# that is in sim_core/ or links mrsim::sim_core, directly or through another
# library's public dependencies. See docs/architecture.md.
set(MRSIM_INCLUDE_ROOTS ${PROJECT_BINARY_DIR}/include_roots)

# The include root of <folder> (relative to the repository root) in <out>;
# its links are made (and links to removed headers dropped) once per
# configure. A header added later re-runs the configure (CONFIGURE_DEPENDS).
function(mrsim_folder_root folder out)
  string(REPLACE "/" "+" key "${folder}")
  set(root ${MRSIM_INCLUDE_ROOTS}/${key})
  get_property(done GLOBAL PROPERTY mrsim_include_root_${key} SET)
  if(NOT done)
    set(src ${PROJECT_SOURCE_DIR}/${folder})
    set(dst ${root}/${folder})
    if(NOT IS_DIRECTORY ${src})
      message(FATAL_ERROR "mrsim_folder_root: no folder ${src}")
    endif()
    file(GLOB headers CONFIGURE_DEPENDS RELATIVE ${src} ${src}/*.h ${src}/*.hpp)
    file(MAKE_DIRECTORY ${dst})
    file(GLOB existing LIST_DIRECTORIES false RELATIVE ${dst} ${dst}/*)
    foreach(name ${existing})
      if(IS_SYMLINK ${dst}/${name} AND NOT name IN_LIST headers)
        file(REMOVE ${dst}/${name})
      endif()
    endforeach()
    foreach(h ${headers})
      file(CREATE_LINK ${src}/${h} ${dst}/${h} SYMBOLIC)
    endforeach()
    set_property(GLOBAL PROPERTY mrsim_include_root_${key} TRUE)
  endif()
  set(${out} ${root} PARENT_SCOPE)
endfunction()

# mrsim_include_root(<target> <PUBLIC|PRIVATE|INTERFACE> <folder>...): the
# target (and, unless PRIVATE, its users) may include the folders' headers.
# For the few targets that are not in the folder they expose (an INTERFACE
# library of header-only test helpers).
function(mrsim_include_root target scope)
  foreach(folder ${ARGN})
    mrsim_folder_root(${folder} root)
    target_include_directories(${target} ${scope} $<BUILD_INTERFACE:${root}>)
  endforeach()
endfunction()

# Gives every target under <dir> the root of its own folder: PUBLIC for a
# library, PRIVATE for a program. Called once, after every add_subdirectory.
function(mrsim_add_own_include_roots dir)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(t ${targets})
    get_target_property(type ${t} TYPE)
    get_target_property(src ${t} SOURCE_DIR)
    file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR} ${src})
    if(folder STREQUAL "")
      continue()
    elseif(type MATCHES "^(STATIC|SHARED|MODULE|OBJECT)_LIBRARY$")
      mrsim_include_root(${t} PUBLIC ${folder})
    elseif(type STREQUAL "EXECUTABLE")
      mrsim_include_root(${t} PRIVATE ${folder})
    endif()
  endforeach()
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(sub ${subdirs})
    mrsim_add_own_include_roots(${sub})
  endforeach()
endfunction()
