# mpirun -n 2 ringcrush sweep … gives the same sweep.csv as one process (timing columns aside).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/grid.toml "base_scene = \"${SOURCE_DIR}/data/scenes/test30_welded.toml\"
model = \"hinge\"
[[axis]]
key = \"hinge.level\"
values = [0, 1]
[[axis]]
key = \"impactor.velocity_m_s\"
values = [15.0, 30.0, 45.0]
")
execute_process(COMMAND ${EXE} sweep ${WORK}/grid.toml -o ${WORK}/one -j 1 RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "single-process sweep failed: ${rc}")
endif()
set(ENV{OMPI_ALLOW_RUN_AS_ROOT} 1)
set(ENV{OMPI_ALLOW_RUN_AS_ROOT_CONFIRM} 1)
execute_process(COMMAND ${MPIEXEC} --oversubscribe -n 2 ${EXE} sweep ${WORK}/grid.toml -o ${WORK}/two -j 1
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mpirun sweep failed: ${rc}\n${out}\n${err}")
endif()
if(NOT out MATCHES "rank 1: 3 run")
  message(FATAL_ERROR "rank 1 did not run its half of the cases:\n${out}")
endif()
# Compare the tables without the columns that measure time.
foreach(run one two)
  file(STRINGS ${WORK}/${run}/sweep.csv lines)
  list(GET lines 0 header)
  string(REPLACE "," ";" names "${header}")
  set(table_${run} "")
  foreach(line IN LISTS lines)
    string(REPLACE "," ";" fields "${line}")
    set(i 0)
    foreach(name IN LISTS names)
      list(GET fields ${i} f)
      if(NOT name MATCHES "wall_time|statistics")
        string(APPEND table_${run} "${f},")
      endif()
      math(EXPR i "${i}+1")
    endforeach()
    string(APPEND table_${run} "\n")
  endforeach()
endforeach()
if(NOT table_one STREQUAL table_two)
  message(FATAL_ERROR "sweep.csv differs between 1 and 2 ranks:\n${table_one}\n---\n${table_two}")
endif()
