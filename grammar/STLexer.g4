// IEC 61131-3 (3rd edition) Structured Text lexer with the CODESYS V2.3/V3
// extensions.  Keywords and identifiers are case-insensitive; the tool is
// ANTLR 4.7 (no caseInsensitive option), so keywords are spelled with
// single-letter fragments.  Pragmas and comments go to hidden channels; the
// pragma pass (compiler/parse/Pragmas.cpp) evaluates {IF ...} blocks before
// the parser sees the tokens.
lexer grammar STLexer;

channels { COMMENTS, PRAGMAS }


// ---- keywords (longest match beats IDENTIFIER because they are listed first)
ABSTRACT : A B S T R A C T ;
ACTION : A C T I O N ;
END_ACTION : E N D '_' A C T I O N ;
AND : A N D ;
AND_THEN : A N D '_' T H E N ;
ARRAY : A R R A Y ;
AT : A T ;
BY : B Y ;
CASE : C A S E ;
END_CASE : E N D '_' C A S E ;
CONFIGURATION : C O N F I G U R A T I O N ;
END_CONFIGURATION : E N D '_' C O N F I G U R A T I O N ;
CONSTANT : C O N S T A N T ;
CONTINUE : C O N T I N U E ;
DO : D O ;
ELSE : E L S E ;
ELSIF : E L S I F ;
END_FOR : E N D '_' F O R ;
END_IF : E N D '_' I F ;
END_REPEAT : E N D '_' R E P E A T ;
END_WHILE : E N D '_' W H I L E ;
EXIT : E X I T ;
EXTENDS : E X T E N D S ;
FALSE : F A L S E ;
FINAL : F I N A L ;
FOR : F O R ;
FUNCTION : F U N C T I O N ;
END_FUNCTION : E N D '_' F U N C T I O N ;
// FUNCTIONBLOCK / END_FUNCTIONBLOCK: the spelling of some CoDeSys 2.3 exports.
FUNCTION_BLOCK : F U N C T I O N '_'? B L O C K ;
END_FUNCTION_BLOCK : E N D '_' F U N C T I O N '_'? B L O C K ;
END_GET : E N D '_' G E T ;
END_SET : E N D '_' S E T ;
IF : I F ;
IMPLEMENTS : I M P L E M E N T S ;
INTERFACE : I N T E R F A C E ;
END_INTERFACE : E N D '_' I N T E R F A C E ;
INTERNAL : I N T E R N A L ;
JMP : J M P ;
METHOD : M E T H O D ;
END_METHOD : E N D '_' M E T H O D ;
MOD : M O D ;
NAMESPACE : N A M E S P A C E ;
END_NAMESPACE : E N D '_' N A M E S P A C E ;
NON_RETAIN : N O N '_' R E T A I N ;
NOT : N O T ;
OF : O F ;
OR : O R ;
OR_ELSE : O R '_' E L S E ;
PERSISTENT : P E R S I S T E N T ;
POINTER : P O I N T E R ;
PRIVATE : P R I V A T E ;
PROGRAM : P R O G R A M ;
END_PROGRAM : E N D '_' P R O G R A M ;
PROPERTY : P R O P E R T Y ;
END_PROPERTY : E N D '_' P R O P E R T Y ;
PROTECTED : P R O T E C T E D ;
PUBLIC : P U B L I C ;
REFERENCE : R E F E R E N C E ;
REF_TO : R E F '_' T O ;
REPEAT : R E P E A T ;
RESOURCE : R E S O U R C E ;
END_RESOURCE : E N D '_' R E S O U R C E ;
RETAIN : R E T A I N ;
RETURN : R E T U R N ;
STRUCT : S T R U C T ;
END_STRUCT : E N D '_' S T R U C T ;
SUPER : S U P E R ;
TASK : T A S K ;
THEN : T H E N ;
THIS : T H I S ;
TO : T O ;
TRUE : T R U E ;
TYPE : T Y P E ;
END_TYPE : E N D '_' T Y P E ;
UNION : U N I O N ;
END_UNION : E N D '_' U N I O N ;
UNTIL : U N T I L ;
VAR : V A R ;
VAR_ACCESS : V A R '_' A C C E S S ;
VAR_CONFIG : V A R '_' C O N F I G ;
VAR_EXTERNAL : V A R '_' E X T E R N A L ;
VAR_GLOBAL : V A R '_' G L O B A L ;
VAR_INPUT : V A R '_' I N P U T ;
VAR_IN_OUT : V A R '_' I N '_' O U T ;
VAR_INST : V A R '_' I N S T ;
VAR_OUTPUT : V A R '_' O U T P U T ;
VAR_STAT : V A R '_' S T A T ;
VAR_TEMP : V A R '_' T E M P ;
END_VAR : E N D '_' V A R ;
WHILE : W H I L E ;
// R_EDGE / F_EDGE: input qualifiers (IEC keywords).
R_EDGE : R '_' E D G E ;
F_EDGE : F '_' E D G E ;
WITH : W I T H ;
XOR : X O R ;

// REF= is CODESYS's reference assignment.  S= and R= are parsed as
// IDENTIFIER '=' in the parser, so that S and R stay usable as names.
REF_ASSIGN : R E F '=' ;

// ---- literals
// Time and date literals: the prefix decides the kind; the body is checked
// and converted by the AST builder, which reports malformed values.
TIME_LITERAL : ( T | L T | T I M E | L T I M E ) '#' '-'? TIME_BODY ;
// Parts may be separated by '_' (IEC examples: T#1h_30m, t#5d_14h_12m_18s_3.5ms).
fragment TIME_BODY : TIME_PART ( '_'? TIME_PART )* ;
fragment TIME_PART : [0-9] [0-9_]* ( '.' [0-9_]+ )? [a-zA-Z]+ ;
DATE_TIME_LITERAL : ( D T | L D T | D A T E '_' A N D '_' T I M E | L D A T E '_' A N D '_' T I M E ) '#' [0-9] [0-9_]* '-' [0-9]+ '-' [0-9]+ '-' [0-9]+ ':' [0-9]+ ( ':' [0-9]+ ( '.' [0-9]+ )? )? ;
DATE_LITERAL : ( D | L D | D A T E | L D A T E ) '#' [0-9] [0-9_]* '-' [0-9]+ '-' [0-9]+ ;
TOD_LITERAL : ( T O D | L T O D | T I M E '_' O F '_' D A Y | L T I M E '_' O F '_' D A Y ) '#' [0-9]+ ':' [0-9]+ ( ':' [0-9]+ ( '.' [0-9]+ )? )? ;

REAL_LITERAL : DIGITS '.' DIGITS EXPONENT? | DIGITS EXPONENT ;
BASED_LITERAL : ( '2' | '8' | '16' ) '#' [0-9a-zA-Z_]+ ;
INTEGER_LITERAL : DIGITS ;
fragment DIGITS : [0-9] ( '_'? [0-9] )* ;
fragment EXPONENT : [eE] [+-]? [0-9]+ ;

STRING_LITERAL : '\'' ( '$' . | ~[$'\r\n] )* '\'' ;
WSTRING_LITERAL : '"' ( '$' . | ~[$"\r\n] )* '"' ;
// Without the closing quote (the terminated form is always one longer and wins).
UNTERMINATED_STRING : '\'' ( '$' . | ~[$'\r\n] )* | '"' ( '$' . | ~[$"\r\n] )* ;

// %IX0.1, %QW4, %MD10, %I*, %Q*
DIRECT_ADDRESS : '%' [iIqQmM] [xXbBwWdDlL]? ( [0-9]+ ( '.' [0-9]+ )* | '*' ) ;
// x.%X3 (partial access)
PARTIAL_ACCESS : '%' [xXbBwWdD] [0-9]+ ;

IDENTIFIER : [a-zA-Z_] [a-zA-Z0-9_]* ;

// ---- operators and punctuation
ASSIGN : ':=' ;
OUTPUT_ASSIGN : '=>' ;
RANGE : '..' ;
POWER : '**' ;
NE : '<>' ;
LE : '<=' ;
GE : '>=' ;
EQ : '=' ;
LT : '<' ;
GT : '>' ;
PLUS : '+' ;
MINUS : '-' ;
STAR : '*' ;
SLASH : '/' ;
AMP : '&' ;
CARET : '^' ;
DOT : '.' ;
COMMA : ',' ;
SEMI : ';' ;
COLON : ':' ;
HASH : '#' ;
LPAREN : '(' ;
RPAREN : ')' ;
LBRACKET : '[' ;
RBRACKET : ']' ;

// ---- trivia
// (* *) and /* */ nest (CODESYS allows nesting of both).  The compiler lexes
// with the hand-written compiler/parse/FastLexer.cpp, which produces the same
// tokens as these rules (checked by tests/unit/LexerTest.cpp) except that it
// nests comments strictly: "(* a (* b *) c" is unterminated, where these
// non-greedy rules would end the comment at the first "*)".
BLOCK_COMMENT : '(*' ( BLOCK_COMMENT | C_COMMENT | . )*? '*)' -> channel(COMMENTS) ;
C_COMMENT : '/*' ( C_COMMENT | BLOCK_COMMENT | . )*? '*/' -> channel(COMMENTS) ;
LINE_COMMENT : '//' ~[\r\n]* -> channel(COMMENTS) ;
PRAGMA : '{' ~[}]* '}' -> channel(PRAGMAS) ;
WS : [ \t\r\n\f\u000B]+ -> channel(HIDDEN) ;

// Anything else is one error token; the parser driver reports it and goes on.
ERROR_CHAR : . ;

fragment A : [aA] ;
fragment B : [bB] ;
fragment C : [cC] ;
fragment D : [dD] ;
fragment E : [eE] ;
fragment F : [fF] ;
fragment G : [gG] ;
fragment H : [hH] ;
fragment I : [iI] ;
fragment J : [jJ] ;
fragment K : [kK] ;
fragment L : [lL] ;
fragment M : [mM] ;
fragment N : [nN] ;
fragment O : [oO] ;
fragment P : [pP] ;
fragment Q : [qQ] ;
fragment R : [rR] ;
fragment S : [sS] ;
fragment T : [tT] ;
fragment U : [uU] ;
fragment V : [vV] ;
fragment W : [wW] ;
fragment X : [xX] ;
fragment Y : [yY] ;
fragment Z : [zZ] ;
