#pragma once
// A running FNV-1a hash over delivered lines (each followed by '\n'): proves exact,
// in-order delivery of a program too long to keep line by line.

#include <cstdint>
#include <string_view>

namespace subfeed::sim {

inline constexpr std::uint64_t delivery_hash_seed = 1469598103934665603ULL;

[[nodiscard]] inline std::uint64_t delivery_hash(std::uint64_t hash, std::string_view line) {
  for (const char c : line) {
    hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ULL;
  }
  return (hash ^ static_cast<unsigned char>('\n')) * 1099511628211ULL;
}

} // namespace subfeed::sim
