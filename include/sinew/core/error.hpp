#pragma once
// The one error type of Sinew: a reason plus where it happened (file, JSON path,
// material, parameter, ...). The CLI prints it on one line and exits with code 2.
#include <stdexcept>
#include <string>

namespace sinew {

class Error : public std::runtime_error {
 public:
  explicit Error(std::string message, std::string context = {});

  const std::string& message() const noexcept { return message_; }
  const std::string& context() const noexcept { return context_; }

  // A copy with an outer context prepended ("outer: inner").
  Error within(const std::string& outer) const;

 private:
  std::string message_;
  std::string context_;
};

}  // namespace sinew
