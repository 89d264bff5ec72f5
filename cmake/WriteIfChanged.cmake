# Writes TEXT to PATH only where it differs from what is there: a generated source whose text did
# not change keeps its time, and nothing that includes it is rebuilt (EmbedFiles.cmake,
# CodeDigests.cmake).
function(relieflab_write_if_changed path text)
  if(EXISTS "${path}")
    file(READ "${path}" old)
  else()
    set(old "")
  endif()
  if(NOT old STREQUAL text)
    file(WRITE "${path}" "${text}")
  endif()
endfunction()
