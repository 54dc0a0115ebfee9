# cmake -P script for ctest python.install: installs the "python" component
# into a scratch prefix, then imports mddual from there (with no other path
# to the module: run from the scratch folder, not the build's module folder)
# and runs one query.
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --component python --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install of component python failed (${rc}):\n${out}\n${err}")
endif()
set(probe "import os, sys, mddual, numpy as np
expected = os.path.realpath(sys.argv[1])
assert os.path.dirname(os.path.realpath(mddual.__file__)) == expected, (mddual.__file__, expected)
cube = mddual.ConvexPolytope(np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float))
X = np.eye(4); X[0, 3] = 3.0
d = mddual.mdd(cube, None, cube, X, [-1, 0, 0]).distance
assert abs(d - 2.0) < 1e-12, d
print('installed module OK:', mddual.__file__)")
execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${WORK_DIR}/prefix/${MODULE_DIR} PYTHONNOUSERSITE=1
                        ${PYTHON} -c "${probe}" ${WORK_DIR}/prefix/${MODULE_DIR}
                WORKING_DIRECTORY ${WORK_DIR}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed module does not work (${rc}):\n${out}\n${err}")
endif()
message(STATUS "${out}")
