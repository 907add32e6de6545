// IEC 61131-3 (3rd edition) Structured Text with CODESYS V2.3/V3 extensions.
//
// The parse tree is only an intermediate: compiler/parse/ASTBuilder.cpp turns
// it into the typed AST at once.  Rules stay close to the standard's
// productions; elementary type names (INT, STRING, ...) are ordinary
// identifiers here and are resolved by semantic analysis, which keeps the
// grammar small and lets `INT#5`, `STRING(80)` and `INT(0..9)` share rules.
parser grammar STParser;

options { tokenVocab = STLexer; }

compilationUnit : libraryElement* EOF ;

libraryElement
    : dataTypeDecl
    | pouDecl
    | interfaceDecl
    | globalVarBlock
    | configurationDecl
    | namespaceDecl
    | actionDecl          // CODESYS 2.3 export: ACTION after its POU
    | methodDecl          // METHOD Owner.Name at top level
    | propertyDecl
    ;

namespaceDecl : NAMESPACE qualifiedName libraryElement* END_NAMESPACE ;

qualifiedName : IDENTIFIER ( DOT IDENTIFIER )* ;

// ---------------------------------------------------------------- types
dataTypeDecl : TYPE typeDeclItem+ END_TYPE ;

typeDeclItem
    : IDENTIFIER ( EXTENDS qualifiedName )? COLON typeDefinition ( ASSIGN initializerList )? SEMI*
    ;

typeDefinition
    : STRUCT ( EXTENDS qualifiedName )? memberDecl* END_STRUCT      # structDef
    | UNION memberDecl* END_UNION                                   # unionDef
    // IEC form with the base type first: INT (a := 1, b := 2).  The first value
    // must carry := so that STRING(MAX_LEN) stays a sized type.
    | typeName LPAREN IDENTIFIER ASSIGN expression ( COMMA enumValue )* RPAREN   # typedEnumDef
    | typeSpec                                                      # aliasDef
    ;

memberDecl : varDecl ;

enumValue : IDENTIFIER ( ASSIGN expression )? ;

typeName : qualifiedName ;

typeSpec
    : ARRAY LBRACKET arrayRange ( COMMA arrayRange )* RBRACKET OF typeSpec     # arrayType
    | POINTER TO typeSpec                                                     # pointerType
    | ( REFERENCE TO | REF_TO ) typeSpec                                      # referenceType
    | qualifiedName LPAREN lo=expression RANGE hi=expression RPAREN           # subrangeType
    // fb : FB_T(param := v): the arguments of FB_INIT (CODESYS V3).
    | qualifiedName LPAREN structInitElement ( COMMA structInitElement )* RPAREN # fbInitType
    | qualifiedName ( LPAREN expression RPAREN | LBRACKET expression RBRACKET ) # sizedType
    | LPAREN enumValue ( COMMA enumValue )* RPAREN typeName?                 # inlineEnumType
    | qualifiedName                                                           # namedType
    ;

arrayRange : lo=expression RANGE hi=expression | STAR ;

// ---------------------------------------------------------------- POUs
pouDecl
    : kind=( PROGRAM | FUNCTION | FUNCTION_BLOCK ) pouModifier* qualifiedName
      ( COLON returnType=typeSpec )?
      ( EXTENDS baseName=qualifiedName )?
      ( IMPLEMENTS qualifiedName ( COMMA qualifiedName )* )?
      varBlock*
      pouMember*
      body
      pouMember*
      endKw=( END_PROGRAM | END_FUNCTION | END_FUNCTION_BLOCK )
    ;

pouModifier : ABSTRACT | FINAL | PUBLIC | PRIVATE | PROTECTED | INTERNAL ;

pouMember : methodDecl | propertyDecl | actionDecl ;

methodDecl
    : METHOD pouModifier* qualifiedName ( COLON typeSpec )? varBlock* body END_METHOD
    ;

propertyDecl
    : PROPERTY pouModifier* qualifiedName COLON typeSpec varBlock* propertyAccessor* END_PROPERTY
    ;

// GET / SET are not reserved words (Set and Get are common names).
propertyAccessor
    : accessor=IDENTIFIER pouModifier* varBlock* body endKw=( END_GET | END_SET )
    ;

actionDecl : ACTION qualifiedName COLON? body END_ACTION ;

interfaceDecl
    : INTERFACE qualifiedName ( EXTENDS qualifiedName ( COMMA qualifiedName )* )?
      ( methodDecl | propertyDecl )*
      END_INTERFACE
    ;

// A body is a sequence of statements, each optionally labelled (`lbl: x := 1;`).
// Labels are tokens of the body itself rather than a wrapper rule, which saves a
// parse-tree node per statement.
body : ( IDENTIFIER COLON | unlabeledStatement )* ;

// ---------------------------------------------------------------- variables
varBlock
    : kind=( VAR | VAR_INPUT | VAR_OUTPUT | VAR_IN_OUT | VAR_TEMP | VAR_STAT | VAR_INST
           | VAR_EXTERNAL | VAR_ACCESS | VAR_GLOBAL )
      varQualifier* varDecl* END_VAR
    ;

globalVarBlock : VAR_GLOBAL varQualifier* varDecl* END_VAR ;

varQualifier : CONSTANT | RETAIN | NON_RETAIN | PERSISTENT ;

varDecl
    : IDENTIFIER ( COMMA IDENTIFIER )* ( AT DIRECT_ADDRESS )? COLON typeSpec edge=( R_EDGE | F_EDGE )? ( ASSIGN initializerList? | REF_ASSIGN refInit=expression )? SEMI
    ;
// REF= x binds a REFERENCE TO variable at its declaration (CODESYS).

// One initializer, or (CODESYS 2.3) the elements of an array without brackets:
// `a : ARRAY[1..4] OF INT := 1, 2, 2(0);`.  One rule, so that the common case
// needs no lookahead past the first element.
initializerList : arrayInitElement ( COMMA arrayInitElement )* ;

initializer
    : LBRACKET arrayInitElement ( COMMA arrayInitElement )* COMMA? RBRACKET    # arrayInit
    | LPAREN structInitElement ( COMMA structInitElement )* RPAREN             # structInit
    | expression                                                               # exprInit
    ;

arrayInitElement
    : INTEGER_LITERAL LPAREN initializer? RPAREN      # repeatedElement
    | initializer                                     # singleElement
    ;

structInitElement : IDENTIFIER ASSIGN initializer ;

// ---------------------------------------------------------------- configuration
configurationDecl
    : CONFIGURATION IDENTIFIER globalVarBlock* ( resourceDecl+ | resourceBody ) varConfigBlock* END_CONFIGURATION
    ;

// `ON` is not a keyword (CODESYS code names variables ON): the builder checks the word.
resourceDecl : RESOURCE IDENTIFIER ( IDENTIFIER IDENTIFIER )? resourceBody END_RESOURCE ;

resourceBody : globalVarBlock* taskDecl* programConfig* ;

taskDecl : TASK IDENTIFIER LPAREN taskInit ( COMMA taskInit )* RPAREN SEMI ;

taskInit : IDENTIFIER ASSIGN expression ;

programConfig
    : PROGRAM ( RETAIN | NON_RETAIN )? IDENTIFIER ( WITH IDENTIFIER )? COLON qualifiedName
      ( LPAREN ( callArgument ( COMMA callArgument )* )? RPAREN )? SEMI
    ;

varConfigBlock : VAR_CONFIG varConfigItem* END_VAR ;

varConfigItem : qualifiedName AT DIRECT_ADDRESS COLON typeSpec ( ASSIGN initializer )? SEMI ;

// ---------------------------------------------------------------- statements
// CASE bodies cannot hold labels: `Red:` there starts the next case element.
caseBody : unlabeledStatement* ;

// Statements that start with an expression share one alternative; the token
// after the expression decides (LL(1)) instead of a prediction over the whole
// left-hand side, which keeps parsing fast.  `a := b := 0` (CODESYS ExST) chains.
unlabeledStatement
    : lhs=expression ( op=( ASSIGN | REF_ASSIGN ) rhs=expression ( ASSIGN chain+=expression )* | sr=IDENTIFIER EQ rhs=expression )? SEMI   # exprBasedStmt
    | IF expression THEN body elsifPart* ( ELSE elseBody=body )? END_IF     # ifStmt
    | CASE expression OF caseElement* ( ELSE elseBody=body )? END_CASE      # caseStmt
    | FOR IDENTIFIER ASSIGN from=expression TO to=expression ( BY by=expression )? DO body END_FOR  # forStmt
    | WHILE expression DO body END_WHILE                           # whileStmt
    | REPEAT body UNTIL expression END_REPEAT                      # repeatStmt
    | EXIT SEMI                                                    # exitStmt
    | CONTINUE SEMI                                                # continueStmt
    | RETURN SEMI                                                  # returnStmt
    | JMP IDENTIFIER SEMI                                          # jmpStmt
    | SEMI                                                         # emptyStmt
    ;

elsifPart : ELSIF expression THEN body ;

caseElement : caseLabel ( COMMA caseLabel )* COLON caseBody ;

caseLabel : lo=expression ( RANGE hi=expression )? ;

// ---------------------------------------------------------------- expressions
// Precedence from IEC 61131-3 table 71, highest first; AND_THEN / OR_ELSE
// (CODESYS) share the level of AND / OR.  Primaries are alternatives of this
// rule (not a rule of their own) to save a parse-tree node per operand.
expression
    : ( INTEGER_LITERAL | REAL_LITERAL | BASED_LITERAL | TRUE | FALSE | STRING_LITERAL | WSTRING_LITERAL
      | TIME_LITERAL | DATE_LITERAL | TOD_LITERAL | DATE_TIME_LITERAL )                 # simpleLiteralExpr
    | typedLiteral                                                     # typedLiteralExpr
    | IDENTIFIER                                                       # nameExpr
    | THIS                                                             # thisExpr
    | SUPER                                                            # superExpr
    | DIRECT_ADDRESS                                                   # addressExpr
    | LPAREN expression RPAREN                                         # parenExpr
    | expression DOT ( IDENTIFIER | INTEGER_LITERAL | PARTIAL_ACCESS )  # memberExpr
    | expression LBRACKET expression ( COMMA expression )* RBRACKET     # indexExpr
    | expression CARET                                                  # derefExpr
    | expression LPAREN ( callArgument ( COMMA callArgument )* )? RPAREN # callExpr
    | <assoc=right> op=( MINUS | PLUS | NOT ) expression                # unaryExpr
    | <assoc=right> expression op=POWER expression                      # binaryExpr
    | expression op=( STAR | SLASH | MOD ) expression                   # binaryExpr
    | expression op=( PLUS | MINUS ) expression                         # binaryExpr
    | expression op=( LT | GT | LE | GE ) expression                    # binaryExpr
    | expression op=( EQ | NE ) expression                              # binaryExpr
    | expression op=( AND | AMP | AND_THEN ) expression                 # binaryExpr
    | expression op=XOR expression                                      # binaryExpr
    | expression op=( OR | OR_ELSE ) expression                         # binaryExpr
    ;

// `name := value`, `name => var`, `NOT name => var` or a positional value.  The
// name is parsed as an expression and checked by the AST builder, so that the
// choice is made by the token after it (LL(1)) instead of a prediction.
callArgument
    : expression ( op=( ASSIGN | OUTPUT_ASSIGN ) value=expression? )?
    ;

// INT#5, REAL#-1.5, DWORD#16#FF, BOOL#TRUE, Color#Red, STRING#'x'
typedLiteral
    : IDENTIFIER HASH ( MINUS | PLUS )? ( INTEGER_LITERAL | REAL_LITERAL | BASED_LITERAL )
    | IDENTIFIER HASH ( TRUE | FALSE | IDENTIFIER | STRING_LITERAL | WSTRING_LITERAL )
    ;
