#include "sinew/core/error.hpp"

namespace sinew {
namespace {
std::string compose(const std::string& message, const std::string& context) {
  return context.empty() ? message : context + ": " + message;
}
}  // namespace

Error::Error(std::string message, std::string context)
    : std::runtime_error(compose(message, context)),
      message_(std::move(message)),
      context_(std::move(context)) {}

Error Error::within(const std::string& outer) const {
  return Error(message_, context_.empty() ? outer : outer + ": " + context_);
}

}  // namespace sinew
