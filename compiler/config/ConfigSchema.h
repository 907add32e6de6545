// The schema of project.toml and scenarios/*.toml, and the one way to read
// them (docs/projects.md, "The schema").
//
// Every reader of these files (compiler/driver/Project.cpp, stdlib-motion's
// [[axis]] / [[io]] / [[cam]] readers, tools/stc/TestCommand.cpp) gets its
// table from loadProjectToml / loadScenarioToml: the file is checked to be a
// regular file (no directory, FIFO, device or symbolic-link loop: never a
// hang), parsed, and validated against the schema below: unknown keys (with a
// "did you mean"), types, required keys, finite numbers in their ranges,
// durations, choices, unique names.  Errors read
// `file:line:col: error: <what> (the offending text)`.  The readers then only
// convert values and check what needs the program (variable names, types).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <toml++/toml.h>

namespace stc::config {

// ---------------------------------------------------------------- files

// Whether `path` names a regular file (following symbolic links, but not a
// loop).  False with `why` ("is a directory", "is a FIFO (named pipe)",
// "is a symbolic link loop", "does not exist" ...) otherwise; a missing file
// is fine when `mayBeMissing` (then `exists` tells).
bool checkRegularFile(const std::string& path, std::string& why, bool mayBeMissing = false, bool* exists = nullptr);

// Reads a regular file of at most `maxBytes` without ever blocking (the type
// is checked before and after opening, which is non-blocking).
bool readRegularFile(const std::string& path, std::string& text, std::string& why, uint64_t maxBytes = 64u << 20);

// ---------------------------------------------------------------- schema

enum class Kind {
  String,       // any string (choices: one of them; nonEmpty)
  Name,         // an ST identifier: letter or '_', then letters, digits, '_'
  VarPath,      // an ST variable path: names separated by '.', with [index] parts
  Unit,         // a unit of measure ("mm", "deg", "°"): 1 to 16 characters, none of them
                // blank, a control character or one of , " ' = # [ ]
  Integer,      // a TOML integer in [min, max]
  Number,       // a TOML integer or float, finite, in [min, max] (minOpen: > min)
  Bool,
  Duration,     // a duration string (config::parseDuration), >= 0 (positive: > 0)
  Sampling,     // a positive duration string or one of `choices` (a scenario's sample = "10ms" | "change")
  Literal,      // an ST literal: a string, boolean, integer or finite float
  NumberPair,   // [a, b] of Numbers in [min, max] (minOpen: both > min); ordered: a <= b
  DurationPair, // ["T1", "T2"], T1 <= T2
  NumberList,   // [x, ...] of Numbers (nested lists of count numbers when count > 0)
  StringList,   // ["...", ...] of the element kind `element` (String, Name or VarPath)
  Table,        // a table of `schema`
  TableArray,   // [[name]]: tables of `schema`
};

struct Schema;

struct Field {
  const char* name;
  Kind kind;
  bool required = false;
  double min = -1e300, max = 1e300;
  bool minOpen = false;           // min is exclusive
  bool positive = false;          // Duration: > 0
  std::vector<const char*> choices;
  const Schema* schema = nullptr; // Table / TableArray
  Kind element = Kind::String;    // StringList
  size_t count = 0;               // NumberList: each element is a list of `count` numbers
  bool nonEmpty = false;          // String / StringList / NumberList / TableArray
  bool ordered = false;           // NumberPair: a <= b (DurationPair always)
  const char* unique = nullptr;   // TableArray: this key's value is unique (case-insensitive)
};

struct Schema {
  const char* what;               // "[[axis]]", "the scenario" ... for messages
  std::vector<Field> fields;
  // Pairs of keys with first <= second when both are given.
  std::vector<std::pair<const char*, const char*>> ordered;
  // Groups of keys of which at most one may be given / exactly one must be.
  std::vector<std::vector<const char*>> atMostOne, exactlyOne;
};

const Schema& projectSchema();    // project.toml
const Schema& scenarioSchema();   // scenarios/*.toml

// Validates `root` against `schema`; the first error as
// "shown:line:col: error: ..." in `error`.
bool validate(const toml::table& root, const Schema& schema, const std::string& shown, std::string& error);

// Reads, parses and validates `path` (shown in messages as `shown`).
bool loadToml(const std::string& path, const std::string& shown, const Schema& schema, toml::table& out, std::string& error);
// dir/project.toml against projectSchema(); messages name dir/project.toml.
bool loadProjectToml(const std::string& dir, toml::table& out, std::string& error);

// "file:line:col" of a node (just "file" when it has no position).
std::string where(const std::string& shown, const toml::node& n);

// The closest of `candidates` to `word` by edit distance, if close enough
// ("" otherwise): the "did you mean" of unknown keys.
std::string closest(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace stc::config
