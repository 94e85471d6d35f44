# What `cmake --install BUILD --prefix P` puts under P besides the programs (README "Installing"):
#   lib/                      the static library of every module (rw_*, rwsim_*, visgrab_*)
#   include/visgrab/          their headers, included as "rw/...", "rwsim/...", "visgrab/..."
#   share/visgrab/scenes      hands, objects, cameras, materials: the programs' default data
#   share/visgrab/xml         the XSD schemas
#   lib/cmake/VisGraB         the CMake package: find_package(VisGraB) gives VisGraB::<module> and
#                             one umbrella target per layer, VisGraB::rw, VisGraB::rwsim and
#                             VisGraB::visgrab, each linking all of its layer's modules.
#   lib/python3/dist-packages/visgrab   the Python module (VISGRAB_BUILD_PYTHON), in Debian's
#                             layout: PYTHONPATH=P/lib/python3/dist-packages (docs/python.md)
include(CMakePackageConfigHelpers)

# Where the Python package goes, relative to the prefix (Debian's layout for the system Python).
set(VISGRAB_PYTHON_INSTALL_DIR lib/python3/dist-packages CACHE STRING
  "Install folder of the Python package visgrab, relative to CMAKE_INSTALL_PREFIX")

# visgrab_install_package(): called once, after every module is defined.
function(visgrab_install_package)
  get_property(modules GLOBAL PROPERTY VISGRAB_MODULES)
  foreach(layer rw rwsim visgrab)
    set(members)
    foreach(module ${modules})
      if(module MATCHES "^${layer}_")
        list(APPEND members ${module})
      endif()
    endforeach()
    # The executable `visgrab` has the layer's name, so the umbrella targets get theirs only when
    # exported; in the build tree they are VisGraB::<layer> aliases, as for a consumer.
    add_library(visgrab_layer_${layer} INTERFACE)
    target_link_libraries(visgrab_layer_${layer} INTERFACE ${members})
    set_target_properties(visgrab_layer_${layer} PROPERTIES EXPORT_NAME ${layer})
    add_library(VisGraB::${layer} ALIAS visgrab_layer_${layer})
    install(TARGETS visgrab_layer_${layer} EXPORT VisGraBTargets)
  endforeach()

  set(package_dir ${CMAKE_INSTALL_LIBDIR}/cmake/VisGraB)
  install(EXPORT VisGraBTargets NAMESPACE VisGraB:: DESTINATION ${package_dir})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/VisGraBConfig.cmake.in
    ${PROJECT_BINARY_DIR}/VisGraBConfig.cmake INSTALL_DESTINATION ${package_dir})
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/VisGraBConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/VisGraBConfig.cmake
    ${PROJECT_BINARY_DIR}/VisGraBConfigVersion.cmake DESTINATION ${package_dir})

  foreach(layer_dir RobWork/rw RobWorkSim/rwsim VisGraB/visgrab)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/${layer_dir}
      DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/visgrab FILES_MATCHING PATTERN "*.hpp")
  endforeach()
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/
    DESTINATION ${CMAKE_INSTALL_DATADIR}/visgrab/scenes)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/xml/ DESTINATION ${CMAKE_INSTALL_DATADIR}/visgrab/xml)
endfunction()
