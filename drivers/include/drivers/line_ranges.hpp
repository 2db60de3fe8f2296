#pragma once
// File line numbers as a machinist reads them in a message: "line 41", "lines 41-43",
// "lines 41-43, 47, 50-52". The numbers are sorted and duplicates dropped first, so any
// collection of lines prints one way.

#include <string>
#include <vector>

namespace subfeed::drivers {

// "" for no lines; otherwise "line N" or "lines ..." with runs of consecutive numbers joined.
[[nodiscard]] std::string describe_lines(std::vector<long> lines);

} // namespace subfeed::drivers
