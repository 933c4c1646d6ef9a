# Fuzz targets. Each target <t> is fuzz/<t>_fuzz.cc defining
# LLVMFuzzerTestOneInput. It is built twice:
#  - always, with the normal compiler, as <t>_replay: a program that feeds
#    every file of fuzz/corpus/<t>/ and fuzz/regressions/<t>/ to the target,
#    run by ctest as the unit test fuzz_replay.<t> (so every crash ever found
#    stays fixed, in every build including the sanitizer one);
#  - with -DMRSIM_FUZZ=ON (clang), as <t>_fuzz: the libFuzzer program that
#    scripts/fuzz.sh runs.
set(MRSIM_FUZZ_DIR ${PROJECT_SOURCE_DIR}/fuzz)

function(mrsim_add_fuzz_target name)
  cmake_parse_arguments(arg "" "" "SOURCES;LIBS" ${ARGN})
  if(NOT arg_SOURCES)
    set(arg_SOURCES ${name}_fuzz.cc)
  endif()
  add_executable(${name}_replay ${arg_SOURCES} ${MRSIM_FUZZ_DIR}/replay_main.cc)
  target_link_libraries(${name}_replay PRIVATE ${arg_LIBS} mrsim_warnings)
  add_test(NAME fuzz_replay.${name}
    COMMAND ${name}_replay ${MRSIM_FUZZ_DIR}/corpus/${name}
            ${MRSIM_FUZZ_DIR}/regressions/${name})
  set_tests_properties(fuzz_replay.${name} PROPERTIES LABELS unit)
  set_property(GLOBAL APPEND PROPERTY MRSIM_FUZZ_REPLAYS ${name}_replay)
  if(MRSIM_FUZZ)
    add_executable(${name}_fuzz ${arg_SOURCES})
    target_link_libraries(${name}_fuzz PRIVATE ${arg_LIBS})
    target_link_options(${name}_fuzz PRIVATE -fsanitize=fuzzer)
    add_dependencies(mrsim_fuzz_targets ${name}_fuzz)
  endif()
endfunction()
