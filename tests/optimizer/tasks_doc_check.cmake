# docs/tasks.md holds, word for word, the tables `mrsim-tasks --markdown`
# prints (the task list and every compared gait's fitness on every task),
# so docs that drift from the code fail here instead of misleading.
#
#   cmake -DMRSIM_TASKS=<mrsim-tasks> -DMRSIM_DOC=<docs/tasks.md>
#         [-DMRSIM_TASKS_ARGS=--optimisers] -P tests/optimizer/tasks_doc_check.cmake
#
# MRSIM_TASKS_ARGS: more flags (--optimisers: the optimiser table too).
execute_process(COMMAND ${MRSIM_TASKS} --markdown ${MRSIM_TASKS_ARGS}
  OUTPUT_VARIABLE tables ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mrsim-tasks --markdown failed (${rc}): ${err}")
endif()
file(READ ${MRSIM_DOC} doc)
# The tables are separated by a blank line; the docs have prose between.
set(missing "")
while(NOT tables STREQUAL "")
  string(FIND "${tables}" "\n\n" end)
  if(end EQUAL -1)
    set(table "${tables}")
    set(tables "")
  else()
    math(EXPR end "${end} + 1")
    string(SUBSTRING "${tables}" 0 ${end} table)
    math(EXPR end "${end} + 1")
    string(SUBSTRING "${tables}" ${end} -1 tables)
  endif()
  string(FIND "${doc}" "${table}" at)
  if(at EQUAL -1)
    string(APPEND missing "\n${table}")
  endif()
endwhile()
if(NOT missing STREQUAL "")
  # Unformatted, so it can be pasted as it is.
  message("${missing}")
  message(FATAL_ERROR
    "${MRSIM_DOC} does not hold the tables above as mrsim-tasks --markdown ${MRSIM_TASKS_ARGS} "
    "prints them: paste the command's output over the old tables.")
endif()
