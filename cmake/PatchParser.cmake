# Post-processes the generated parser (PARSER_CPP): every prediction calls
# getInterpreter<ParserATNSimulator>(), a dynamic_cast; the interpreter of our
# parser is always a ParserATNSimulator, so a static_cast is equivalent.
file(READ ${PARSER_CPP} content)
string(REPLACE "getInterpreter<atn::ParserATNSimulator>()" "static_cast<atn::ParserATNSimulator *>(_interpreter)" content "${content}")
file(WRITE ${PARSER_CPP} "${content}")
