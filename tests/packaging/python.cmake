# The Python package as a user installs it, offline: an sdist made from bindings/python (which
# carries the library's sources under native/), built into a wheel by pip with Debian's
# setuptools and wheel (--no-build-isolation --no-index), installed into fresh virtual
# environments; the example and the test suite then run outside the repository with no
# RAPS_LIBRARY, loading the libraps.so inside the package. A source file missing from the sdist
# fails the wheel's build here.
file(REMOVE_RECURSE ${WORK_DIR})

include(${CMAKE_CURRENT_LIST_DIR}/../run_step.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/package_root.cmake)

# Nothing from the repository or the build tree may reach the installed package.
set(clean_env ${CMAKE_COMMAND} -E env --unset=RAPS_LIBRARY --unset=PYTHONPATH
    --unset=LD_LIBRARY_PATH --unset=RAPS_SOURCE_DIR PYTHONDONTWRITEBYTECODE=1 PIP_NO_CACHE_DIR=1
    PIP_DISABLE_PIP_VERSION_CHECK=1)

# A venv that sees Debian's setuptools, wheel and numpy, and one that sees nothing.
run(${PYTHON} -m venv --system-site-packages ${WORK_DIR}/venv)
run(${PYTHON} -m venv ${WORK_DIR}/venv-bare)
set(python ${WORK_DIR}/venv/bin/python)

# The sdist, from a copy of bindings/python (setuptools writes its egg-info beside setup.py,
# and tests write nothing into the source tree); RAPS_SOURCE_DIR says where the library's
# sources are, which the sdist copies under native/.
file(COPY ${SOURCE_DIR}/bindings/python/ DESTINATION ${WORK_DIR}/python
     PATTERN __pycache__ EXCLUDE PATTERN build EXCLUDE PATTERN *.egg-info EXCLUDE
     PATTERN libraps.so EXCLUDE)
run(${CMAKE_COMMAND} -E chdir ${WORK_DIR}/python ${clean_env} RAPS_SOURCE_DIR=${SOURCE_DIR}
    ${python} -c "import sys\nfrom setuptools import build_meta\nbuild_meta.build_sdist(sys.argv[1])"
    ${WORK_DIR}/dist)
file(GLOB sdist ${WORK_DIR}/dist/raps-*.tar.gz)
if(NOT sdist)
  message(FATAL_ERROR "no sdist in ${WORK_DIR}/dist")
endif()
# Unpacked here rather than by pip into a random folder, and built at PACKAGE_ROOT, so that the
# compiler launcher's cache (ccache) sees the same paths as the other package builds.
file(MAKE_DIRECTORY ${WORK_DIR}/sdist)
run(${CMAKE_COMMAND} -E chdir ${WORK_DIR}/sdist ${CMAKE_COMMAND} -E tar xzf ${sdist})
file(GLOB unpacked LIST_DIRECTORIES true ${WORK_DIR}/sdist/raps-*)
package_root_claim(${unpacked})

list(JOIN package_cmake_args " " cmake_args)
run(${clean_env} ${package_build_env} "RAPS_CMAKE_ARGS=${cmake_args}"
    CMAKE_BUILD_PARALLEL_LEVEL=${JOBS}
    ${python} -m pip wheel --no-build-isolation --no-index --no-deps -w ${WORK_DIR}/wheels
    ${PACKAGE_ROOT})
file(GLOB wheel ${WORK_DIR}/wheels/raps-*.whl)
if(NOT wheel MATCHES "-py3-none-linux_[a-z0-9_]+\\.whl$")
  message(FATAL_ERROR "the wheel is not tagged for this platform: ${wheel}")
endif()
# (Python code in newlines, not semicolons, which CMake would take for list separators.)
run(${python} -c "import sys, zipfile\nnames = zipfile.ZipFile(sys.argv[1]).namelist()\n\
sys.exit(0 if 'raps/libraps.so' in names else 'no raps/libraps.so in the wheel: %s' % names)"
    ${wheel})

# Installed offline into both environments, then used from outside the repository.
file(MAKE_DIRECTORY ${WORK_DIR}/run)
file(COPY ${SOURCE_DIR}/bindings/python/example.py DESTINATION ${WORK_DIR}/run)
foreach(venv venv venv-bare)
  run(${clean_env} ${WORK_DIR}/${venv}/bin/python -m pip install --no-index --no-deps ${wheel})
  run(${CMAKE_COMMAND} -E chdir ${WORK_DIR}/run ${clean_env}
      ${WORK_DIR}/${venv}/bin/python example.py)
  message(STATUS "${venv}: example.py: ${last_output}")
endforeach()
# The whole suite once, with numpy (python_plain runs it without, against the build tree).
run(${CMAKE_COMMAND} -E chdir ${WORK_DIR}/run ${clean_env} RAPS_TEST_INSTALLED=1
    RAPS_SHARED_DATA_DIR=${DATA_DIR}
    ${python} ${SOURCE_DIR}/bindings/python/tests/test_raps.py)
