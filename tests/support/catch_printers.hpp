#pragma once
// Lets Catch print an Expected that failed a check as its error's one-line description.

#include "base/error.hpp"

#include <catch2/catch.hpp>

namespace Catch {

template <class T> struct StringMaker<subfeed::Expected<T>> {
  static std::string convert(const subfeed::Expected<T>& value) {
    return value ? std::string("{value}") : "{error: " + value.error().describe() + "}";
  }
};

} // namespace Catch
