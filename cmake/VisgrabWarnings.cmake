# Warning flags shared by every project target (not by third-party code).
set(VISGRAB_WARNING_FLAGS -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
    -Wold-style-cast -Wcast-align -Woverloaded-virtual
    -Wimplicit-fallthrough)
if(VISGRAB_WERROR)
  list(APPEND VISGRAB_WARNING_FLAGS -Werror)
endif()

# visgrab_set_warnings(<target>): apply the project warnings to a target.
function(visgrab_set_warnings target)
  target_compile_options(${target} PRIVATE ${VISGRAB_WARNING_FLAGS})
endfunction()
