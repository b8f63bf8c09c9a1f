// libFuzzer target: the material expression parser (ScalarFunction::parse) and its evaluation
// at a few points. Errors name the expression rather than a file, so any sinew::Error passes;
// anything else (a crash, another exception, undefined behaviour) is a finding.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "sinew/core/error.hpp"
#include "sinew/material/expression.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto f = sinew::ScalarFunction::parse(text, {{"a", 2.0}, {"mu", 1e5}, {"k", -3.5}});
    for (const double x : {0.0, 0.5, 1.0, 2.0, -1.0, 1e300}) {
      try {
        f.derivatives(x);
      } catch (const sinew::Error&) {
      }
    }
  } catch (const sinew::Error&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sinew fuzz finding: an exception other than sinew::Error: %s\n", e.what());
    std::abort();
  }
  return 0;
}
