#include "ast/AST.h"

#include "basic/Text.h"

namespace stc::ast {

std::string QualifiedName::str() const {
  std::string s;
  for (size_t i = 0; i < parts.size(); ++i) {
    if (i) s += '.';
    s += parts[i].name;
  }
  return s;
}

const char* spelling(UnaryOp op) {
  switch (op) {
    case UnaryOp::Neg: return "-";
    case UnaryOp::Plus: return "+";
    case UnaryOp::Not: return "NOT";
  }
  return "?";
}

const char* spelling(BinaryOp op) {
  switch (op) {
    case BinaryOp::Pow: return "**";
    case BinaryOp::Mul: return "*";
    case BinaryOp::Div: return "/";
    case BinaryOp::Mod: return "MOD";
    case BinaryOp::Add: return "+";
    case BinaryOp::Sub: return "-";
    case BinaryOp::Lt: return "<";
    case BinaryOp::Gt: return ">";
    case BinaryOp::Le: return "<=";
    case BinaryOp::Ge: return ">=";
    case BinaryOp::Eq: return "=";
    case BinaryOp::Ne: return "<>";
    case BinaryOp::And: return "AND";
    case BinaryOp::AndThen: return "AND_THEN";
    case BinaryOp::Xor: return "XOR";
    case BinaryOp::Or: return "OR";
    case BinaryOp::OrElse: return "OR_ELSE";
  }
  return "?";
}

const char* spelling(VarSection s) {
  switch (s) {
    case VarSection::Var: return "VAR";
    case VarSection::Input: return "VAR_INPUT";
    case VarSection::Output: return "VAR_OUTPUT";
    case VarSection::InOut: return "VAR_IN_OUT";
    case VarSection::Temp: return "VAR_TEMP";
    case VarSection::Stat: return "VAR_STAT";
    case VarSection::Inst: return "VAR_INST";
    case VarSection::Global: return "VAR_GLOBAL";
    case VarSection::External: return "VAR_EXTERNAL";
    case VarSection::Access: return "VAR_ACCESS";
    case VarSection::Config: return "VAR_CONFIG";
  }
  return "VAR";
}

const char* spelling(PouKind k) {
  switch (k) {
    case PouKind::Program: return "PROGRAM";
    case PouKind::Function: return "FUNCTION";
    case PouKind::FunctionBlock: return "FUNCTION_BLOCK";
    case PouKind::Method: return "METHOD";
    case PouKind::Property: return "PROPERTY";
    case PouKind::Action: return "ACTION";
    case PouKind::Interface: return "INTERFACE";
    case PouKind::PropertyGet: return "GET accessor";
    case PouKind::PropertySet: return "SET accessor";
  }
  return "POU";
}

const Pragma* findAttribute(const std::vector<Pragma>& attrs, std::string_view name) {
  for (const Pragma& p : attrs)
    if (equalsIgnoreCase(p.name, name)) return &p;
  return nullptr;
}

}  // namespace stc::ast
