#pragma once
// What the harnesses share: the input as text, and the rule that tells a parser's
// documented error from a finding. A finding aborts, so libFuzzer keeps the input as a
// crash file; so do sanitizer reports and inputs that run past -timeout.
#include <cxxabi.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <typeinfo>

namespace deepnav::fuzz {

inline std::string as_text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// The exception's dynamic type, readable ("YAML::BadConversion", not its mangled name).
inline std::string type_name(const std::exception& e) {
  int status = 0;
  std::unique_ptr<char, void (*)(void*)> name(abi::__cxa_demangle(typeid(e).name(), nullptr, nullptr, &status),
                                              std::free);
  return status == 0 && name ? name.get() : typeid(e).name();
}

[[noreturn]] inline void finding(const std::exception& e, const char* why) {
  std::fprintf(stderr, "fuzz finding: %s: %s: %s\n", why, type_name(e).c_str(), e.what());
  std::abort();
}

/// Runs `parse`; an exception that `expected` accepts is the parser's documented error,
/// any other std::exception is a finding (exceptions of other types escape, and libFuzzer
/// reports them itself). Returns whether `parse` completed.
template <typename Parse, typename Expected>
bool guarded(Parse&& parse, Expected&& expected) {
  try {
    parse();
    return true;
  } catch (const std::exception& e) {
    if (!expected(e)) finding(e, "unexpected exception");
    return false;
  }
}

/// The file readers' rule: a std::runtime_error or std::invalid_argument whose message
/// names the input, so that the user learns which file is wrong (a bare "stod" or a
/// yaml-cpp message without the file is a finding).
inline auto names_input(std::string name) {
  return [name = std::move(name)](const std::exception& e) {
    const bool documented = dynamic_cast<const std::runtime_error*>(&e) != nullptr ||
                            dynamic_cast<const std::invalid_argument*>(&e) != nullptr;
    return documented && std::string_view(e.what()).find(name) != std::string_view::npos;
  };
}

/// Exactly the type E (or one derived from it).
template <typename E>
bool is_a(const std::exception& e) {
  return dynamic_cast<const E*>(&e) != nullptr;
}

/// A check of the parser's result that failed (a value it promised to reject came out).
[[noreturn]] inline void broken_promise(const std::string& what) {
  std::fprintf(stderr, "fuzz finding: %s\n", what.c_str());
  std::abort();
}

}  // namespace deepnav::fuzz
