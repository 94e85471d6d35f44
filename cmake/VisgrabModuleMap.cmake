# visgrab_write_module_map(<file>): writes, at configure time, every target built from this source
# tree as JSON: name, type, source folder, sources, include folders and link items (PUBLIC ones
# and all direct ones). scripts/check-includes.py reads it to check that each target includes
# only headers of the targets it links (CTest test include_graph). Written only when it changes.
function(_visgrab_targets_below dir out)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(sub IN LISTS subdirs)
    _visgrab_targets_below(${sub} below)
    list(APPEND targets ${below})
  endforeach()
  set(${out} ${targets} PARENT_SCOPE)
endfunction()

# A CMake list as a JSON array of strings.
function(_visgrab_json_array out)
  set(items)
  foreach(item IN LISTS ARGN)
    string(REPLACE "\\" "\\\\" item "${item}")
    string(REPLACE "\"" "\\\"" item "${item}")
    list(APPEND items "\"${item}\"")
  endforeach()
  list(JOIN items ", " joined)
  set(${out} "[${joined}]" PARENT_SCOPE)
endfunction()

function(visgrab_write_module_map file)
  _visgrab_targets_below(${PROJECT_SOURCE_DIR} targets)
  set(entries)
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(NOT type MATCHES "^(STATIC_LIBRARY|SHARED_LIBRARY|OBJECT_LIBRARY|INTERFACE_LIBRARY|EXECUTABLE)$")
      continue()
    endif()
    # The layers' umbrella targets of the installed package (VisgrabInstall.cmake) own no files;
    # nothing in the tree links them.
    if(target MATCHES "^visgrab_layer_")
      continue()
    endif()
    get_target_property(dir ${target} SOURCE_DIR)
    set(fields)
    foreach(property SOURCES INCLUDE_DIRECTORIES INTERFACE_INCLUDE_DIRECTORIES LINK_LIBRARIES
        INTERFACE_LINK_LIBRARIES)
      get_target_property(value ${target} ${property})
      if(NOT value)
        set(value)
      endif()
      _visgrab_json_array(array ${value})
      list(APPEND fields "\"${property}\": ${array}")
    endforeach()
    list(JOIN fields ",\n     " joined)
    list(APPEND entries
      "    {\"name\": \"${target}\", \"type\": \"${type}\", \"source_dir\": \"${dir}\",\n     ${joined}}")
  endforeach()
  list(JOIN entries ",\n" body)
  file(CONFIGURE OUTPUT ${file}
    CONTENT "{\n  \"source_dir\": \"${PROJECT_SOURCE_DIR}\",\n  \"targets\": [\n${body}\n  ]\n}\n"
    @ONLY)
endfunction()
