# Writes EMBED_OUT: a C++ file defining `extern const char* const EMBED_NAME`
# holding the text of EMBED_IN.
file(READ ${EMBED_IN} text)
file(WRITE ${EMBED_OUT} "extern const char* const ${EMBED_NAME};\nconst char* const ${EMBED_NAME} = R\"stcembed(${text})stcembed\";\n")
