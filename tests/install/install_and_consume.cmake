# cmake -P script: install, configure and build the consumer, run it. Fails on the first error.
function(run_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "step failed (${status}): ${ARGN}\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${PREFIX} ${CONSUMER_BUILD})
run_step(${CMAKE_COMMAND} --install ${POSEKIT_BUILD_DIR} --prefix ${PREFIX})
run_step(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${CONSUMER_BUILD} -G ${GENERATOR}
         -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${PREFIX})
run_step(${CMAKE_COMMAND} --build ${CONSUMER_BUILD})
run_step(${POSEKIT_CLI} generate --output-dir ${CONSUMER_BUILD}/poses)
run_step(${CONSUMER_BUILD}/consumer ${CONSUMER_BUILD}/poses/arm-rest.obj)
if(NOT step_output MATCHES "^0 self-intersecting faces" OR NOT step_output MATCHES "cpu: available")
  message(FATAL_ERROR "unexpected consumer output:\n${step_output}")
endif()
message(STATUS "consumer output:\n${step_output}")

# The Python package, where it was built: importable from the prefix, forwarding to the prefix's tool.
if(PYTHON AND EXISTS ${PREFIX}/${PYTHON_PACKAGES}/posekit)
  run_step(${CMAKE_COMMAND} -E env PYTHONPATH=${PREFIX}/${PYTHON_PACKAGES}
           ${PYTHON} -c "import posekit; assert any(d['name'] == 'cpu' for d in posekit.devices())")
  run_step(${CMAKE_COMMAND} -E env PYTHONPATH=${PREFIX}/${PYTHON_PACKAGES} ${PYTHON} -m posekit --version)
  if(NOT step_output MATCHES "^posekit ")
    message(FATAL_ERROR "python3 -m posekit --version printed:\n${step_output}")
  endif()
  message(STATUS "Python package imported from ${PREFIX}/${PYTHON_PACKAGES}")
endif()
