// The diagnostics engine: every stage reports through it.  Diagnostics are
// collected, then rendered as clang-style text or JSON by the driver, or
// matched against `expected-*` comments by the verifier.
#pragma once

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "basic/SourceManager.h"

namespace stc {

enum class Severity { Note, Warning, Error };

struct FixIt {
  SourceRange range;        // text to replace (empty range = insertion)
  std::string replacement;
};

struct Diagnostic {
  Severity severity = Severity::Error;
  SourceLoc loc;
  std::vector<SourceRange> ranges;   // highlighted with ~
  std::string message;
  std::string code;                  // e.g. "undeclared-name" or "-Wunused-variable"
  std::vector<FixIt> fixits;
  std::vector<Diagnostic> notes;
};

class DiagnosticsEngine;

// Returned by DiagnosticsEngine::error() etc.; the diagnostic is committed
// when the builder goes out of scope, so callers can chain ranges and notes.
class DiagBuilder {
public:
  DiagBuilder(DiagnosticsEngine* engine, Diagnostic d) : engine_(engine), diag_(std::move(d)) {}
  DiagBuilder(DiagBuilder&& o) noexcept : engine_(o.engine_), diag_(std::move(o.diag_)) { o.engine_ = nullptr; }
  DiagBuilder(const DiagBuilder&) = delete;
  ~DiagBuilder();

  DiagBuilder& range(SourceRange r) { if (r.valid()) diag_.ranges.push_back(r); return *this; }
  DiagBuilder& fixit(SourceRange r, std::string text) { diag_.fixits.push_back({r, std::move(text)}); return *this; }
  DiagBuilder& note(SourceLoc loc, std::string message, SourceRange r = {});

private:
  DiagnosticsEngine* engine_;
  Diagnostic diag_;
};

struct DiagnosticOptions {
  bool warningsAsErrors = false;
  bool noWarnings = false;
  std::set<std::string> disabledWarnings;   // codes without the "-W" prefix
  unsigned errorLimit = 100;                // 0 = unlimited
};

class DiagnosticsEngine {
public:
  explicit DiagnosticsEngine(const SourceManager& sm) : sm_(sm) {}

  DiagBuilder error(SourceLoc loc, std::string message, std::string code = {});
  DiagBuilder warning(SourceLoc loc, std::string message, std::string warningName);
  DiagBuilder note(SourceLoc loc, std::string message);

  void commit(Diagnostic d);

  const std::vector<Diagnostic>& diagnostics() const { return diags_; }
  unsigned errorCount() const { return errors_; }
  unsigned warningCount() const { return warnings_; }
  bool hasErrors() const { return errors_ != 0; }
  bool limitReached() const { return opts.errorLimit && errors_ >= opts.errorLimit; }
  void clear() { diags_.clear(); errors_ = warnings_ = 0; }

  const SourceManager& sourceManager() const { return sm_; }
  DiagnosticOptions opts;

private:
  const SourceManager& sm_;
  std::vector<Diagnostic> diags_;
  unsigned errors_ = 0, warnings_ = 0;
};

// The diagnostic with its locations mapped out of generated buffers
// (SourceManager::originalLoc); the renderers apply it.
Diagnostic originalDiagnostic(const SourceManager& sm, const Diagnostic& d);

// Renderers.
std::string renderText(const SourceManager& sm, const Diagnostic& d, bool color = false);
std::string renderJson(const SourceManager& sm, const std::vector<Diagnostic>& diags);

// Levenshtein distance, case-insensitive; used for "did you mean" hints.
unsigned editDistance(std::string_view a, std::string_view b, unsigned limit = 100);
// Best candidate within a distance proportional to the name length, or "".
std::string closestMatch(std::string_view name, const std::vector<std::string>& candidates);

}  // namespace stc
