// Error handling in two tiers, as everywhere in Penumbra:
//  - PN_CHECK(cond, msg): a precondition for programming mistakes. It prints the message with
//    file and line and aborts; it is never used for bad input.
//  - Result<T>: the return type of everything that can fail on bad input or a failing
//    environment (missing file, malformed glTF, no GL context). It carries a one-line message.
// No exception leaves a Penumbra function: code that calls throwing libraries catches at its
// own boundary and returns a Result, so nothing crosses the wasm boundary either.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <variant>

namespace penumbra {

struct Error {
  std::string message;
};

inline Error makeError(std::string message) {
  return Error{std::move(message)};
}

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::in_place_index<0>, std::move(value)) {}  // NOLINT: implicit by design
  Result(Error error) : v_(std::in_place_index<1>, std::move(error)) {}  // NOLINT

  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }

  T& value() & { return checked(); }
  const T& value() const& { return const_cast<Result*>(this)->checked(); }
  T&& value() && { return std::move(checked()); }
  T& operator*() & { return checked(); }
  const T& operator*() const& { return const_cast<Result*>(this)->checked(); }
  T* operator->() { return &checked(); }
  const T* operator->() const { return &const_cast<Result*>(this)->checked(); }

  const Error& error() const {
    if (ok()) {
      std::fprintf(stderr, "penumbra: Result::error() called on a value\n");
      std::abort();
    }
    return std::get<1>(v_);
  }
  const std::string& message() const { return error().message; }

 private:
  T& checked() {
    if (!ok()) {
      std::fprintf(stderr, "penumbra: Result::value() called on an error: %s\n",
                   std::get<1>(v_).message.c_str());
      std::abort();
    }
    return std::get<0>(v_);
  }
  std::variant<T, Error> v_;
};

template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Error error) : error_(std::move(error)), failed_(true) {}  // NOLINT: implicit by design
  bool ok() const { return !failed_; }
  explicit operator bool() const { return ok(); }
  const Error& error() const { return error_; }
  const std::string& message() const { return error_.message; }

 private:
  Error error_;
  bool failed_ = false;
};

using Status = Result<void>;

[[noreturn]] inline void checkFailed(const char* expr, const std::string& message, const char* file,
                                     int line) {
  std::fprintf(stderr, "penumbra: precondition failed at %s:%d: %s (%s)\n", file, line,
               message.c_str(), expr);
  std::abort();
}

}  // namespace penumbra

// Precondition for programming mistakes; never for bad input (use Result for that).
#define PN_CHECK(cond, msg)                                                 \
  do {                                                                      \
    if (!(cond)) ::penumbra::checkFailed(#cond, (msg), __FILE__, __LINE__); \
  } while (0)

// Returns the error of a failed Result from the enclosing function (which returns a Result).
#define PN_TRY(expr)                                         \
  do {                                                       \
    auto&& pn_try_result_ = (expr);                          \
    if (!pn_try_result_.ok()) return pn_try_result_.error(); \
  } while (0)
