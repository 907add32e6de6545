#include "config/ConfigSchema.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <sstream>

#include "config/Duration.h"

namespace stc::config {

// ---------------------------------------------------------------- files

namespace {

const char* typeName(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISFIFO(m)) return "a FIFO (named pipe)";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

}  // namespace

bool checkRegularFile(const std::string& path, std::string& why, bool mayBeMissing, bool* exists) {
  if (exists) *exists = false;
  struct stat st {};
  // stat follows symbolic links and fails with ELOOP on a loop: nothing is opened.
  if (::stat(path.c_str(), &st) != 0) {
    const int e = errno;
    if (e == ELOOP) return why = "is a symbolic link loop", false;
    if (e == ENOENT) {
      struct stat l {};
      // A file that may be missing may also be a link to a missing file (it is created through it).
      if (mayBeMissing) return true;
      if (::lstat(path.c_str(), &l) == 0 && S_ISLNK(l.st_mode)) return why = "is a dangling symbolic link", false;
      return why = "does not exist", false;
    }
    return why = std::string("cannot be read: ") + std::strerror(e), false;
  }
  if (exists) *exists = true;
  if (!S_ISREG(st.st_mode)) return why = std::string("is ") + typeName(st.st_mode) + ", not a file", false;
  return true;
}

bool readRegularFile(const std::string& path, std::string& text, std::string& why, uint64_t maxBytes) {
  if (!checkRegularFile(path, why)) return false;
  // O_NONBLOCK: if the file was replaced by a FIFO since the check, open does not wait for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return why = std::string("cannot be opened: ") + std::strerror(errno), false;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return why = std::string("is ") + typeName(st.st_mode) + ", not a file", false;
  }
  if (static_cast<uint64_t>(st.st_size) > maxBytes) {
    ::close(fd);
    return why = "is larger than " + std::to_string(maxBytes >> 20) + " MB", false;
  }
  text.clear();
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ::close(fd);
      return why = std::string("cannot be read: ") + std::strerror(errno), false;
    }
    if (n == 0) break;
    text.append(buf, static_cast<size_t>(n));
    if (text.size() > maxBytes) {
      ::close(fd);
      return why = "is larger than " + std::to_string(maxBytes >> 20) + " MB", false;
    }
  }
  ::close(fd);
  return true;
}

// ---------------------------------------------------------------- helpers

std::string where(const std::string& shown, const toml::node& n) {
  const auto& s = n.source();
  if (!s.begin) return shown;
  return shown + ":" + std::to_string(s.begin.line) + ":" + std::to_string(s.begin.column);
}

std::string closest(const std::string& word, const std::vector<std::string>& candidates) {
  auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  const std::string w = lower(word.substr(0, 64));
  std::string best;
  size_t bestD = SIZE_MAX;
  for (const std::string& cand : candidates) {
    const std::string c = lower(cand);
    // Levenshtein distance with adjacent transpositions (optimal string alignment).
    std::vector<std::vector<size_t>> d(w.size() + 1, std::vector<size_t>(c.size() + 1));
    for (size_t i = 0; i <= w.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= c.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= w.size(); ++i)
      for (size_t j = 1; j <= c.size(); ++j) {
        d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (w[i - 1] == c[j - 1] ? 0 : 1)});
        if (i > 1 && j > 1 && w[i - 1] == c[j - 2] && w[i - 2] == c[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    size_t dist = d[w.size()][c.size()];
    // One name a prefix of the other ("trapezoid" for "trapez"): as close as a typo.
    if (std::min(w.size(), c.size()) >= 4 && (w.compare(0, c.size(), c) == 0 || c.compare(0, w.size(), w) == 0)) dist = std::min<size_t>(dist, 1);
    if (dist < bestD) bestD = dist, best = cand;
  }
  const size_t allowed = std::max<size_t>(1, std::min<size_t>(3, (word.size() + 2) / 4));
  return bestD <= allowed ? best : std::string();
}

namespace {

// The value as written (TOML syntax), shortened for messages.
std::string text(const toml::node& n) {
  std::ostringstream s;
  n.visit([&](auto&& v) {
    if constexpr (toml::is_string<decltype(v)>) {
      std::string q = "\"";
      for (char c : v.get()) {
        if (c == '"' || c == '\\') q += '\\', q += c;
        else if (static_cast<unsigned char>(c) < 0x20) q += "\\u00" + std::string(1, "0123456789abcdef"[c >> 4]) + "0123456789abcdef"[c & 15];
        else q += c;
      }
      s << q << '"';
    } else {
      s << v;
    }
  });
  std::string t = s.str();
  for (char& c : t)
    if (c == '\n' || c == '\r') c = ' ';
  if (t.size() > 60) t = t.substr(0, 57) + "...";
  return t;
}

bool isName(std::string_view s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isalnum(c) || c == '_'; });
}

// A unit of measure (Kind::Unit): 1 to 16 UTF-8 characters, no blanks,
// control characters or characters that delimit it in traces and labels.
static bool isUnit(std::string_view s) {
  size_t chars = 0;
  for (unsigned char c : s) {
    if (c < 0x21 || c == 0x7f || std::strchr(",\"'=#[]", c)) return false;
    if ((c & 0xC0) != 0x80) ++chars;
  }
  return chars >= 1 && chars <= 16;
}

// NAME{.NAME | [i, ...]}: what --watch, traces and scenario checks take.
bool isVarPath(std::string_view s) {
  size_t i = 0;
  auto name = [&] {
    const size_t b = i;
    if (i >= s.size() || !(std::isalpha(static_cast<unsigned char>(s[i])) || s[i] == '_')) return false;
    while (i < s.size() && (std::isalnum(static_cast<unsigned char>(s[i])) || s[i] == '_')) ++i;
    return i > b;
  };
  if (!name()) return false;
  while (i < s.size()) {
    if (s[i] == '.') {
      ++i;
      if (!name()) return false;
    } else if (s[i] == '[') {
      const size_t close = s.find(']', i);
      if (close == std::string_view::npos || close == i + 1) return false;
      for (size_t k = i + 1; k < close; ++k)
        if (!(std::isdigit(static_cast<unsigned char>(s[k])) || s[k] == ',' || s[k] == '-' || s[k] == ' ')) return false;
      i = close + 1;
    } else if (s[i] == '^') {
      ++i;
    } else {
      return false;
    }
  }
  return true;
}

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

struct Validator {
  const std::string& shown;
  std::string& error;

  bool fail(const toml::node& n, const std::string& msg) {
    error = where(shown, n) + ": error: " + msg;
    return false;
  }
  bool failKey(const toml::key& k, const toml::node& n, const std::string& msg) {
    const auto& s = k.source();
    error = (s.begin ? shown + ":" + std::to_string(s.begin.line) + ":" + std::to_string(s.begin.column) : where(shown, n)) + ": error: " + msg;
    return false;
  }

  std::string range(const Field& f) {
    const bool lo = f.min > -1e299, hi = f.max < 1e299;
    if (lo && hi) return std::string(f.minOpen ? "> " : ">= ") + number(f.min) + " and <= " + number(f.max);
    if (lo) return std::string(f.minOpen ? "> " : ">= ") + number(f.min);
    if (hi) return "<= " + number(f.max);
    return "finite";
  }

  bool numberIn(const Field& f, const std::string& label, const toml::node& n, double& out) {
    std::optional<double> d;
    if (auto i = n.value_exact<int64_t>()) d = static_cast<double>(*i);
    else if (auto x = n.value_exact<double>()) d = *x;
    if (!d) return fail(n, label + " = " + text(n) + ": a number is expected");
    if (!std::isfinite(*d)) return fail(n, label + " = " + text(n) + ": the number must be finite");
    if (*d < f.min || *d > f.max || (f.minOpen && *d == f.min))
      return fail(n, label + " = " + text(n) + ": out of range (must be " + range(f) + ")");
    out = *d;
    return true;
  }

  bool stringOf(const Field& f, Kind kind, const std::string& label, const toml::node& n) {
    auto s = n.value_exact<std::string>();
    if (!s) return fail(n, label + " = " + text(n) + ": a string is expected");
    if (kind == Kind::Name && !isName(*s)) return fail(n, label + " = " + text(n) + ": an ST name is expected (a letter or '_', then letters, digits, '_')");
    if (kind == Kind::VarPath && !isVarPath(*s)) return fail(n, label + " = " + text(n) + ": a variable name is expected (e.g. \"GVL.bStart\", \"MAIN.a[2]\")");
    if (f.nonEmpty && s->empty()) return fail(n, label + ": must not be empty");
    if (kind == Kind::Unit && !isUnit(*s))
      return fail(n, label + " = " + text(n) + ": a unit of measure is expected (e.g. \"mm\", \"deg\"): 1 to 16 characters, no blanks, " +
                         "control characters or any of , \" ' = # [ ]");
    if (!f.choices.empty() && kind == Kind::String &&
        std::find_if(f.choices.begin(), f.choices.end(), [&](const char* c) { return *s == c; }) == f.choices.end()) {
      std::string list;
      for (size_t i = 0; i < f.choices.size(); ++i) list += std::string(i ? (i + 1 == f.choices.size() ? " or " : ", ") : "") + "\"" + f.choices[i] + "\"";
      std::string hint = closest(*s, std::vector<std::string>(f.choices.begin(), f.choices.end()));
      return fail(n, label + " = " + text(n) + ": must be " + list + (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
    }
    return true;
  }

  bool field(const Field& f, const std::string& owner, const toml::node& n) {
    const std::string label = owner.empty() ? f.name : owner + " " + f.name;
    switch (f.kind) {
      case Kind::String:
      case Kind::Name:
      case Kind::VarPath:
      case Kind::Unit: return stringOf(f, f.kind, label, n);
      case Kind::Bool:
        if (!n.is_boolean()) return fail(n, label + " = " + text(n) + ": true or false is expected");
        return true;
      case Kind::Integer: {
        auto i = n.value_exact<int64_t>();
        if (!i) return fail(n, label + " = " + text(n) + ": an integer is expected");
        if (!f.choices.empty()) {
          std::string list;
          bool found = false;
          for (size_t k = 0; k < f.choices.size(); ++k) {
            found = found || std::to_string(*i) == f.choices[k];
            list += std::string(k ? (k + 1 == f.choices.size() ? " or " : ", ") : "") + f.choices[k];
          }
          if (!found) return fail(n, label + " = " + text(n) + ": must be " + list);
        }
        if (static_cast<double>(*i) < f.min || static_cast<double>(*i) > f.max)
          return fail(n, label + " = " + text(n) + ": out of range (must be " + range(f) + ")");
        return true;
      }
      case Kind::Number: {
        double d;
        return numberIn(f, label, n, d);
      }
      case Kind::Duration: {
        auto s = n.value_exact<std::string>();
        if (!s) return fail(n, label + " = " + text(n) + ": a duration string is expected (e.g. \"10ms\", \"1.5s\", \"T#1h30m\")");
        int64_t ns = 0;
        std::string why;
        if (!parseDuration(*s, f.positive ? DurationSign::Positive : DurationSign::NonNegative, ns, &why)) return fail(n, label + ": " + why);
        return true;
      }
      case Kind::Sampling: {
        auto s = n.value_exact<std::string>();
        std::string list;
        for (size_t i = 0; i < f.choices.size(); ++i) list += std::string(" or \"") + f.choices[i] + "\"";
        if (!s) return fail(n, label + " = " + text(n) + ": a duration string (e.g. \"10ms\")" + list + " is expected");
        if (std::find_if(f.choices.begin(), f.choices.end(), [&](const char* c) { return *s == c; }) != f.choices.end()) return true;
        int64_t ns = 0;
        std::string why;
        if (parseDuration(*s, DurationSign::Positive, ns, &why)) return true;
        // Not a duration: a misspelt choice ("chnage"), else the duration's own message.
        const std::string hint = closest(*s, std::vector<std::string>(f.choices.begin(), f.choices.end()));
        if (!hint.empty() || s->find_first_of("0123456789") == std::string::npos)
          return fail(n, label + " = " + text(n) + ": a duration (e.g. \"10ms\")" + list + " is expected" +
                             (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
        return fail(n, label + ": " + why);
      }
      case Kind::Literal: {
        if (auto d = n.value_exact<double>(); d && !std::isfinite(*d)) return fail(n, label + " = " + text(n) + ": the number must be finite");
        if (!n.is_string() && !n.is_boolean() && !n.is_integer() && !n.is_floating_point())
          return fail(n, label + " = " + text(n) + ": an ST literal is expected (a string such as \"TRUE\", \"42\", \"T#1s\", or a boolean or number)");
        return true;
      }
      case Kind::NumberPair:
      case Kind::DurationPair: {
        const toml::array* a = n.as_array();
        const bool dur = f.kind == Kind::DurationPair;
        if (!a || a->size() != 2) return fail(n, label + " = " + text(n) + (dur ? ": [\"T1\", \"T2\"] is expected" : ": [low, high] (two numbers) is expected"));
        double v[2];
        for (size_t i = 0; i < 2; ++i) {
          const toml::node& e = *a->get(i);
          if (dur) {
            auto s = e.value_exact<std::string>();
            int64_t ns = 0;
            std::string why;
            if (!s) return fail(e, label + ": " + text(e) + ": a duration string is expected");
            if (!parseDuration(*s, DurationSign::NonNegative, ns, &why)) return fail(e, label + ": " + why);
            v[i] = static_cast<double>(ns);
          } else if (!numberIn(f, label, e, v[i])) {
            return false;
          }
        }
        if ((dur || f.ordered) && v[0] > v[1]) return fail(n, label + " = " + text(n) + ": the first value must not be greater than the second");
        return true;
      }
      case Kind::NumberList: {
        const toml::array* a = n.as_array();
        if (!a) return fail(n, label + " = " + text(n) + ": an array of numbers is expected");
        if (f.nonEmpty && a->empty()) return fail(n, label + ": must not be empty");
        for (const toml::node& e : *a) {
          if (f.count) {
            const toml::array* row = e.as_array();
            if (!row || row->size() != f.count)
              return fail(e, label + ": " + text(e) + ": each element is an array of " + std::to_string(f.count) + " numbers");
            for (const toml::node& x : *row) {
              double d;
              if (!numberIn(f, label, x, d)) return false;
            }
          } else {
            double d;
            if (!numberIn(f, label, e, d)) return false;
          }
        }
        return true;
      }
      case Kind::StringList: {
        const toml::array* a = n.as_array();
        if (!a) return fail(n, label + " = " + text(n) + ": an array of strings is expected");
        if (f.nonEmpty && a->empty()) return fail(n, label + ": must not be empty");
        Field e = f;
        e.nonEmpty = true;
        for (const toml::node& x : *a)
          if (!stringOf(e, f.element, label, x)) return false;
        return true;
      }
      case Kind::Table: {
        const toml::table* t = n.as_table();
        if (!t) return fail(n, label + ": a table is expected ([" + f.name + "])");
        return table(*t, *f.schema, n);
      }
      case Kind::TableArray: {
        const toml::array* a = n.as_array();
        if (!a || !a->is_array_of_tables())
          return fail(n, std::string("'") + f.name + "' must be an array of tables ([[" + f.name + "]])");
        if (a->size() > 100000) return fail(n, std::string("more than 100000 [[") + f.name + "]] tables");
        std::vector<std::pair<std::string, const toml::node*>> seen;
        for (const toml::node& e : *a) {
          if (!table(*e.as_table(), *f.schema, e)) return false;
          if (f.unique)
            if (auto s = (*e.as_table())[f.unique].value_exact<std::string>()) {
              std::string key = *s;
              for (char& c : key) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
              seen.emplace_back(std::move(key), (*e.as_table()).get(f.unique));
            }
        }
        if (f.unique) {
          std::vector<size_t> order(seen.size());
          for (size_t i = 0; i < order.size(); ++i) order[i] = i;
          std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return seen[x].first < seen[y].first; });
          for (size_t i = 1; i < order.size(); ++i)
            if (seen[order[i]].first == seen[order[i - 1]].first) {
              const size_t first = std::min(order[i], order[i - 1]), second = std::max(order[i], order[i - 1]);
              return fail(*seen[second].second, std::string("[[") + f.name + "]] " + f.unique + " = " + text(*seen[second].second) +
                                                    " is given twice (first at " + where(shown, *seen[first].second) + "; names are case-insensitive)");
            }
        }
        return true;
      }
    }
    return true;
  }

  bool table(const toml::table& t, const Schema& s, const toml::node& self) {
    std::vector<std::string> names;
    for (const Field& f : s.fields) names.emplace_back(f.name);
    for (auto&& [k, v] : t) {
      auto f = std::find_if(s.fields.begin(), s.fields.end(), [&](const Field& x) { return k.str() == x.name; });
      if (f == s.fields.end()) {
        std::string key(k.str().substr(0, 60));
        std::string hint = closest(key, names);
        std::string list;
        for (size_t i = 0; i < names.size(); ++i) list += (i ? ", " : "") + names[i];
        return failKey(k, v, "unknown key '" + key + "' in " + s.what +
                                 (hint.empty() ? " (known keys: " + list + ")" : "; did you mean '" + hint + "'?"));
      }
      if (!field(*f, s.what[0] == '[' ? s.what : "", v)) return false;
    }
    for (const Field& f : s.fields)
      if (f.required && !t.get(f.name)) return fail(self, std::string(s.what) + " needs " + f.name);
    for (const auto& [lo, hi] : s.ordered) {
      const toml::node *a = t.get(lo), *b = t.get(hi);
      if (a && b && a->value<double>() && b->value<double>() && *a->value<double>() > *b->value<double>())
        return fail(*b, std::string(s.what) + " " + hi + " = " + text(*b) + " is less than " + lo + " = " + text(*a));
    }
    auto given = [&](const std::vector<const char*>& keys, std::string& list) {
      int n = 0;
      for (size_t i = 0; i < keys.size(); ++i) {
        n += t.get(keys[i]) ? 1 : 0;
        list += std::string(i ? (i + 1 == keys.size() ? " or " : ", ") : "") + keys[i];
      }
      return n;
    };
    for (const auto& g : s.atMostOne) {
      std::string list;
      if (given(g, list) > 1) return fail(self, std::string(s.what) + ": give only one of " + list);
    }
    for (const auto& g : s.exactlyOne) {
      std::string list;
      if (given(g, list) != 1) return fail(self, std::string(s.what) + " needs exactly one of " + list);
    }
    return true;
  }
};

// ---------------------------------------------------------------- the schemas

Field str(const char* n, std::vector<const char*> choices = {}) {
  Field f{n, Kind::String};
  f.choices = std::move(choices);
  return f;
}
Field kind(const char* n, Kind k, bool required = false) {
  Field f{n, k};
  f.required = required;
  return f;
}
Field num(const char* n, double lo, double hi, bool loOpen = false) {
  Field f{n, Kind::Number};
  f.min = lo, f.max = hi, f.minOpen = loOpen;
  return f;
}
Field integer(const char* n, double lo, double hi) {
  Field f{n, Kind::Integer};
  f.min = lo, f.max = hi;
  return f;
}
Field pair(const char* n, double lo, double hi, bool loOpen = false) {
  Field f = num(n, lo, hi, loOpen);
  f.kind = Kind::NumberPair;
  return f;
}
Field list(const char* n, Kind element, bool required = false) {
  Field f{n, Kind::StringList};
  f.element = element, f.required = required, f.nonEmpty = required;
  return f;
}
Field tables(const char* n, const Schema& s, const char* unique = nullptr) {
  Field f{n, Kind::TableArray};
  f.schema = &s, f.unique = unique;
  return f;
}
Field required(Field f) {
  f.required = true;
  return f;
}
Field ordered(Field f) {
  f.ordered = true;
  return f;
}
Field sampling(const char* n, std::vector<const char*> choices) {
  Field f{n, Kind::Sampling};
  f.choices = std::move(choices);
  return f;
}
Field positiveDuration(const char* n) {
  Field f{n, Kind::Duration};
  f.positive = true;
  return f;
}

// Plausibility bounds as in stdlib-motion/core/InputBounds.h.
constexpr double kPos = 1e12, kVel = 1e9, kAcc = 1e12, kJerk = 1e15;
const std::vector<const char*> kFaultKinds = {"drive_error", "communication_lost", "communication_restored", "limit_positive", "limit_negative",
                                              "limits_released"};

}  // namespace

const Schema& projectSchema() {
  static const Schema project{"[project]",
                              {[] { Field f = str("name"); f.nonEmpty = true; return f; }(), str("description"), list("libraries", Kind::Name), str("motion_profile", {"amc1600c", "leadshine_pmc600"}),
                               [] { Field f = str("data_dir"); f.nonEmpty = true; return f; }()}};
  static const Schema build{"[build]", {str("dialect", {"codesys", "iec"}), list("defines", Kind::Name), [] { Field f = integer("address_model", 32, 64); f.choices = {"32", "64"}; return f; }()}};
  static const Schema task{"[[task]]",
                           {required(kind("name", Kind::Name)), positiveDuration("interval"), kind("event", Kind::VarPath),
                            integer("priority", 0, 31), list("programs", Kind::Name, true)},
                           {},
                           {},
                           {{"interval", "event"}}};
  static const Schema axisFault{"[[axis.fault]]", {required(kind("at", Kind::Duration)), required(str("kind", kFaultKinds))}};
  static const Schema axis{
      "[[axis]]",
      {required(kind("name", Kind::VarPath)), str("type", {"servo", "virtual", "encoder", "pulse"}), kind("task", Kind::Name),
       num("period", 0, kPos), num("increments_per_unit", 0, 1e12, true), num("encoder_resolution", 0, 1e12, true),
       pair("gear_ratio", 0, 1e12, true), num("units_per_revolution", 0, kPos, true), num("max_velocity", 0, kVel),
       num("max_acceleration", 0, kAcc), num("max_deceleration", 0, kAcc), num("max_jerk", 0, kJerk), num("error_deceleration", 0, kAcc),
       num("sw_limit_positive", -kPos, kPos), num("sw_limit_negative", -kPos, kPos), str("drive", {"ideal", "lag"}), num("lag_time", 0, 10),
       num("kv", 0, 10000, true), num("following_error_limit", 0, kPos), num("inertia", 0, 1e12), num("encoder_velocity", -kVel, kVel),
       num("limit_switch_positive", -kPos, kPos), num("limit_switch_negative", -kPos, kPos), ordered(pair("home_switch", -kPos, kPos)),
       num("index_period", 0, kPos), num("index_offset", -kPos, kPos), str("ramp", {"trapez", "quadratic", "quadratic_ramp"}),
       integer("encoder_channel", 0, 2), kind("unit", Kind::Unit), tables("fault", axisFault)},
      {{"sw_limit_negative", "sw_limit_positive"}, {"limit_switch_negative", "limit_switch_positive"}},
      {{"increments_per_unit", "encoder_resolution"}, {"increments_per_unit", "units_per_revolution"}, {"increments_per_unit", "gear_ratio"}}};
  static const Schema group{"[[group]]", {required(kind("name", Kind::VarPath)), [] {
                              Field f = list("axes", Kind::VarPath, true);
                              f.count = 0;
                              return f;
                            }()}};
  static const Schema io{"[[io]]",
                         {required(kind("var", Kind::VarPath)), required(str("kind", {"axis_window", "delay"})), kind("axis", Kind::VarPath),
                          ordered(pair("window", -kPos, kPos)), kind("source", Kind::VarPath), kind("delay", Kind::Duration)}};
  static const Schema tappet{"[[cam.tappets]]",
                             {required(num("x", -kPos, kPos)), required(integer("group", 1, 512)), str("positive", {"on", "off", "invert", "none"}),
                              str("negative", {"on", "off", "invert", "none"})}};
  static const Schema segment{"[[cam.segments]]",
                              {required(str("law", {"linear", "harmonic", "cycloid", "modified_sine", "modified_trapezoid", "poly345"})),
                               required(pair("to", -kPos, kPos)), num("base_slope", -1e6, 1e6)}};
  static const Schema table1d{"[cam.table1d]", {required(pair("master", -kPos, kPos)), required([] {
                                                 Field f = num("values", -kPos, kPos);
                                                 f.kind = Kind::NumberList;
                                                 f.nonEmpty = true;
                                                 return f;
                                               }())}};
  auto rows = [](const char* n, size_t count) {
    Field f = num(n, -kPos, kPos);
    f.kind = Kind::NumberList;
    f.count = count;
    f.nonEmpty = true;
    return f;
  };
  static const Schema cam{"[[cam]]",
                          {required(kind("var", Kind::VarPath)), [] { Field f = str("file"); f.nonEmpty = true; return f; }(), rows("xyva", 4),
                           rows("table2d", 2), [] { Field f{"table1d", Kind::Table}; f.schema = &table1d; return f; }(),
                           pair("start", -kPos, kPos), tables("segments", segment), tables("tappets", tappet)},
                          {},
                          {},
                          {{"file", "xyva", "table1d", "table2d", "segments"}}};
  static const Schema cncProgram{"[[cnc_program]]",
                                 {required(kind("var", Kind::VarPath)), required([] { Field f = str("file"); f.nonEmpty = true; return f; }()),
                                  num("default_vel", 0, kVel), num("default_accel", 0, kAcc), num("default_decel", 0, kAcc),
                                  num("default_vel_ff", 0, kVel), num("default_accel_ff", 0, kAcc), num("default_decel_ff", 0, kAcc)}};
  static const Schema root{"project.toml",
                           {[] { Field f{"project", Kind::Table}; f.schema = &project; return f; }(),
                            [] { Field f{"build", Kind::Table}; f.schema = &build; return f; }(), tables("task", task, "name"),
                            tables("axis", axis, "name"), tables("group", group, "name"), tables("io", io, "var"),
                            tables("cam", cam, "var"), tables("cnc_program", cncProgram, "var")}};
  return root;
}

const Schema& scenarioSchema() {
  static const Schema set{"[[set]]", {required(kind("at", Kind::Duration)), required(kind("var", Kind::VarPath)), required(kind("value", Kind::Literal))}};
  static const Schema fault{"[[fault]]", {required(kind("at", Kind::Duration)), required(kind("axis", Kind::VarPath)), required(str("kind", kFaultKinds))}};
  static const Schema check{"[[check]]",
                            {kind("at", Kind::Duration), required(kind("var", Kind::VarPath)), kind("equals", Kind::Literal),
                             kind("rises_between", Kind::DurationPair), num("min", -1e300, 1e300), num("max", -1e300, 1e300)},
                            {{"min", "max"}}};
  static const Schema root{"the scenario",
                           {str("description"), positiveDuration("duration"), integer("cycles", 1, 1e12), list("trace", Kind::VarPath),
                            num("tolerance", 0, 1e300), sampling("sample", {"change"}), tables("set", set), tables("fault", fault), tables("check", check)},
                           {},
                           {},
                           {{"duration", "cycles"}}};
  return root;
}

bool validate(const toml::table& root, const Schema& schema, const std::string& shown, std::string& error) {
  Validator v{shown, error};
  return v.table(root, schema, root);
}

bool loadToml(const std::string& path, const std::string& shown, const Schema& schema, toml::table& out, std::string& error) {
  std::string text, why;
  if (!readRegularFile(path, text, why)) {
    error = shown + ": error: " + why;
    return false;
  }
  try {
    out = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& s = e.source();
    error = shown + (s.begin ? ":" + std::to_string(s.begin.line) + ":" + std::to_string(s.begin.column) : std::string()) + ": error: " +
            std::string(e.description());
    return false;
  } catch (const std::exception& e) {
    error = shown + ": error: " + e.what();
    return false;
  }
  return validate(out, schema, shown, error);
}

bool loadProjectToml(const std::string& dir, toml::table& out, std::string& error) {
  const std::string path = (dir.empty() ? std::string(".") : dir) + "/project.toml";
  return loadToml(path, path, projectSchema(), out, error);
}

}  // namespace stc::config
