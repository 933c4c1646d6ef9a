# Installs the libraries, headers, generated message types and a CMake
# package so another project can find_package(mrsim).
include(CMakePackageConfigHelpers)

# Exported names drop the mrsim_ prefix, as the build tree's aliases do:
# mrsim::sim_core, mrsim::sim_bridge, mrsim::gait_lcm, mrsim::optimizer_farm...
foreach(lib common sim_core codec sim_bridge gait gait_lcm optimizer optimizer_farm
            logger viewer lcmtypes runtime warnings)
  set_target_properties(mrsim_${lib} PROPERTIES EXPORT_NAME ${lib})
endforeach()

set(MRSIM_EXTRA_DEPENDENCIES "")
if(Pagmo_FOUND)
  set(MRSIM_EXTRA_DEPENDENCIES "find_dependency(Pagmo)")
endif()

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/mrsim)
install(EXPORT mrsimTargets NAMESPACE mrsim:: DESTINATION ${config_dir} ${MRSIM_DEV_INSTALL})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/mrsimConfig.cmake.in
  ${PROJECT_BINARY_DIR}/mrsimConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/mrsimConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/mrsimConfig.cmake
  ${PROJECT_BINARY_DIR}/mrsimConfigVersion.cmake DESTINATION ${config_dir} ${MRSIM_DEV_INSTALL})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenarios/ DESTINATION ${CMAKE_INSTALL_DATADIR}/mrsim/scenarios)
# The documentation beside the data, so an installed mrsim (the Debian
# package, scripts/package.sh) has it offline; README's links to docs/
# still resolve from share/mrsim/README.md.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/mrsim/docs)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DATADIR}/mrsim)
# The Slurm batch script for farm workers started by hand, so a cluster
# with mrsim installed on its nodes needs no source tree.
install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/slurm/mrsim-worker.sbatch
  DESTINATION ${CMAKE_INSTALL_DATADIR}/mrsim/slurm)
