# Helpers for the scripts that embed text files in C++ sources (nodes/embed.cmake,
# runtime/shaders/embed_shaders.cmake), run with `cmake -P`.

# Sets OUT to TEXT as a C++ string literal: raw string chunks with DELIMITER, each below
# compilers' literal length limits (MSVC's is 16 KB), or "" for an empty text.
function(embed_raw_string_literal OUT TEXT DELIMITER)
  string(LENGTH "${TEXT}" length)
  set(chunks "")
  set(offset 0)
  while(offset LESS length)
    string(SUBSTRING "${TEXT}" ${offset} 8000 chunk)
    string(APPEND chunks "R\"${DELIMITER}(${chunk})${DELIMITER}\" ")
    math(EXPR offset "${offset} + 8000")
  endwhile()
  if(chunks STREQUAL "")
    set(chunks "\"\"")
  endif()
  set(${OUT} "${chunks}" PARENT_SCOPE)
endfunction()

# Writes CONTENT to FILE, leaving the file (and its time stamp, so nothing rebuilds) as it is
# when it already holds CONTENT.
function(embed_write_if_different FILE CONTENT)
  file(WRITE ${FILE}.tmp "${CONTENT}")
  file(COPY_FILE ${FILE}.tmp ${FILE} ONLY_IF_DIFFERENT)
  file(REMOVE ${FILE}.tmp)
endfunction()
