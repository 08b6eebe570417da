#pragma once
// One error type for the whole engine. The apps map kinds to exit codes:
// BadInput -> 2 (config, arguments, files), Internal -> 1 (device, driver, bugs).
// Messages are one line that says what and where ("scene.yaml:4:3: camera.latitude: ...").
#include <stdexcept>
#include <string>

namespace sky {

enum class ErrorKind { BadInput, Internal };

class Error : public std::runtime_error {
public:
  Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), mKind(kind) {}
  ErrorKind kind() const { return mKind; }
  int exitCode() const { return mKind == ErrorKind::BadInput ? 2 : 1; }

private:
  ErrorKind mKind;
};

// Throw helpers: inputError for anything the user can fix, internalError otherwise.
[[noreturn]] void inputError(const std::string& message);
[[noreturn]] void internalError(const std::string& message);

}  // namespace sky
