// `subfeed config M.toml...`: validates machine configs and shows what subfeed understood
// from them, so that a sign or a limit can be checked before the first block is posted.

#include "command.hpp"

#include "post/machine_config.hpp"

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

Expected<void> check_configs(const std::vector<std::string>& files, Logger& log) {
  std::size_t rejected = 0;
  for (const auto& file : files) {
    auto config = post::load_machine_config(file);
    if (!config) {
      if (rejected++ == 0 && files.size() == 1) {
        return std::unexpected(config.error());
      }
      log.error(config.error());
      continue;
    }
    describe(*config, log);
  }
  if (rejected > 0) {
    return fail(ErrorCode::bad_input,
                fmt::format("{} of {} machine configs rejected", rejected, files.size()));
  }
  return {};
}

} // namespace

void add_config_command(CLI::App& app, Action& chosen) {
  auto files = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand("config", "Validate machine configs and show what they say");
  cmd->add_option("machine", *files, "Machine config files (TOML)")
      ->required()
      ->type_name("M.toml");
  cmd->callback(
      [&chosen, files] { chosen = [files](Logger& log) { return check_configs(*files, log); }; });
}

} // namespace subfeed::cli
