// libFuzzer target for compiler/config: the duration grammar and the schema validation of
// project.toml / scenario text (built with STC_FUZZ; tools/fuzz_config.py fuzzes the whole
// stc binary with mutated projects instead).
//   build-fuzz/tests/fuzz/stc_fuzz_config CORPUS -max_len=4096
#include <cstdint>
#include <string>

#include "config/ConfigSchema.h"
#include "config/Duration.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  int64_t ns = 0;
  std::string why;
  stc::config::parseDuration(text, ns, &why);
  try {
    toml::table t = toml::parse(std::string_view(text), std::string_view("f.toml"));
    std::string error;
    stc::config::validate(t, (size & 1) ? stc::config::projectSchema() : stc::config::scenarioSchema(), "f.toml", error);
  } catch (const toml::parse_error&) {
  }
  return 0;
}
