#include "ins/simulated_disk.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string_view>

namespace deepnav::simulated_disk {
namespace {

constexpr std::uint64_t kNoDisk = std::numeric_limits<std::uint64_t>::max();  ///< nothing simulated

std::atomic<std::uint64_t> g_capacity{kNoDisk};
std::atomic<std::uint64_t> g_used{0};
std::once_flag g_environment_read;

/// The simulated disk's size (kNoDisk: none), from the environment at the first call.
std::uint64_t capacity_bytes() {
  std::call_once(g_environment_read, [] {
    const char* text = std::getenv(kVariable);
    if (text == nullptr || *text == '\0') return;
    const std::string_view value(text);
    std::uint64_t bytes = 0;
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), bytes);
    if (error != std::errc() || end != value.data() + value.size() || bytes == kNoDisk)
      throw std::runtime_error(fmt::format(
          "environment variable {}='{}': expected a number of bytes (a test's simulated disk size)", kVariable, value));
    g_capacity = bytes;
  });
  return g_capacity.load();
}

}  // namespace

bool take(std::uint64_t bytes) {
  const std::uint64_t capacity = capacity_bytes();
  if (capacity == kNoDisk) return true;
  std::uint64_t used = g_used.load();
  do {
    if (bytes > capacity - std::min(used, capacity)) return false;
  } while (!g_used.compare_exchange_weak(used, used + bytes));
  return true;
}

void give_back(std::uint64_t bytes) noexcept {
  std::uint64_t used = g_used.load();
  while (!g_used.compare_exchange_weak(used, used >= bytes ? used - bytes : 0)) {
  }
}

void simulate(std::optional<std::uint64_t> capacity) {
  std::call_once(g_environment_read, [] {});  // the environment's setting no longer applies
  g_capacity = capacity.value_or(kNoDisk);
  g_used = 0;
}

}  // namespace deepnav::simulated_disk
