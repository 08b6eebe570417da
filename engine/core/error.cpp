#include "engine/core/error.h"

namespace sky {

void inputError(const std::string& message) {
  throw Error(ErrorKind::BadInput, message);
}
void internalError(const std::string& message) {
  throw Error(ErrorKind::Internal, message);
}

}  // namespace sky
