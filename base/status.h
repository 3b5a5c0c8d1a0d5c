// Status: the result of an operation that can fail for a reason the user must hear about.
// kInvalidInput = the input (file, config, mesh) is wrong: the CLI exits with code 2.
// kInternal     = the program could not complete a valid request: exit code 1.
// The message is one line that names the file, key or element at fault.
// CHECK() stays reserved for programmer errors.
#pragma once

#include <string>
#include <utility>

namespace pqlayout {

enum class StatusCode { kOk = 0, kInvalidInput = 2, kInternal = 1 };

class [[nodiscard]] Status {
 public:
  Status() = default;
  static Status Ok() { return Status(); }
  static Status InvalidInput(std::string message) {
    return Status(StatusCode::kInvalidInput, std::move(message));
  }
  static Status Internal(std::string message) {
    return Status(StatusCode::kInternal, std::move(message));
  }

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }

  // Returns a copy whose message is prefixed with `context: ` (e.g. the file name).
  Status WithContext(const std::string& context) const {
    if (ok()) return *this;
    return Status(code_, context + ": " + message_);
  }

 private:
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

// A message as one line: a library's multi-line text (Ceres lists parameter blocks) joined,
// trailing spaces dropped. The CLI's stderr line and the Python module's exceptions use it.
inline std::string OneLine(std::string message) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  while (!message.empty() && message.back() == ' ') message.pop_back();
  return message;
}

// Evaluates an expression returning Status and returns it from the caller if not ok.
#define PQ_RETURN_IF_ERROR(expr)             \
  do {                                       \
    ::pqlayout::Status _pq_status = (expr);  \
    if (!_pq_status.ok()) return _pq_status; \
  } while (0)

}  // namespace pqlayout
