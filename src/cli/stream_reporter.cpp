#include "stream_reporter.hpp"

#include "progress_text.hpp"

#include <cstdio>
#include <fmt/format.h>
#include <unistd.h>

namespace subfeed::cli {

// JSON string contents: controller messages may carry quotes, backslashes or noise bytes.
std::string json_escape(std::string_view text) {
  std::string out;
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20 || c >= 0x7f) {
      out += fmt::format("\\u{:04x}", c);
    } else {
      out += ch;
    }
  }
  return out;
}

std::string state_text(const drivers::StreamProgress& p) {
  if (!p.status) {
    return p.link_state.empty() ? "?" : p.link_state;
  }
  return p.status->substate >= 0 ? fmt::format("{}:{}", p.status->state, p.status->substate)
                                 : p.status->state;
}

StreamReporter::StreamReporter(Logger& log, bool json)
    : log_(log), json_(json),
      terminal_(!json && log.verbosity() != job::Verbosity::quiet && ::isatty(STDERR_FILENO) != 0) {
}

StreamReporter::~StreamReporter() {
  end_progress_line();
}

void StreamReporter::end_progress_line() {
  if (progress_shown_) {
    std::fputs("\n", stderr);
    progress_shown_ = false;
  }
}

void StreamReporter::connected(const drivers::ControllerInfo& info) {
  const std::string rx =
      fmt::format("{} bytes{}", info.rx_buffer, info.rx_buffer_reported ? " (from $I)" : "");
  if (json_) {
    std::printf("{\"event\":\"connected\",\"grblhal\":%s,\"version\":\"%s\",\"rx_buffer\":%d,"
                "\"line_limit\":%d}\n",
                info.grblhal ? "true" : "false", json_escape(info.version).c_str(), info.rx_buffer,
                info.line_limit);
    std::fflush(stdout);
  }
  log_.detail(fmt::format("controller {} {}; rx buffer {}, line limit {}",
                          info.grblhal ? "grblHAL" : "GRBL", info.version, rx, info.line_limit));
}

void StreamReporter::progress(const drivers::StreamProgress& p) {
  const auto now = std::chrono::steady_clock::now();
  const std::string state = state_text(p);
  const bool state_changed = state != last_state_;
  if (now - last_update_ < std::chrono::milliseconds(json_ ? 500 : 100) && !state_changed) {
    return;
  }
  last_update_ = now;
  last_state_ = state;
  const double fraction =
      p.lines_total > 0 ? static_cast<double>(p.lines_acked) / p.lines_total : 0.0;
  const double eta = fraction > 0.0 ? p.elapsed_s * (1.0 - fraction) / fraction : 0.0;
  if (json_) {
    std::printf("{\"event\":\"progress\",\"checking\":%s,\"acked\":%ld,\"sent\":%ld,\"total\":%ld,"
                "\"elapsed_s\":%.2f,\"eta_s\":%.1f,\"state\":\"%s\"}\n",
                p.checking ? "true" : "false", p.lines_acked, p.lines_sent, p.lines_total,
                p.elapsed_s, eta, json_escape(state).c_str());
    std::fflush(stdout);
  } else if (terminal_) {
    std::fprintf(stderr, "\r%s%ld/%ld lines  %5.1f%%  elapsed %s  ETA %s  %-8s\x1b[K",
                 p.checking ? "check " : "", p.lines_acked, p.lines_total, 100.0 * fraction,
                 clock_text(p.elapsed_s).c_str(), clock_text(eta).c_str(), state.c_str());
    progress_shown_ = true;
  }
}

void StreamReporter::message(std::string_view line) {
  if (json_) {
    std::printf("{\"event\":\"message\",\"text\":\"%s\"}\n", json_escape(line).c_str());
    std::fflush(stdout);
  }
  log_.detail(fmt::format("controller: {}", line));
}

void StreamReporter::line_error(const drivers::LineError& e) {
  const std::string text =
      fmt::format("{}:{}: error:{} ({}){}", e.file, e.line, e.code, drivers::error_meaning(e.code),
                  e.latched ? " [latched: rejected for the error before it]" : "");
  if (json_) {
    std::printf(
        "{\"event\":\"line_error\",\"file\":\"%s\",\"line\":%ld,\"code\":%d,\"latched\":%s}\n",
        json_escape(e.file).c_str(), e.line, e.code, e.latched ? "true" : "false");
    std::fflush(stdout);
  }
  end_progress_line();
  log_.warning(text);
}

void StreamReporter::phase(std::string_view name) {
  if (json_) {
    std::printf("{\"event\":\"phase\",\"name\":\"%s\"}\n", std::string(name).c_str());
    std::fflush(stdout);
  }
  log_.detail(fmt::format("phase: {}", name));
}

void StreamReporter::finished(const drivers::StreamSummary& s, std::optional<int> baud,
                              int bits_per_character) {
  end_progress_line();
  const double rate = s.seconds > 0.0 ? s.bytes / s.seconds : 0.0;
  const std::string link = baud ? fmt::format(", link use {:.1f}% of {} baud",
                                              100.0 * rate * bits_per_character / *baud, *baud)
                                : std::string();
  if (json_) {
    std::printf(
        "{\"event\":\"done\",\"lines\":%ld,\"bytes\":%ld,\"seconds\":%.3f,\"bytes_per_s\":%.1f,"
        "\"errors\":%ld}\n",
        s.lines, s.bytes, s.seconds, rate, s.errors);
    std::fflush(stdout);
    return;
  }
  log_.info(fmt::format(
      "done: {} lines, {} bytes in {:.2f} s ({:.0f} bytes/s{}){}", s.lines, s.bytes, s.seconds,
      rate, link, s.errors > 0 ? fmt::format(", {} lines answered with errors", s.errors) : ""));
}

void StreamReporter::failed(const Error& error) {
  end_progress_line();
  if (json_) {
    std::printf("{\"event\":\"failed\",\"exit_code\":%d,\"message\":\"%s\"}\n",
                exit_code(error.code), json_escape(error.describe()).c_str());
    std::fflush(stdout);
  }
}

} // namespace subfeed::cli
