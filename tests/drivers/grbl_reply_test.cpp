#include "drivers/gcode_line.hpp"
#include "drivers/grbl_reply.hpp"

#include <catch2/catch.hpp>

using namespace subfeed::drivers;

TEST_CASE("only ok and error:N answer a line, every push message is recognised") {
  CHECK(classify_reply("ok").kind == ReplyKind::ok);
  const auto e = classify_reply("error:22");
  CHECK(e.kind == ReplyKind::error);
  CHECK(e.code == 22);
  const auto a = classify_reply("ALARM:3");
  CHECK(a.kind == ReplyKind::alarm);
  CHECK(a.code == 3);
  CHECK(classify_reply("Grbl 1.1h ['$' for help]").kind == ReplyKind::banner);
  const auto hal = classify_reply("GrblHAL 1.1f ['$' or '$HELP' for help]");
  CHECK(hal.kind == ReplyKind::banner);
  CHECK(hal.grblhal);
  for (const auto* msg : {"[MSG:Caution: Unlocked]", "[GC:G0 G54 G17 G21 G90 G94 M5 M9 T0 F0 S0]",
                          "[HLP:$$ $# $G $I $N $x=val $Nx=line $J=line $C $X $H ~ ! ? ctrl-x]",
                          "[VER:1.1h.20190825:]", "[OPT:VL,15,128]", "[echo:G1X1]"}) {
    CHECK(classify_reply(msg).kind == ReplyKind::feedback);
  }
  CHECK(classify_reply("$10=1").kind == ReplyKind::setting);
  CHECK(classify_reply("$N0=G54").kind == ReplyKind::setting);
  CHECK(classify_reply(">G54G20:ok").kind == ReplyKind::startup_echo);
  CHECK(classify_reply("<Idle|MPos:0.000,0.000,0.000|FS:0,0>").kind == ReplyKind::status);
  CHECK(classify_reply("").kind == ReplyKind::empty);
  CHECK(classify_reply("okay").kind == ReplyKind::unknown);
  CHECK(classify_reply("error:x").kind == ReplyKind::unknown);
  CHECK(classify_reply("\xfe\xff#@!").kind == ReplyKind::unknown);
}

TEST_CASE("status reports are parsed field by field") {
  const auto s = parse_status("<Hold:1|MPos:1.000,-2.500,3.250,90.000,0.000|Bf:15,128|FS:600,12000|"
                              "Ln:42|WCO:10.000,0.000,-5.000|Ov:110,100,90|Pn:XZ|A:SF>");
  REQUIRE(s);
  CHECK(s->state == "Hold");
  CHECK(s->substate == 1);
  CHECK(s->machine_position == std::vector<double>{1.0, -2.5, 3.25, 90.0, 0.0});
  CHECK_FALSE(s->work_position);
  CHECK(*s->planner_free == 15);
  CHECK(*s->rx_free == 128);
  CHECK(*s->feed == 600.0);
  CHECK(*s->spindle == 12000.0);
  CHECK(*s->line_number == 42);
  CHECK((*s->work_offset)[2] == -5.0);
  CHECK((*s->overrides)[0] == 110);

  const auto w = parse_status("<Run|WPos:0.000,0.000,0.000,0.000,0.000,0.000|F:300>");
  REQUIRE(w);
  CHECK(w->work_position);
  CHECK(w->machine_position.size() == 6);
  CHECK(*w->feed == 300.0);
  CHECK(w->substate == -1);

  CHECK(parse_status("<Door:2|MPos:0.000,0.000,0.000>")->substate == 2);
  CHECK_FALSE(parse_status("<Idle|MPos:0.000,x,0.000>"));
  CHECK_FALSE(parse_status("<Idle|MPos:0.000,0.000>")); // fewer than 3 axes
  CHECK_FALSE(parse_status("Idle|MPos:0,0,0"));
}

TEST_CASE("[OPT:] gives the planner and RX buffer sizes") {
  const auto grbl = parse_build_options("[OPT:VL,15,128]");
  CHECK(*grbl.planner_blocks == 15);
  CHECK(*grbl.rx_buffer == 128);
  CHECK(*parse_build_options("[OPT:VNML+,100,1024,3,0]").rx_buffer == 1024);
  CHECK_FALSE(parse_build_options("[OPT:V]").rx_buffer);
  CHECK_FALSE(parse_build_options("[VER:1.1h]").rx_buffer);
}

TEST_CASE("error and alarm codes have GRBL's meanings") {
  CHECK(error_meaning(20) == "unsupported or invalid G-code command found in block");
  CHECK(error_meaning(11) == "max characters per line exceeded; line was not processed");
  CHECK(error_meaning(99) == "unknown error");
  CHECK(alarm_meaning(3).starts_with("reset while in motion"));
  CHECK(alarm_meaning(42) == "unknown alarm");
}

TEST_CASE("lines are stripped of comments and spaces and upper-cased") {
  const LineRules rules{79, false};
  CHECK(prepare_line("g1 x1.5 (move) y2 ; rest", rules, {})->text == "G1X1.5Y2");
  CHECK(prepare_line("  (only a comment)  ", rules, {})->text.empty());
  CHECK(prepare_line("\tG0\tZ5", rules, {})->text == "G0Z5");
  const auto kept = prepare_line("G1 X1 (keep) ", {79, true}, {});
  CHECK(kept->text == "G1 X1 (keep)");
}

TEST_CASE("lines the controller would misread are refused with their location") {
  const LineRules rules{79, false};
  const subfeed::Where where{"job.nc", 7, {}};
  const auto question = prepare_line("G1 X1 (why?)", rules, where);
  REQUIRE_FALSE(question);
  CHECK(question.error().describe() ==
        "job.nc:7: '?' would act as a realtime command on the controller");
  CHECK_FALSE(prepare_line("G1 X1 !", rules, where));
  CHECK_FALSE(prepare_line("G1 X1 ~", rules, where));
  const auto high = prepare_line("G1 X1 \xc2\xb0", rules, where);
  REQUIRE_FALSE(high);
  CHECK(high.error().message == "byte 0xC2 would act as a realtime command on the controller");
  CHECK(prepare_line(std::string("G1\x01X1"), rules, where).error().message ==
        "control character byte 0x01 in line");
  const auto longer = prepare_line("G1X" + std::string(77, '1'), rules, where);
  REQUIRE_FALSE(longer);
  CHECK(longer.error().message ==
        "line is 80 characters after stripping; the controller takes at most 79");
  CHECK(prepare_line("G1X" + std::string(76, '1') + " (long comments do not count)", rules, where));
}

TEST_CASE("EEPROM writes and system commands are sent alone") {
  CHECK(needs_send_and_wait("$10=1"));
  CHECK(needs_send_and_wait("$H"));
  CHECK(needs_send_and_wait("$RST=*"));
  CHECK(needs_send_and_wait("G10L2P1X0Y0"));
  CHECK(needs_send_and_wait("G10L20P1X0"));
  CHECK(needs_send_and_wait("G28.1"));
  CHECK(needs_send_and_wait("G30.1"));
  CHECK_FALSE(needs_send_and_wait("G10L1P1"));
  CHECK_FALSE(needs_send_and_wait("G28"));
  CHECK_FALSE(needs_send_and_wait("G1X10L2")); // an L word without G10
  CHECK_FALSE(needs_send_and_wait("G1X28.1"));
}
