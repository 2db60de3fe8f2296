#pragma once
// Pieces of the one-line progress displays (`send`, `run`, `plan`).

#include <string>

namespace subfeed::cli {

// "mm:ss", or "h:mm:ss" from an hour on.
[[nodiscard]] std::string clock_text(double seconds);
// "[#####...............]": `fraction` (0..1, clamped) of 20 cells, to the nearest cell.
[[nodiscard]] std::string progress_bar(double fraction);
// The time left at the rate so far, `spent` seconds for the share `done` (0..1), as
// clock_text; "--:--" until 2 % is done, too little to tell a rate from.
[[nodiscard]] std::string eta_text(double spent, double done);

} // namespace subfeed::cli
