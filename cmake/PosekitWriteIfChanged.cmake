# posekit_write_if_changed(FILE CONTENT): writes CONTENT to FILE unless FILE already holds it, so that
# a generated source whose inputs did not change does not rebuild what uses it. For -P scripts.
function(posekit_write_if_changed file content)
  if(EXISTS "${file}")
    file(READ "${file}" previous)
    if(previous STREQUAL content)
      return()
    endif()
  endif()
  file(WRITE "${file}" "${content}")
endfunction()
