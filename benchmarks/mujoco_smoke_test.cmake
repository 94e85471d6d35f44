# Smoke test of mujoco_comparison_benchmark (cmake -DPROGRAM=... -P mujoco_smoke_test.cmake): a
# few trials per benchmark; passes when the program exits 0 (GraspTrial held the box, stable or
# slipped, in every trial on both engines) and printed both ratio lines. No timing is checked.
execute_process(COMMAND ${PROGRAM} --benchmark_min_time=0.15
  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "mujoco_comparison_benchmark exited with ${result}")
endif()
foreach(line "ratio with Q_GWS: [0-9.]+" "ratio without Q_GWS: [0-9.]+")
  if(NOT out MATCHES "${line}")
    message(FATAL_ERROR "mujoco_comparison_benchmark did not print '${line}'")
  endif()
endforeach()
