// The link the commands open to a simulated Fanuc control: over the real pty and serial code,
// an alarm the control raises is named in the one error line the sender prints.

#include "job/controller_link.hpp"
#include "support/fanuc_alarm.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <string_view>

using namespace subfeed;
using namespace subfeed::job;
using namespace std::chrono_literals;

namespace {

Link fanuc_link() {
  LinkRequest request;
  request.sim = "fanuc";
  request.protocol = "fanuc";
  auto link = open_link(request, drivers::SerialOptions{});
  REQUIRE(link.has_value());
  REQUIRE(link->control != nullptr);
  REQUIRE(link->transport != nullptr);
  return std::move(*link);
}

} // namespace

TEST_CASE("an error names the alarm the simulated control shows", "[pty]") {
  const auto link = fanuc_link();
  const Error held{ErrorCode::machine_fault, "the control has held the tape (XOFF) for 500 ms", {}};
  CHECK(with_simulated_alarm(held, link).message == held.message); // no alarm yet
  constexpr std::string_view tape = "G01 X1.0 F600,\n"; // ',' is not an ISO 840 character
  REQUIRE(drivers::write_all(*link.transport, tape, 1s).has_value());
  REQUIRE(subfeed::testing::alarm_within(*link.control, 5s) == "TH character ','");
  const Error shown = with_simulated_alarm(held, link);
  CHECK(shown.message == held.message + "; the simulated control shows alarm TH character ','");
  CHECK(shown.code == ErrorCode::machine_fault);
}

TEST_CASE("an error from a link without a simulated control is left as it is", "[pty]") {
  LinkRequest request;
  request.sim = "grbl";
  auto link = open_link(request, drivers::SerialOptions{});
  REQUIRE(link.has_value());
  const Error lost{ErrorCode::machine_fault, "the controller stopped answering", {}};
  CHECK(with_simulated_alarm(lost, *link).message == lost.message);
}
