# visgrab_set_unity_build(<target>): with VISGRAB_UNITY_BUILD on, compile the target's sources in
# batches of VISGRAB_UNITY_BATCH_SIZE files, one compiler run per batch: the shared headers
# (Eigen, gtest, the standard library) are parsed once per batch instead of once per file. Sources
# of one target must therefore not define the same internal name twice (an anonymous-namespace
# helper, a file-scope `using namespace` that makes a name ambiguous, a macro): give such helpers
# distinct names; a source that cannot share a batch gets SKIP_UNITY_BUILD_INCLUSION in its
# folder's CMakeLists.txt, with the reason. A whole target that cannot be built this way is listed
# in VISGRAB_NO_UNITY_TARGETS below, with the reason. visgrab_add_module and visgrab_add_test
# call this.
#
# VISGRAB_NO_UNITY_TARGETS: none at present.
set(VISGRAB_NO_UNITY_TARGETS)
function(visgrab_set_unity_build target)
  if(VISGRAB_UNITY_BUILD AND NOT target IN_LIST VISGRAB_NO_UNITY_TARGETS)
    set_target_properties(${target} PROPERTIES
      UNITY_BUILD ON
      UNITY_BUILD_BATCH_SIZE ${VISGRAB_UNITY_BATCH_SIZE})
  endif()
endfunction()

# visgrab_add_module(<name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...] INCLUDE_ROOT <dir>)
#
# One library target per module. Sources are listed explicitly (no GLOB). A module without
# sources becomes an INTERFACE library. INCLUDE_ROOT is the layer folder (RobWork/, RobWorkSim/,
# VisGraB/) so that headers are included as "rw/math/rpy.hpp", in the build tree and installed.
function(visgrab_add_module name)
  cmake_parse_arguments(ARG "" "INCLUDE_ROOT" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  if(NOT ARG_INCLUDE_ROOT)
    message(FATAL_ERROR "visgrab_add_module(${name}): INCLUDE_ROOT is required")
  endif()
  # Installed, the headers of every layer are under include/visgrab (cmake/VisgrabInstall.cmake).
  set(_include $<BUILD_INTERFACE:${ARG_INCLUDE_ROOT}> $<INSTALL_INTERFACE:include/visgrab>)
  if(ARG_SOURCES)
    add_library(${name} STATIC ${ARG_SOURCES})
    target_include_directories(${name} PUBLIC ${_include})
    target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
    set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    visgrab_set_warnings(${name})
    visgrab_set_unity_build(${name})
  else()
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${_include})
    target_link_libraries(${name} INTERFACE ${ARG_PUBLIC_DEPS})
  endif()
  # Every module is installed and exported (VisGraB::<name>); the layers' umbrella targets are
  # made from this list once all modules exist (visgrab_install_package).
  install(TARGETS ${name} EXPORT VisGraBTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  set_property(GLOBAL APPEND PROPERTY VISGRAB_MODULES ${name})
endfunction()

# visgrab_add_test(<name> SOURCES ... DEPS ... [LABELS ...]): one GoogleTest executable,
# its tests registered individually with CTest. Label "sanitize" marks suites that CI runs again
# under AddressSanitizer+UBSan (target sanitize_tests builds just those).
function(visgrab_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} visgrab_test_support GTest::gtest GTest::gtest_main)
  visgrab_set_warnings(${name})
  visgrab_set_unity_build(${name})
  if(VISGRAB_TEST_PCH)
    # gtest, Eigen and the standard library precompiled once, in tests/support.
    target_precompile_headers(${name} REUSE_FROM visgrab_test_support)
  endif()
  include(GoogleTest)
  gtest_discover_tests(${name}
    PROPERTIES ENVIRONMENT "VISGRAB_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
    DISCOVERY_TIMEOUT 60)
  # gtest_discover_tests flattens a list-valued LABELS property, so the labels are set after
  # discovery from a CTest include file instead.
  if(ARG_LABELS)
    set(_labels_file ${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake)
    file(WRITE ${_labels_file}
      "if(${name}_TESTS)\n"
      "  set_tests_properties(\${${name}_TESTS} PROPERTIES LABELS \"${ARG_LABELS}\")\n"
      "endif()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${_labels_file})
  endif()
  if("sanitize" IN_LIST ARG_LABELS)
    add_dependencies(sanitize_tests ${name})
  endif()
endfunction()

# visgrab_add_benchmark(<name> SOURCES ... DEPS ...): a Google Benchmark program, also registered
# in CTest as a short smoke run (label "benchmark").
function(visgrab_add_benchmark name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} benchmark::benchmark)
  target_compile_definitions(${name} PRIVATE VISGRAB_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  visgrab_set_warnings(${name})
  add_test(NAME ${name}_smoke COMMAND ${name} --benchmark_min_time=0.01)
  set_tests_properties(${name}_smoke PROPERTIES LABELS benchmark)
endfunction()

# visgrab_embed_file(<template.in> <output> <VARIABLE> <file>): configures <template.in> into
# <output> with @VARIABLE@ replaced by the text of <file>, re-run whenever <file> changes. Used to
# compile the XSD schemas into the loaders, so no schema file is needed at run time.
function(visgrab_embed_file template output variable file)
  file(READ ${file} ${variable})
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${file})
  configure_file(${template} ${output} @ONLY)
endfunction()
