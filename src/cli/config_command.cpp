// `subfeed config FILE...`: validates machine configs and tool tables and shows what subfeed
// understood from them, so that a sign, a limit or a holder can be checked before the first
// block is posted.

#include "command.hpp"

#include "post/config_kind.hpp"
#include "post/machine_config.hpp"
#include "post/tool_table.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace subfeed::cli {

namespace {

std::string describe_axis(std::size_t index, const post::AxisLimits& a) {
  const char letter = post::axis_letters[index];
  const char* unit = post::is_rotary_axis(index) ? "deg" : "mm";
  if (a.cyclic) {
    return fmt::format("  {} cyclic, max feed {} {}/min", letter, a.max_feed, unit);
  }
  return fmt::format("  {} {} .. {} {}, max feed {} {}/min", letter, a.min, a.max, unit, a.max_feed,
                     unit);
}

void describe(const post::MachineConfig& m, Logger& log) {
  const auto& c = m.controller;
  log.info(fmt::format("{}: '{}', kinematics {}, protocol {}, dialect {}", m.source, m.name,
                       post::to_string(m.kinematics), post::to_string(c.protocol),
                       post::to_string(c.dialect)));
  for (std::size_t i = 0; i < m.axes.size(); ++i) {
    if (m.axes[i]) {
      log.info(describe_axis(i, *m.axes[i]));
    }
  }
  if (m.rotary) {
    const auto& g = *m.rotary;
    const char tilt = post::axis_letters[post::tilt_axis(m.kinematics)];
    if (m.kinematics == post::KinematicsType::xyzac_head) {
      log.info(
          fmt::format("  pivot length {} mm, tool length {} mm", g.pivot_length, g.tool_length));
    } else {
      log.info(fmt::format("  pivot ({}, {}, {}) mm, offsets x {} y {} z {} mm, tool length {} mm",
                           g.pivot[0], g.pivot[1], g.pivot[2], g.x_offset, g.y_offset, g.z_offset,
                           g.tool_length));
    }
    log.info(fmt::format("  {} direction {:+d}, C direction {:+d}; singularity cone {} deg, "
                         "retract {} mm",
                         tilt, g.tilt_direction, g.c_direction, m.post.singularity_cone,
                         m.post.retract));
  }
  const auto& s = c.serial;
  log.info(
      fmt::format("  serial {} baud {}{}{} flow {}; line length {}, {} decimals, rx buffer {}{}",
                  s.baud, s.data_bits, "NEO"[static_cast<int>(s.parity)], s.stop_bits,
                  post::to_string(s.flow_control), c.line_length, c.decimals,
                  c.rx_buffer ? fmt::format("{} bytes", *c.rx_buffer) : "from controller",
                  c.tcp ? ", TCP control" : ""));
}

void describe(const post::ToolTable& table, Logger& log) {
  log.info(fmt::format("{}: tool table, {} tools", table.file, table.tools.size()));
  for (const auto& t : table.tools) {
    const auto size = [](const char* what, const std::optional<double>& mm, const char* fallback) {
      return mm ? fmt::format(", {} {:g}", what, *mm) : fmt::format(", {} {}", what, fallback);
    };
    std::string holder;
    for (const auto& h : t.holder) {
      holder += holder.empty() ? ", holder " : " then ";
      holder +=
          h.bottom_diameter == h.top_diameter
              ? fmt::format("{:g} x {:g}", h.bottom_diameter, h.length)
              : fmt::format("{:g} to {:g} x {:g}", h.bottom_diameter, h.top_diameter, h.length);
    }
    log.info(fmt::format("  {} (line {}): {} {:g}{}{}{}{}", t.name, t.line, t.cutter, t.diameter,
                         size("flutes", t.flute, "3D"), size("shank", t.shank, "D"),
                         size("stick-out", t.stickout, "4D"),
                         holder.empty() ? std::string(", no holder") : holder));
  }
}

// One file checked and described, by what it holds.
Expected<void> check_config(const std::string& file, Logger& log) {
  SUBFEED_TRY_ASSIGN(const auto kind, post::config_kind(file));
  if (kind == post::ConfigKind::machine) {
    SUBFEED_TRY_ASSIGN(const auto config, post::load_machine_config(file));
    describe(config, log);
  } else {
    SUBFEED_TRY_ASSIGN(const auto table, post::load_tool_table(file));
    describe(table, log);
  }
  return {};
}

Expected<void> check_configs(const std::vector<std::string>& files, Logger& log) {
  std::size_t rejected = 0;
  for (const auto& file : files) {
    if (auto checked = check_config(file, log); !checked) {
      if (rejected++ == 0 && files.size() == 1) {
        return checked;
      }
      log.error(checked.error());
    }
  }
  if (rejected > 0) {
    return fail(ErrorCode::bad_input,
                fmt::format("{} of {} configs rejected", rejected, files.size()));
  }
  return {};
}

} // namespace

void add_config_command(CLI::App& app, Action& chosen) {
  auto files = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand(
      "config", "Validate machine configs and tool tables and show what they say");
  cmd->add_option("files", *files, "Machine configs (with a [machine] table) or tool tables (TOML)")
      ->required()
      ->type_name("FILE.toml");
  cmd->callback(
      [&chosen, files] { chosen = [files](Logger& log) { return check_configs(*files, log); }; });
}

} // namespace subfeed::cli
