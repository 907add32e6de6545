# Writes a C++ file embedding text files as string literals.
#   EMBED_OUT   output .cpp
#   EMBED_ROOT  directory the names are relative to
#   (embeds every EMBED_ROOT/iec/*.st, sorted)
file(GLOB EMBED_FILES ${EMBED_ROOT}/iec/*.st)
list(SORT EMBED_FILES)
set(body "#include <cstddef>\nnamespace stc {\nstruct EmbeddedSource { const char* name; const char* text; };\nextern const EmbeddedSource kStdlibSources[] = {\n")
set(count 0)
foreach(f ${EMBED_FILES})
  file(READ ${f} content)
  file(RELATIVE_PATH rel ${EMBED_ROOT} ${f})
  string(APPEND body "  {\"<stdlib>/${rel}\", R\"STCEMBED(${content})STCEMBED\"},\n")
  math(EXPR count "${count} + 1")
endforeach()
string(APPEND body "};\nextern const size_t kStdlibSourceCount = ${count};\n}  // namespace stc\n")
file(WRITE ${EMBED_OUT}.tmp "${body}")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${EMBED_OUT}.tmp ${EMBED_OUT})
