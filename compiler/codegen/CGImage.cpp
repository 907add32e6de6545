// The memory image: one global holding every GVL variable, PROGRAM instance
// and VAR_STAT, whose constant initialiser is the cold-start state; the
// process image areas %I, %Q, %M; initial values of every object.
#include <llvm/IR/Constants.h>

#include "basic/Text.h"
#include "codegen/CGInternal.h"

namespace stc::codegen {

using namespace stc::ast;

namespace {
uint64_t alignUp(uint64_t v, uint64_t a) { return (v + a - 1) / a * a; }
}  // namespace

void ConstBuffer::put(uint64_t off, uint64_t value, unsigned nbytes) {
  for (unsigned i = 0; i < nbytes; ++i) bytes[off + i] = static_cast<uint8_t>(value >> (8 * i));
}

bool ConstBuffer::allZero() const {
  if (!relocs.empty()) return false;
  for (uint8_t b : bytes)
    if (b) return false;
  return true;
}

bool parseDirectAddress(const std::string& text, DirectLocation& out) {
  // %IX2.3  %QB4  %MW10  %MD48  %IL1  %I2.1 (bit without size letter)
  if (text.size() < 3 || text[0] != '%') return false;
  out.area = asciiUpper(text[1]);
  if (out.area != 'I' && out.area != 'Q' && out.area != 'M') return false;
  size_t i = 2;
  char size = 'X';
  if (i < text.size() && std::isalpha(static_cast<unsigned char>(text[i]))) size = asciiUpper(text[i++]);
  std::vector<uint64_t> parts;
  uint64_t cur = 0;
  bool digit = false;
  for (; i < text.size(); ++i) {
    char c = text[i];
    if (c >= '0' && c <= '9') { cur = cur * 10 + static_cast<uint64_t>(c - '0'); digit = true; }
    else if (c == '.') { if (!digit) return false; parts.push_back(cur); cur = 0; digit = false; }
    else return false;
  }
  if (!digit) return false;
  parts.push_back(cur);
  switch (size) {
    case 'X':
      out.bytes = 1;
      if (parts.size() >= 2) { out.byteOffset = parts[parts.size() - 2]; out.bit = static_cast<int>(parts.back() % 8); }
      else { out.byteOffset = parts[0] / 8; out.bit = static_cast<int>(parts[0] % 8); }
      return true;
    case 'B': out.bytes = 1; break;
    case 'W': out.bytes = 2; break;
    case 'D': out.bytes = 4; break;
    case 'L': out.bytes = 8; break;
    default: return false;
  }
  // CODESYS V3 indexes by unit: %MW10 is bytes 20..21.
  out.byteOffset = parts[0] * out.bytes;
  out.bit = -1;
  return true;
}

// ------------------------------------------------------------------ layout of the image

void CodeGen::layoutImage() {
  uint64_t off = 0;
  auto place = [&](const std::string& path, const Type* t, const VarDecl* decl, bool retain, bool persistent, bool constant) {
    off = alignUp(off, std::max<uint64_t>(1, alignOf(t)));
    if (decl) imageOffsets_[decl] = off;
    ImageRoot r;
    r.path = path;
    r.offset = off;
    r.type = t;
    r.retain = retain;
    r.persistent = persistent;
    r.constant = constant;
    out_.image.roots.push_back(r);
    off += std::max<uint64_t>(sizeOf(t), 1);
    return r.offset;
  };
  auto alias = [&](const std::string& path, uint64_t offset, const Type* t) {
    ImageRoot r;
    r.path = path;
    r.offset = offset;
    r.type = t;
    r.alias = true;
    out_.image.roots.push_back(r);
  };
  auto placeVar = [&](const VarDecl* v, const std::string& prefix, const VarBlock& b) {
    if (!v->resolvedType) return;
    if (!v->address.empty() && v->address.find('*') == std::string::npos) {
      DirectLocation loc;
      if (parseDirectAddress(v->address, loc)) { atViews_[v] = loc; return; }
    }
    bool retain = b.isRetain || v->isRetain, persistent = b.isPersistent || v->isPersistent;
    uint64_t o = place(prefix.empty() ? v->name.name : prefix + "." + v->name.name, v->resolvedType, v, retain, persistent,
                       b.isConstant || v->isConstant);
    if (!prefix.empty()) alias(v->name.name, o, v->resolvedType);
  };
  for (GlobalVarDecl* g : model_.globalLists)
    for (const VarDecl* v : g->block.vars) placeVar(v, g->listName.name, g->block);
  for (ConfigurationDecl* c : model_.configurations) {
    for (const VarBlock& b : c->globals)
      for (const VarDecl* v : b.vars) placeVar(v, "", b);
    for (const ResourceDecl& r : c->resources) {
      for (const VarBlock& b : r.globals)
        for (const VarDecl* v : b.vars) placeVar(v, "", b);
    }
  }
  // PROGRAM singletons, named after their type.
  for (Symbol* p : model_.pous)
    if (p->kind == Symbol::Program) programOffsets_[p] = place(p->name, p->type, nullptr, false, false, false);
  // Program instances of configurations.
  for (ConfigurationDecl* c : model_.configurations)
    for (const ResourceDecl& r : c->resources)
      for (const ProgramConfig& pc : r.programs)
        for (Symbol* p : model_.pous) {
          if (p->kind != Symbol::Program || !equalsIgnoreCase(p->name, pc.type.parts.back().name)) continue;
          // An instance named like its type is the program's singleton; any other
          // name already in the image (a global variable, another program) would
          // make two objects share storage.
          if (!out_.image.find(asciiUpper(pc.name.name)))
            place(pc.name.name, p->type, nullptr, pc.retain, false, false);
          else if (!equalsIgnoreCase(pc.name.name, p->name))
            error(pc.name.range, "program instance '" + pc.name.name +
                                     "' has the name of a global variable or program; instance names must be unique");
        }
  // A program the configurations run only under other instance names, and that
  // no POU calls: its own instance never runs; paths through it get a hint.
  if (!model_.configurations.empty())
    for (Symbol* p : model_.pous) {
      if (p->kind != Symbol::Program || model_.calledPrograms.count(p)) continue;
      std::string others;
      bool self = false;
      for (ConfigurationDecl* c : model_.configurations)
        for (const ResourceDecl& r : c->resources)
          for (const ProgramConfig& pc : r.programs)
            if (equalsIgnoreCase(p->name, pc.type.parts.back().name)) {
              if (equalsIgnoreCase(pc.name.name, p->name)) self = true;
              else others += (others.empty() ? "" : ", ") + pc.name.name;
            }
      if (self || others.empty()) continue;
      for (ImageRoot& r : out_.image.roots)
        if (!r.alias && equalsIgnoreCase(r.path, p->name)) r.runsAs = others;
    }
  // VAR_STAT and AT views of POUs.
  for (Symbol* p : model_.pous) {
    if (!p->pou || !p->pou->decl) continue;
    for (const VarBlock& b : p->pou->decl->varBlocks)
      for (const VarDecl* v : b.vars) {
        if (!v->address.empty() && v->address.find('*') == std::string::npos) {
          DirectLocation loc;
          if (parseDirectAddress(v->address, loc)) atViews_[v] = loc;
        }
        if (v->section == VarSection::Stat && v->resolvedType) {
          std::string owner = p->pou->owner ? p->pou->owner->name + "." + p->name : p->name;
          place(owner + "." + v->name.name, v->resolvedType, v, b.isRetain, b.isPersistent, b.isConstant);
        }
      }
  }
  // VAR_CONFIG: Resource.Instance.var AT %IX1.0 locates a variable declared
  // AT %I* / %Q*.  The location belongs to the declaration, so two instances
  // of one program type cannot be mapped to different addresses.
  std::vector<std::pair<std::string, const VarDecl*>> configViews;
  for (ConfigurationDecl* c : model_.configurations)
    for (const auto& cv : c->configVars) {
      const auto& parts = cv.path.parts;
      for (const ResourceDecl& r : c->resources)
        for (const ProgramConfig& pc : r.programs) {
          size_t i = 0;
          if (parts.size() >= 3 && equalsIgnoreCase(parts[0].name, r.name.name)) i = 1;
          if (parts.size() < i + 2 || !equalsIgnoreCase(parts[i].name, pc.name.name)) continue;
          for (Symbol* p : model_.pous) {
            if (p->kind != Symbol::Program || !equalsIgnoreCase(p->name, pc.type.parts.back().name)) continue;
            for (const VarBlock& b : p->pou->decl->varBlocks)
              for (const VarDecl* v : b.vars) {
                if (!equalsIgnoreCase(v->name.name, parts[i + 1].name)) continue;
                DirectLocation loc;
                if (!parseDirectAddress(cv.address, loc)) continue;
                auto it = atViews_.find(v);
                if (it != atViews_.end() && (it->second.area != loc.area || it->second.byteOffset != loc.byteOffset || it->second.bit != loc.bit)) {
                  error(cv.range, "'" + v->name.name + "' of program '" + p->name +
                                      "' is located twice by VAR_CONFIG; instances of one program type share their addresses");
                  continue;
                }
                atViews_[v] = loc;
                configViews.push_back({pc.name.name + "." + v->name.name, v});
              }
          }
        }
    }
  // The process image areas: large enough for every AT declaration, and at
  // least 4 KiB each for direct addresses used in code.
  uint64_t areaEnd[3] = {4096, 4096, 4096};
  auto areaIndex = [](char a) { return a == 'I' ? 0 : a == 'Q' ? 1 : 2; };
  for (auto& [v, loc] : atViews_) {
    uint64_t end = loc.byteOffset + std::max<uint64_t>(loc.bytes, v->resolvedType ? sizeOf(v->resolvedType) : 1);
    areaEnd[areaIndex(loc.area)] = std::max(areaEnd[areaIndex(loc.area)], alignUp(end, 8));
    if (loc.area == 'I') out_.image.inputUsed = std::max(out_.image.inputUsed, end);
    if (loc.area == 'Q') out_.image.outputUsed = std::max(out_.image.outputUsed, end);
  }
  off = alignUp(off, 16);
  out_.image.inputOffset = off;
  out_.image.inputSize = areaEnd[0];
  off += areaEnd[0];
  out_.image.outputOffset = off;
  out_.image.outputSize = areaEnd[1];
  off += areaEnd[1];
  out_.image.memoryOffset = off;
  out_.image.memorySize = areaEnd[2];
  off += areaEnd[2];
  // Watchable names of the AT views.
  auto areaBase = [&](char a) { return a == 'I' ? out_.image.inputOffset : a == 'Q' ? out_.image.outputOffset : out_.image.memoryOffset; };
  auto viewRoot = [&](const std::string& path, const VarDecl* v) {
    auto it = atViews_.find(v);
    if (it == atViews_.end() || !v->resolvedType) return;
    ImageRoot r;
    r.path = path;
    r.offset = areaBase(it->second.area) + it->second.byteOffset;
    r.type = v->resolvedType;
    r.bit = strip(v->resolvedType)->isBool() ? it->second.bit : -1;
    out_.image.roots.push_back(r);
  };
  for (GlobalVarDecl* g : model_.globalLists)
    for (const VarDecl* v : g->block.vars) {
      viewRoot(v->name.name, v);
      if (!g->listName.name.empty()) viewRoot(g->listName.name + "." + v->name.name, v);
    }
  for (Symbol* p : model_.pous)
    if (p->kind == Symbol::Program && p->pou->decl)
      for (const VarBlock& b : p->pou->decl->varBlocks)
        for (const VarDecl* v : b.vars) viewRoot(p->name + "." + v->name.name, v);
  for (auto& [path, v] : configViews) viewRoot(path, v);
  imageSize_ = alignUp(std::max<uint64_t>(off, 8), 16);
  out_.image.size = imageSize_;
  image_ = new llvm::GlobalVariable(mod_, llvm::ArrayType::get(i8_, imageSize_), false, llvm::GlobalValue::ExternalLinkage, nullptr,
                                    "__stc_image.tmp");
  image_->setAlignment(llvm::Align(16));
}

llvm::Value* CodeGen::imageAddr(uint64_t off) { return b_.CreateConstInBoundsGEP1_64(i8_, image_, off); }

void CodeGen::buildImage() {
  ConstBuffer buf;
  buf.bytes.assign(imageSize_, 0);
  auto initRoots = [&](const VarDecl* v) {
    auto it = imageOffsets_.find(v);
    if (it != imageOffsets_.end()) initObject(buf, it->second, v->resolvedType, v->init, imageDynamic_, v);
  };
  for (GlobalVarDecl* g : model_.globalLists)
    for (const VarDecl* v : g->block.vars) initRoots(v);
  for (ConfigurationDecl* c : model_.configurations) {
    for (const VarBlock& b : c->globals)
      for (const VarDecl* v : b.vars) initRoots(v);
    for (const ResourceDecl& r : c->resources)
      for (const VarBlock& b : r.globals)
        for (const VarDecl* v : b.vars) initRoots(v);
  }
  for (const ImageRoot& r : out_.image.roots)
    if (!r.alias && r.type && (r.type->kind == TypeKind::Program)) defaultObject(buf, r.offset, r.type, imageDynamic_);
  for (Symbol* p : model_.pous) {
    if (!p->pou || !p->pou->decl) continue;
    for (const VarBlock& b : p->pou->decl->varBlocks)
      for (const VarDecl* v : b.vars)
        if (v->section == VarSection::Stat) initRoots(v);
  }
  llvm::Type* ty = nullptr;
  llvm::Constant* init = bufferConstant(buf, &ty);
  auto* g = new llvm::GlobalVariable(mod_, ty, false, llvm::GlobalValue::ExternalLinkage, init, "__stc_image");
  g->setAlignment(llvm::Align(16));
  image_->replaceAllUsesWith(g);
  image_->eraseFromParent();
  image_ = g;

  // Initial values that do not fold run once after the image is copied.
  auto* f = llvm::Function::Create(llvm::FunctionType::get(llvm::Type::getVoidTy(ctx_), false), llvm::Function::ExternalLinkage,
                                   "__stc_init_dynamic", mod_);
  FnState st;
  beginFunction(st, f);
  st.returnBlock = llvm::BasicBlock::Create(ctx_, "return", f);
  for (const DynamicInit& d : imageDynamic_) emitDynamicInit(imageAddr(0), d);
  if (blockOpen()) b_.CreateBr(st.returnBlock);
  b_.SetInsertPoint(st.returnBlock);
  b_.CreateRetVoid();
  fs_ = nullptr;
  emitLifecycleEntryPoints();
  if (foldFn_) {
    foldFn_->eraseFromParent();
    foldFn_ = nullptr;
  }
}

llvm::Constant* CodeGen::bufferConstant(const ConstBuffer& buf, llvm::Type** tyOut) {
  std::vector<llvm::Constant*> parts;
  uint64_t pos = 0;
  auto bytes = [&](uint64_t from, uint64_t to) {
    if (to <= from) return;
    parts.push_back(llvm::ConstantDataArray::get(ctx_, llvm::ArrayRef<uint8_t>(buf.bytes.data() + from, to - from)));
  };
  for (auto& [off, c] : buf.relocs) {
    bytes(pos, off);
    parts.push_back(c);
    pos = off + (c->getType()->isIntegerTy(32) ? 4 : 8);
  }
  bytes(pos, buf.bytes.size());
  llvm::Constant* c = llvm::ConstantStruct::getAnon(ctx_, parts, /*packed=*/true);
  if (tyOut) *tyOut = c->getType();
  return c;
}

// ------------------------------------------------------------------ initial values

std::string CodeGen::literalBytes(const LiteralExpr* lit, bool wide) const {
  // lit->text is UTF-8.  STRING: Latin-1 when every character fits, else
  // the UTF-8 bytes (docs/dialect.md).  WSTRING: UTF-16LE.
  std::vector<uint32_t> cps;
  const std::string& s = lit->text;
  for (size_t i = 0; i < s.size();) {
    unsigned char c = static_cast<unsigned char>(s[i]);
    uint32_t cp = c;
    int n = 0;
    if (c >= 0xF0) { cp = c & 7; n = 3; }
    else if (c >= 0xE0) { cp = c & 15; n = 2; }
    else if (c >= 0xC0) { cp = c & 31; n = 1; }
    ++i;
    for (int k = 0; k < n && i < s.size(); ++k, ++i) cp = (cp << 6) | (static_cast<unsigned char>(s[i]) & 63);
    cps.push_back(cp);
  }
  std::string out;
  if (wide) {
    for (uint32_t cp : cps) {
      auto unit = [&](uint32_t u) { out.push_back(static_cast<char>(u & 0xFF)); out.push_back(static_cast<char>(u >> 8)); };
      if (cp >= 0x10000) { cp -= 0x10000; unit(0xD800 + (cp >> 10)); unit(0xDC00 + (cp & 0x3FF)); }
      else unit(cp);
    }
    return out;
  }
  bool latin1 = true;
  for (uint32_t cp : cps) latin1 = latin1 && cp <= 0xFF;
  if (!latin1) return s;
  for (uint32_t cp : cps) out.push_back(static_cast<char>(cp));
  return out;
}

// A packed BIT member: sets or clears its bit (a constant initial value; BIT members
// take constants only).
void CodeGen::initBit(ConstBuffer& buf, uint64_t at, int bit, const Expr* init) {
  llvm::Constant* c = nullptr;
  bool on = init && foldScalar(init, elementary(TypeKind::Bool), c) && c && !c->isNullValue();
  uint8_t mask = static_cast<uint8_t>(1u << bit);
  if (at < buf.bytes.size()) buf.bytes[at] = on ? (buf.bytes[at] | mask) : (buf.bytes[at] & static_cast<uint8_t>(~mask));
}

void CodeGen::writeScalar(ConstBuffer& buf, uint64_t off, const Type* t, llvm::Constant* c) {
  unsigned n = static_cast<unsigned>(sizeOf(t));
  if (auto* ci = llvm::dyn_cast<llvm::ConstantInt>(c)) {
    buf.put(off, ci->getZExtValue(), n);   // iN values fit in 64 bits
  } else if (auto* cf = llvm::dyn_cast<llvm::ConstantFP>(c)) {
    buf.put(off, cf->getValueAPF().bitcastToAPInt().getZExtValue(), n);
  } else if (llvm::isa<llvm::ConstantPointerNull>(c) || c->isNullValue()) {
    buf.put(off, 0, n);
  } else if (c->getType()->isPointerTy()) {
    // A 4-byte slot holds the low address (the image lies below 4 GiB in the 32-bit model).
    buf.relocs[off] = n == 4 ? llvm::ConstantExpr::getPtrToInt(c, i32_) : c;
  }
}

bool CodeGen::foldScalar(const Expr* e, const Type* to, llvm::Constant*& out) {
  if (auto* lit = dyn_cast<LiteralExpr>(e); lit && lit->litKind != LiteralExpr::String && lit->litKind != LiteralExpr::WString) {
    if (auto* c = llvm::dyn_cast_or_null<llvm::Constant>(convert(constantValue(lit, lit->type), lit->type, to, e))) {
      out = c;
      return true;
    }
  }
  // Emit the expression into a scratch function: the IRBuilder's constant
  // folder turns it into a constant when it only involves constants.
  if (!foldFn_)
    foldFn_ = llvm::Function::Create(llvm::FunctionType::get(llvm::Type::getVoidTy(ctx_), false), llvm::Function::InternalLinkage,
                                     "__stc_fold", mod_);
  FnState* savedFs = fs_;
  llvm::DebugLoc savedLoc = b_.getCurrentDebugLocation();
  b_.SetCurrentDebugLocation(llvm::DebugLoc());
  auto savedBlock = b_.GetInsertBlock();
  auto savedPoint = b_.GetInsertPoint();
  bool hadPoint = savedBlock != nullptr;
  FnState st;
  beginFunction(st, foldFn_);
  st.returnBlock = b_.GetInsertBlock();
  unsigned errorsBefore = errors_;
  ++folding_;
  llvm::Value* v = emitValue(e, to);
  --folding_;
  auto* c = llvm::dyn_cast_or_null<llvm::Constant>(v);
  bool ok = c != nullptr && errors_ == errorsBefore;
  if (ok) out = c;
  errors_ = errorsBefore;
  foldFn_->dropAllReferences();
  while (!foldFn_->empty()) foldFn_->begin()->eraseFromParent();
  fs_ = savedFs;
  if (hadPoint) b_.SetInsertPoint(savedBlock, savedPoint);
  else b_.ClearInsertionPoint();
  b_.SetCurrentDebugLocation(savedLoc);
  return ok;
}

void CodeGen::defaultObject(ConstBuffer& buf, uint64_t off, const Type* t, std::vector<DynamicInit>& dyn) {
  if (!t) return;
  switch (t->kind) {
    case TypeKind::Enum:
      if (t->decl && t->decl->init) {
        llvm::Constant* c = nullptr;
        if (foldScalar(t->decl->init, t, c)) writeScalar(buf, off, t, c);
        return;
      }
      if (!t->enumValues.empty()) buf.put(off, static_cast<uint64_t>(t->enumValues.front().second), static_cast<unsigned>(sizeOf(t)));
      return;
    case TypeKind::Subrange:
      buf.put(off, static_cast<uint64_t>(t->lo), static_cast<unsigned>(sizeOf(t)));
      return;
    case TypeKind::Array: {
      ConstBuffer one;
      one.bytes.assign(sizeOf(t->element), 0);
      std::vector<DynamicInit> oneDyn;
      defaultObject(one, 0, t->element, oneDyn);
      if (one.allZero() && oneDyn.empty()) return;
      uint64_t stride = alignUp(sizeOf(t->element), alignOf(t->element));
      uint64_t count = stride ? sizeOf(t) / stride : 0;
      for (uint64_t i = 0; i < count; ++i) {
        std::copy(one.bytes.begin(), one.bytes.end(), buf.bytes.begin() + static_cast<long>(off + i * stride));
        for (auto& [o, c] : one.relocs) buf.relocs[off + i * stride + o] = c;
        for (const DynamicInit& d : oneDyn) dyn.push_back(d.shifted(off + i * stride));
      }
      return;
    }
    case TypeKind::Struct: case TypeKind::Union: case TypeKind::FunctionBlock: case TypeKind::Program: {
      if (t->decl && t->decl->init && (t->kind == TypeKind::Struct || t->kind == TypeKind::Union) && !inTypeDefault_.count(t)) {
        inTypeDefault_.insert(t);
        initObject(buf, off, t, t->decl->init, dyn);
        inTypeDefault_.erase(t);
        return;
      }
      const sema::TypeLayout& l = layout_.of(t);
      if (l.hasVptr) buf.relocs[off] = vtableFor(t);
      size_t firstDyn = dyn.size();
      for (const sema::FieldLayout& f : l.fields) {
        if (!f.type || f.indirect) continue;
        if (f.bit >= 0) {
          initBit(buf, off + f.offset, f.bit, f.decl ? f.decl->init : nullptr);
          continue;
        }
        if (f.decl) initObject(buf, off + f.offset, f.type, f.decl->init, dyn, f.decl);
        else defaultObject(buf, off + f.offset, f.type, dyn);
        if (t->kind == TypeKind::Union) break;   // the first member decides
      }
      // Initial values inside an FB or program may name its other variables
      // (`p : POINTER TO INT := ADR(x)`, `r : REFERENCE TO INT REF= x`).
      if (t->kind == TypeKind::FunctionBlock || t->kind == TypeKind::Program)
        for (size_t k = firstDyn; k < dyn.size(); ++k)
          if (dyn[k].ownerOffset < 0) {
            dyn[k].ownerOffset = static_cast<int64_t>(off);
            dyn[k].ownerType = t;
          }
      return;
    }
    default:
      return;   // zero
  }
}

void CodeGen::initObject(ConstBuffer& buf, uint64_t off, const Type* t, const Expr* init, std::vector<DynamicInit>& dyn, const VarDecl* decl,
                         bool overlay) {
  if (!t) return;
  if (init && decl && decl->bindsReference) {
    dyn.push_back({off, t, init, true});
    return;
  }
  // No initial value: the default of a named alias type (TYPE Percent : INT := 50).
  if (!init && decl && decl->type)
    for (const TypeDecl* td = decl->type->aliasDecl; td && !init; td = td->def ? td->def->aliasDecl : nullptr)
      if (td->init && ((!isa<ArrayInitExpr>(td->init) && !isa<StructInitExpr>(td->init) && !isAggregate(t)) ||
                       (isa<ArrayInitExpr>(td->init) && t->kind == TypeKind::Array)))   // TYPE Row : ARRAY[1..3] OF INT := [1, 2, 3]
        init = td->init;
  if (!init) { defaultObject(buf, off, t, dyn); return; }
  if (auto* ai = dyn_cast<ArrayInitExpr>(init); ai && t->kind == TypeKind::Array) {
    if (!overlay) defaultObject(buf, off, t, dyn);
    uint64_t stride = alignUp(sizeOf(t->element), alignOf(t->element));
    uint64_t count = stride ? sizeOf(t) / stride : 0;
    uint64_t i = 0;
    for (const auto& el : ai->elements)
      for (uint64_t k = 0; k < el.repeat && i < count; ++k, ++i)
        if (el.value) initObject(buf, off + i * stride, t->element, el.value, dyn, nullptr, true);
    return;
  }
  if (auto* si = dyn_cast<StructInitExpr>(init)) {
    if (!overlay) defaultObject(buf, off, t, dyn);
    for (const auto& f : si->fields) {
      const sema::FieldLayout* fl = layout_.field(t, f.name.name);
      if (fl && f.value && fl->bit >= 0) initBit(buf, off + fl->offset, fl->bit, f.value);
      else if (fl && f.value && !fl->indirect) initObject(buf, off + fl->offset, fl->type, f.value, dyn, nullptr, true);
    }
    return;
  }
  const Type* s = strip(t);
  if (s->isString()) {
    if (auto* lit = dyn_cast<LiteralExpr>(init); lit && (lit->litKind == LiteralExpr::String || lit->litKind == LiteralExpr::WString)) {
      bool wide = s->kind == TypeKind::WString;
      std::string bytes = literalBytes(lit, wide);
      uint64_t cap = wide ? 2ull * s->length : s->length;
      if (bytes.size() > cap) bytes.resize(cap);
      std::copy(bytes.begin(), bytes.end(), buf.bytes.begin() + static_cast<long>(off));
      return;
    }
    dyn.push_back({off, t, init});
    return;
  }
  if (isAggregate(s)) {
    dyn.push_back({off, t, init});
    return;
  }
  llvm::Constant* c = nullptr;
  if (foldScalar(init, t, c)) writeScalar(buf, off, t, c);
  else dyn.push_back({off, t, init});
}

// One initial value that runs as code; `base` is where offsets count from.
void CodeGen::emitDynamicInit(llvm::Value* base, const DynamicInit& d) {
  llvm::Value* savedSelf = fs_->self;
  const Type* savedType = fs_->selfType;
  if (d.ownerOffset >= 0) {
    fs_->self = b_.CreateConstInBoundsGEP1_64(i8_, base, static_cast<uint64_t>(d.ownerOffset));
    fs_->selfType = d.ownerType;
  }
  llvm::Value* at = b_.CreateConstInBoundsGEP1_64(i8_, base, d.offset);
  if (d.bind) storeAddress(at, d.type, referenceTarget(d.expr));
  else assign(Address{at, d.type}, d.expr);
  fs_->self = savedSelf;
  fs_->selfType = savedType;
}

void CodeGen::initAt(Address dst, const Expr* init, const VarDecl* decl) {
  const Type* t = dst.type;
  if (init && decl && decl->bindsReference) {
    storeAddress(dst.ptr, dst.type, referenceTarget(init));
    return;
  }
  if (!isAggregate(t) && init && !isa<ArrayInitExpr>(init) && !isa<StructInitExpr>(init)) {
    assign(dst, init);
    return;
  }
  ConstBuffer buf;
  buf.bytes.assign(std::max<uint64_t>(sizeOf(t), 1), 0);
  std::vector<DynamicInit> dyn;
  initObject(buf, 0, t, init, dyn, decl);
  if (!isAggregate(t)) {
    llvm::Type* vt = valueType(t);
    uint64_t raw = 0;
    for (size_t i = 0; i < buf.bytes.size() && i < 8; ++i) raw |= static_cast<uint64_t>(buf.bytes[i]) << (8 * i);
    llvm::Value* v;
    if (vt->isFloatTy()) v = llvm::ConstantFP::get(ctx_, llvm::APFloat(llvm::APFloat::IEEEsingle(), llvm::APInt(32, raw)));
    else if (vt->isDoubleTy()) v = llvm::ConstantFP::get(ctx_, llvm::APFloat(llvm::APFloat::IEEEdouble(), llvm::APInt(64, raw)));
    else if (vt->isPointerTy()) v = llvm::ConstantPointerNull::get(ptrTy_);
    else v = llvm::ConstantInt::get(vt, raw);
    store(dst, v);
    return;
  }
  uint64_t size = sizeOf(t);
  if (buf.allZero()) {
    b_.CreateMemSet(dst.ptr, b_.getInt8(0), size, llvm::MaybeAlign(alignOf(t)));
  } else {
    llvm::Type* ty = nullptr;
    llvm::Constant* c = bufferConstant(buf, &ty);
    auto* g = new llvm::GlobalVariable(mod_, ty, true, llvm::GlobalValue::PrivateLinkage, c, "init");
    g->setUnnamedAddr(llvm::GlobalValue::UnnamedAddr::Global);
    g->setAlignment(llvm::Align(std::max<uint64_t>(alignOf(t), 1)));
    b_.CreateMemCpy(dst.ptr, llvm::MaybeAlign(alignOf(t)), g, llvm::MaybeAlign(alignOf(t)), size);
  }
  for (const DynamicInit& d : dyn) emitDynamicInit(dst.ptr, d);
}

// ------------------------------------------------------------------ vtables

std::string CodeGen::slotKey(const Symbol* m) {
  const PouDecl* d = m->pou ? m->pou->decl : nullptr;
  if (d && d->pouKind == PouKind::PropertyGet) return "__GET_" + asciiUpper(d->owner->name.parts.back().name);
  if (d && d->pouKind == PouKind::PropertySet) return "__SET_" + asciiUpper(d->owner->name.parts.back().name);
  return asciiUpper(m->name);
}

const std::vector<std::pair<std::string, Symbol*>>& CodeGen::vtableSlots(const Type* fb) {
  auto it = vtableSlots_.find(fb);
  if (it != vtableSlots_.end()) return it->second;
  std::vector<std::pair<std::string, Symbol*>> slots;
  if (fb->pou && fb->pou->pou && fb->pou->pou->base) slots = vtableSlots(fb->pou->pou->base->type);
  if (methodsOf_.empty())
    for (Symbol* p : model_.pous)
      if (p->kind == Symbol::Method && p->pou && p->pou->owner) methodsOf_[p->pou->owner].push_back(p);
  for (Symbol* m : methodsOf_[fb->pou]) {
    std::string key = slotKey(m);
    bool replaced = false;
    for (auto& s : slots)
      if (s.first == key) { s.second = m; replaced = true; }
    if (!replaced) slots.push_back({key, m});
  }
  return vtableSlots_[fb] = slots;
}

int CodeGen::vtableSlot(const Type* fb, const std::string& key) {
  // Only function block instances carry a vtable pointer: a PROGRAM's methods are called directly.
  if (!fb || fb->kind != TypeKind::FunctionBlock) return -1;
  const auto& slots = vtableSlots(fb);
  for (size_t i = 0; i < slots.size(); ++i)
    if (slots[i].first == key) return static_cast<int>(i);
  return -1;
}

// {ptr name, ptr body, ptr slot0, ...}
llvm::Constant* CodeGen::vtableFor(const Type* fb) {
  auto it = vtables_.find(fb);
  if (it != vtables_.end()) return it->second;
  std::vector<llvm::Constant*> fields;
  auto* nameArr = llvm::ConstantDataArray::getString(ctx_, fb->name);
  auto* name = new llvm::GlobalVariable(mod_, nameArr->getType(), true, llvm::GlobalValue::PrivateLinkage, nameArr, "typename");
  fields.push_back(name);
  fields.push_back(fb->pou ? static_cast<llvm::Constant*>(functionFor(fb->pou)) : llvm::ConstantPointerNull::get(ptrTy_));
  for (auto& [key, m] : vtableSlots(fb)) {
    const PouDecl* d = m->pou->decl;
    bool callable = d && (d->hasBody || d->pouKind == PouKind::PropertyGet || d->pouKind == PouKind::PropertySet) && !d->isAbstract;
    fields.push_back(callable || isNative(m) ? static_cast<llvm::Constant*>(functionFor(m)) : llvm::ConstantPointerNull::get(ptrTy_));
  }
  auto* init = llvm::ConstantStruct::getAnon(ctx_, fields);
  auto* g = new llvm::GlobalVariable(mod_, init->getType(), true, llvm::GlobalValue::InternalLinkage, init, "st." + fb->name + ".__vtable");
  vtables_[fb] = g;
  vtableOrder_.push_back(g);
  return g;
}

llvm::Value* CodeGen::loadVptr(llvm::Value* self, const ast::Node* at) {
  markSite(at);
  llvm::Value* vptr = b_.CreateAlignedLoad(ptrTy_, self, llvm::MaybeAlign(8));
  checkInVtables(vptr, at);
  return vptr;
}

void CodeGen::checkInVtables(llvm::Value* p, const ast::Node* at) {
  if (!opts_.checks) return;
  if (!vtablesBegin_) {
    vtablesBegin_ = new llvm::GlobalVariable(mod_, i8_, true, llvm::GlobalValue::ExternalLinkage, nullptr, "__stc_vtables.begin");
    vtablesEnd_ = new llvm::GlobalVariable(mod_, i8_, true, llvm::GlobalValue::ExternalLinkage, nullptr, "__stc_vtables.end");
  }
  llvm::Value* ok = b_.CreateAnd(b_.CreateICmpUGE(p, vtablesBegin_), b_.CreateICmpULT(p, vtablesEnd_));
  check(ok, FaultKind::BadVtable, site(at));
}

// Every vtable becomes one element of __stc_vtables, so "is this a vtable of the
// program" is two comparisons (a MEMCPY over an instance cannot make a call jump
// anywhere else).
void CodeGen::finishVtables() {
  if (vtableOrder_.empty()) {
    if (vtablesBegin_) {
      vtablesBegin_->replaceAllUsesWith(llvm::ConstantPointerNull::get(ptrTy_));
      vtablesEnd_->replaceAllUsesWith(llvm::ConstantPointerNull::get(ptrTy_));
      vtablesBegin_->eraseFromParent();
      vtablesEnd_->eraseFromParent();
    }
    return;
  }
  std::vector<llvm::Constant*> inits;
  for (llvm::GlobalVariable* g : vtableOrder_) inits.push_back(g->getInitializer());
  auto* all = llvm::ConstantStruct::getAnon(ctx_, inits);
  auto* big = new llvm::GlobalVariable(mod_, all->getType(), true, llvm::GlobalValue::InternalLinkage, all, "__stc_vtables");
  big->setAlignment(llvm::Align(8));
  for (size_t k = 0; k < vtableOrder_.size(); ++k) {
    llvm::Constant* at = llvm::ConstantExpr::getInBoundsGetElementPtr(all->getType(), big, llvm::ArrayRef<llvm::Constant*>{b_.getInt32(0), b_.getInt32(static_cast<uint32_t>(k))});
    vtableOrder_[k]->replaceAllUsesWith(at);
    vtableOrder_[k]->eraseFromParent();
  }
  if (vtablesBegin_) {
    vtablesBegin_->replaceAllUsesWith(big);
    vtablesEnd_->replaceAllUsesWith(llvm::ConstantExpr::getInBoundsGetElementPtr(all->getType(), big, llvm::ArrayRef<llvm::Constant*>{b_.getInt32(1)}));
    vtablesBegin_->eraseFromParent();
    vtablesEnd_->eraseFromParent();
  }
  vtables_.clear();
  vtableOrder_.clear();
}

}  // namespace stc::codegen
