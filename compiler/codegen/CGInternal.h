// State shared by the code generator's files:
//   CodeGen.cpp   - module setup, POU functions, program entries, tasks
//   CGImage.cpp   - the memory image and initial values (constant buffers)
//   CGExpr.cpp    - expressions, lvalues, conversions
//   CGStmt.cpp    - statements, loops and safepoints
//   CGCall.cpp    - calls: functions, FB instances, methods, builtins
//   CGChecks.cpp  - runtime checks and fault sites
//   Emit.cpp      - optimisation pipelines and --emit
#pragma once

#include <llvm/IR/DIBuilder.h>
#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>

#include <map>
#include <set>
#include <vector>

#include "codegen/CodeGen.h"
#include "codegen/CodeGenLLVM.h"
#include "sema/Model.h"

namespace stc::codegen {

using sema::Symbol;
using sema::Type;
using sema::TypeKind;

// An object in memory: its address and its ST type.
struct Address {
  llvm::Value* ptr = nullptr;
  const Type* type = nullptr;
  int bit = -1;          // a BOOL view of one bit of the byte at ptr (AT %IX1.2)
};

// `AT %IX2.3` and friends: a view into an area of the image.
struct DirectLocation {
  char area = 'M';       // I, Q, M
  uint64_t byteOffset = 0;
  int bit = -1;          // bit addresses
  unsigned bytes = 1;
};
bool parseDirectAddress(const std::string& text, DirectLocation& out);

// Bytes of a constant object plus the pointers inside it (vptrs, ADR()).
struct ConstBuffer {
  std::vector<uint8_t> bytes;
  std::map<uint64_t, llvm::Constant*> relocs;     // offset -> ptr constant
  void put(uint64_t off, uint64_t value, unsigned nbytes);
  bool allZero() const;
};

// An initial value that does not fold: evaluated by code at start-up.
struct DynamicInit {
  uint64_t offset;
  const Type* type;
  const ast::Expr* expr;
  bool bind = false;                  // REFERENCE TO bound at its declaration: store expr's address
  int64_t ownerOffset = -1;           // the FB/program instance whose variables expr may name
  const Type* ownerType = nullptr;
  DynamicInit shifted(uint64_t by) const {
    DynamicInit d = *this;
    d.offset += by;
    if (d.ownerOffset >= 0) d.ownerOffset += static_cast<int64_t>(by);
    return d;
  }
};

// FB_INIT / FB_EXIT (CGLifecycle.cpp).
enum class Lifecycle { Init, Exit };

struct FnState {
  llvm::Function* fn = nullptr;
  Symbol* pou = nullptr;                       // the POU being lowered (null: init code)
  llvm::Value* self = nullptr;                 // instance pointer (FB/program bodies, methods, actions)
  const Type* selfType = nullptr;              // its FB/program type
  std::map<const Symbol*, Address> locals;     // symbols without a VarDecl (result, SET value)
  std::map<const ast::VarDecl*, Address> localDecls;
  llvm::BasicBlock* returnBlock = nullptr;
  struct Loop { llvm::BasicBlock* cont; llvm::BasicBlock* exit; };
  std::vector<Loop> loops;
  size_t maxLoopDepth = 0;                     // deepest loop nesting in the body
  std::map<std::string, llvm::BasicBlock*> labels;   // upper-case label -> block
  llvm::IRBuilder<>* allocaBuilder = nullptr;
  std::unique_ptr<llvm::IRBuilder<>> allocaBuilderStorage;
  bool hasSafepoint = false;
  llvm::AllocaInst* budget = nullptr;          // the function's copy of __stc_budget (a register after mem2reg)
  llvm::DISubprogram* sp = nullptr;            // -g
};

class CodeGen {
public:
  CodeGen(const sema::Model& model, const SourceManager& sm, DiagnosticsEngine& diags, const CodegenOptions& opts,
          llvm::LLVMContext& ctx, llvm::Module& mod, CompiledModule& out);
  bool run(bool needTasks);

  // ------------------------------------------------------------ types (CodeGen.cpp)
  llvm::Type* valueType(const Type* t);        // SSA type: i1 for BOOL, iN, float, double, ptr; aggregates: ptr
  llvm::Type* memType(const Type* t);          // in memory: i8 for BOOL, [n x i8] for aggregates
  bool isAggregate(const Type* t) const;       // lives in memory only (strings, arrays, structs, FBs, interfaces)
  uint64_t sizeOf(const Type* t) const { return layout_.sizeOf(t); }
  uint64_t alignOf(const Type* t) const { return layout_.alignOf(t); }
  const Type* elementary(TypeKind k) const { return model_.types->elementary(k); }
  static const Type* strip(const Type* t);     // aliases, subranges, enums -> underlying; references kept

  // ------------------------------------------------------------ POUs (CodeGen.cpp)
  llvm::Function* functionFor(Symbol* pou);    // declares on demand
  llvm::FunctionType* signatureOf(Symbol* pou);
  bool returnsIndirect(Symbol* pou);
  const Type* returnTypeOf(Symbol* pou);       // result type (accessors: the property's)           // aggregate result through a leading pointer
  void lowerPou(Symbol* pou);
  bool isNative(const Symbol* pou) const;
  // Starts lowering `f`: an entry block for allocas falling through to the
  // code block, where b_ is left; fs_ = &st.
  void beginFunction(FnState& st, llvm::Function* f);
  Symbol* ownerOf(Symbol* pou) const;          // FB/program of a method/action/accessor
  const std::vector<Symbol*>& paramsOf(Symbol* pou);   // inherited params first (FB)

  // ------------------------------------------------------------ image (CGImage.cpp)
  void layoutImage();
  void buildImage();
  // overlay: the bytes already hold the initial value of the enclosing object (a member or
  // element of a structure or array initialiser), so a nested initialiser only changes
  // what it names instead of starting from the type's default.
  void initObject(ConstBuffer& buf, uint64_t off, const Type* t, const ast::Expr* init, std::vector<DynamicInit>& dyn,
                  const ast::VarDecl* decl = nullptr, bool overlay = false);
  void defaultObject(ConstBuffer& buf, uint64_t off, const Type* t, std::vector<DynamicInit>& dyn);
  bool foldScalar(const ast::Expr* e, const Type* to, llvm::Constant*& out);
  void writeScalar(ConstBuffer& buf, uint64_t off, const Type* t, llvm::Constant* c);
  void initBit(ConstBuffer& buf, uint64_t at, int bit, const ast::Expr* init);
  llvm::Constant* bufferConstant(const ConstBuffer& buf, llvm::Type** tyOut = nullptr);
  // Initialises memory at run time: constant part copied, the rest computed.
  void initAt(Address dst, const ast::Expr* init, const ast::VarDecl* decl = nullptr);
  void emitDynamicInit(llvm::Value* base, const DynamicInit& d);
  int folding_ = 0;
  bool libraryMode_ = false;   // no PROGRAM: every POU keeps external linkage
  // CGLifecycle.cpp
  std::map<std::pair<const Type*, Lifecycle>, bool> lifecycleMemo_;
  bool hasLifecycle(const Type* t, Lifecycle w);
  void emitLifecycle(llvm::Value* obj, const Type* t, Lifecycle w, llvm::Value* initRetains, const ast::StructInitExpr* args = nullptr);
  void callLifecycleMethod(sema::Symbol* m, llvm::Value* self, llvm::Value* initRetains, const ast::StructInitExpr* args);
  const ast::StructInitExpr* fbInitArguments(const ast::VarDecl* v);
  void emitLifecycleEntryPoints();
  void emitBodyInParts(FnState& st, const std::vector<ast::Stmt*>& body);   // inside foldScalar: errors mean "not a constant", not a diagnostic
  Address referenceSlot(const ast::Expr* e);
  llvm::Value* referenceTarget(const ast::Expr* e);
  llvm::Value* imageAddr(uint64_t off);
  std::string literalBytes(const ast::LiteralExpr* lit, bool wide) const;
  llvm::Constant* vtableFor(const Type* fb);

  // ------------------------------------------------------------ expressions (CGExpr.cpp)
  llvm::Value* emitValue(const ast::Expr* e, const Type* to);   // converted to `to` (null: its own type)
  llvm::Value* emitRaw(const ast::Expr* e);                      // in its own type; aggregates: address
  Address emitAddr(const ast::Expr* e);                          // lvalue
  Address varAddr(const Symbol* s, const ast::Expr* at);
  llvm::Value* load(Address a);
  // Pointer and reference slots: 4 bytes (an i32 address) in the 32-bit address model
  // unless the type is wide (native libraries' structures), else 8.  SSA values are `ptr`.
  bool narrowSlot(const Type* t) const;
  llvm::Value* loadAddress(llvm::Value* slot, const Type* slotType);
  void storeAddress(llvm::Value* slot, const Type* slotType, llvm::Value* p);
  void store(Address a, llvm::Value* v);                          // v in a.type's value type
  void assign(Address dst, const ast::Expr* src);                  // with conversion, strings, aggregates
  llvm::Value* convert(llvm::Value* v, const Type* from, const Type* to, const ast::Expr* at);
  llvm::Value* toBool(llvm::Value* v);
  llvm::Value* emitBinary(const ast::BinaryExpr* e);
  // CODESYS integer temporaries (DialectRule::RegisterWidthTemporaries): + - * / MOD on
  // integers narrower than the register are computed in the register width.
  unsigned registerBits_ = 0;                  // 0: every operation in its type's width (IEC)
  bool widensIntermediate(const ast::Expr* e) const;
  llvm::Value* emitWideBinary(const ast::BinaryExpr* e);           // in the register width
  llvm::Value* emitWideInt(const ast::Expr* e, const Type* as);    // e as `as`, extended to the register width
  // CODESYS implicit check functions: a user FUNCTION named CheckBounds, CheckRangeSigned,
  // CheckRangeUnsigned, CheckDivInt/DInt/LInt/Real/LReal is called where CODESYS calls it
  // (an index, a value entering a subrange, a divisor) and its result used instead
  // (not inside the check functions themselves).  Null if the program has none.
  Symbol* implicitCheck(const char* name);
  // Records `at` in __stc_site before an operation that may fault in hardware (a
  // dereference, MEMCPY, an indirect call): vm/FaultSignals.cpp reports it there.
  void markSite(const ast::Node* at, const std::string& detail = "");
  // [p, p + bytes) must be the program's memory (image or task stack): __stc_check_ptr.
  void checkPointerRange(llvm::Value* p, llvm::Value* bytes, const ast::Node* at);
  llvm::GlobalVariable* siteVar_ = nullptr;
  llvm::Value* callImplicitCheck(Symbol* fn, std::vector<llvm::Value*> args, bool isSigned);
  std::map<std::string, Symbol*> implicitChecks_;
  bool implicitChecksFound_ = false;
  llvm::Value* intDivide(llvm::Value* l, llvm::Value* r, bool isDiv, bool isSigned, const ast::Node* at);
  llvm::Value* emitCompare(ast::BinaryOp op, llvm::Value* l, llvm::Value* r, const Type* t);
  llvm::Value* emitStringLiteral(const ast::LiteralExpr* lit, const Type* t);
  llvm::Value* constantValue(const ast::LiteralExpr* lit, const Type* t);
  Address temporary(const Type* t, const char* name = "tmp");
  llvm::Value* bitRead(llvm::Value* word, unsigned bit, unsigned width, llvm::Type* resultTy);
  void storeBits(const ast::MemberExpr* m, llvm::Value* v);
  Address directAddress(const std::string& text, const Type* t);
  llvm::Value* instancePtr(const ast::Expr* e);                  // FB/program instance of an expression
  // ARRAY[*] parameters get a descriptor {ptr data, i64 lo1, i64 hi1, ...}.
  static bool isOpenArray(const Type* t);
  llvm::Value* arrayDescriptor(const ast::Expr* array);

  // ------------------------------------------------------------ statements (CGStmt.cpp)
  void emitStmts(const std::vector<ast::Stmt*>& stmts);
  void emitStmt(const ast::Stmt* s);
  void emitFor(const ast::ForStmt* s);
  void emitCase(const ast::CaseStmt* s);
  void safepoint(const ast::Node* at);
  void syncBudgetAroundCalls(FnState& st);
  llvm::AllocaInst* budgetSlot();     // the local budget meets the global one at calls and returns
  bool blockOpen() const;
  llvm::BasicBlock* newBlock(const char* name);

  // ------------------------------------------------------------ calls (CGCall.cpp)
  llvm::Value* emitCall(const ast::CallExpr* e, Address* resultOut = nullptr);
  // fnPtr: call through this pointer (interface slots) instead of the symbol.
  llvm::Value* callPou(const ast::CallExpr* e, Symbol* target, llvm::Value* self, bool virtualCall, llvm::Value* fnPtr = nullptr);
  void callInstance(const ast::CallExpr* e, Symbol* fbType, llvm::Value* inst);
  llvm::Value* emitBuiltin(const ast::CallExpr* e);
  llvm::Value* stringConversion(const ast::Expr* arg, const Type* resultType, const ast::Expr* at);
  llvm::Value* arg(const ast::CallExpr* e, size_t i, const Type* to);
  llvm::Value* emitPropertyGet(const ast::Expr* e, Symbol* prop);
  void emitPropertySet(const ast::Expr* lhs, Symbol* prop, const ast::Expr* rhs);

  // ------------------------------------------------------------ interfaces (CGOop.cpp)
  std::vector<std::string> itableKeys(const Type* itf);
  llvm::Constant* itableFor(const Type* fb, const Type* itf);
  llvm::Value* interfaceSelf(const ast::Expr* e);
  void assignInterface(Address dst, const ast::Expr* src);
  std::pair<llvm::Value*, llvm::Value*> interfaceSlot(const ast::Expr* receiver, Symbol* method);   // {self, function}
  std::map<std::pair<const Type*, const Type*>, llvm::Constant*> itables_;

  // ------------------------------------------------------------ checks (CGChecks.cpp)
  uint32_t site(const ast::Node* n, std::string detail = "");
  uint32_t site(SourceRange r, std::string detail = "");
  void check(llvm::Value* ok, FaultKind kind, uint32_t site);
  void checkIndex(llvm::Value* idx, int64_t lo, int64_t hi, uint32_t site);
  llvm::Value* checkedDivisor(llvm::Value* d, const ast::Node* at);
  llvm::Value* nullChecked(llvm::Value* p, FaultKind kind, const ast::Node* at);

  // ------------------------------------------------------------ debug info (CGDebug.cpp)
  void beginDebugInfo();
  void finishDebugInfo();
  llvm::DISubprogram* debugFunction(llvm::Function* f, Symbol* pou);
  void debugLocation(SourceLoc loc);           // for the instructions that follow
  llvm::DIFile* debugFile(uint32_t fileId);
  std::unique_ptr<llvm::DIBuilder> di_;
  llvm::DICompileUnit* cu_ = nullptr;
  std::map<uint32_t, llvm::DIFile*> diFiles_;

  // ------------------------------------------------------------ runtime ABI
  llvm::FunctionCallee runtime(const char* name, llvm::Type* ret, llvm::ArrayRef<llvm::Type*> params, bool noreturn = false);

  // ------------------------------------------------------------ state
  const sema::Model& model_;
  const sema::Layout& layout_;
  const SourceManager& sm_;
  DiagnosticsEngine& diags_;
  const CodegenOptions& opts_;
  llvm::LLVMContext& ctx_;
  llvm::Module& mod_;
  CompiledModule& out_;
  llvm::IRBuilder<> b_;
  llvm::PointerType* ptrTy_;
  llvm::IntegerType *i1_, *i8_, *i16_, *i32_, *i64_;
  llvm::GlobalVariable* image_ = nullptr;
  llvm::GlobalVariable* budget_ = nullptr;
  llvm::GlobalVariable* callChain_ = nullptr;   // __stc_calls: the running task's vm::CallChain
  // Around each call of an ST POU: the call site on the task's call chain, so
  // that a fault names the callers (CGCall.cpp).
  llvm::Value* pushCallSite(uint32_t site);
  void popCallSite(llvm::Value* depth);
  FnState* fs_ = nullptr;
  std::map<const ast::VarDecl*, uint64_t> imageOffsets_;   // globals, VAR_STAT, program instances' decls
  std::map<const Symbol*, uint64_t> programOffsets_;       // PROGRAM type -> its singleton instance
  std::map<const ast::VarDecl*, Symbol*> varOwner_;
  std::map<const ast::VarDecl*, DirectLocation> atViews_;   // AT %I/%Q/%M variables
  std::map<const Symbol*, std::vector<Symbol*>> methodsOf_;  // FB -> its methods and accessors
  std::map<const Type*, std::vector<std::pair<std::string, Symbol*>>> vtableSlots_;
  const std::vector<std::pair<std::string, Symbol*>>& vtableSlots(const Type* fb);
  int vtableSlot(const Type* fb, const std::string& key);
  static std::string slotKey(const Symbol* method);
  llvm::Function* foldFn_ = nullptr;
  Address stringDest_;                     // assignment target a string builtin may write into directly
  std::set<const Type*> inTypeDefault_;   // a type's own initialiser is being applied
  std::map<const Symbol*, llvm::Function*> functions_;
  std::map<const Symbol*, std::vector<Symbol*>> params_;
  std::map<const Type*, llvm::GlobalVariable*> vtables_;
  std::vector<llvm::GlobalVariable*> vtableOrder_;            // creation order: their place in __stc_vtables
  // Dynamic dispatch reads an instance's vtable pointer; with checks it must point
  // into __stc_vtables, the one array holding every vtable (finishVtables).
  llvm::Value* loadVptr(llvm::Value* self, const ast::Node* at);
  void checkInVtables(llvm::Value* p, const ast::Node* at);
  void finishVtables();
  llvm::GlobalVariable* vtablesBegin_ = nullptr;              // placeholders until finishVtables
  llvm::GlobalVariable* vtablesEnd_ = nullptr;
  std::map<std::string, llvm::Constant*> stringLits_;
  std::vector<DynamicInit> imageDynamic_;
  std::map<llvm::Function*, std::set<llvm::Function*>> calls_;   // direct call graph (may-suspend analysis)
  std::set<llvm::Function*> indirectCallers_, safepointFns_;
  uint64_t imageSize_ = 0;
  unsigned errors_ = 0;
  void error(SourceRange r, const std::string& msg);
};

}  // namespace stc::codegen
