#include "job/job_record.hpp"

#include "base/number_text.hpp"

#include "job/cl_gate.hpp"

#include "cl/cl_reader.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/part_setup.hpp"
#include "post/post_file.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fmt/format.h>
#include <map>

namespace subfeed::job {

namespace {

std::string escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (c == '%' || c == ' ' || c == '=' || static_cast<unsigned char>(c) < 0x21) {
      out += fmt::format("%{:02X}", static_cast<unsigned char>(c));
    } else {
      out += c;
    }
  }
  return out;
}

std::string unescape(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '%' && i + 2 < text.size()) {
      int value = 0;
      std::from_chars(text.data() + i + 1, text.data() + i + 3, value, 16);
      out += static_cast<char>(value);
      i += 2;
    } else {
      out += text[i];
    }
  }
  return out;
}

std::string number(double v) {
  return fmt::format("{}", v);
}

} // namespace

bool reads_cl(const JobRecord& o) {
  auto extension = std::filesystem::path(o.cage).extension().string();
  std::ranges::transform(extension, extension.begin(),
                         [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".cl";
}

JobFiles job_files(const JobRecord& o) {
  const std::filesystem::path base = o.output.empty()
                                         ? std::filesystem::path(o.cage).replace_extension()
                                         : std::filesystem::path(o.output);
  auto cl = base, nc = base;
  cl += ".cl";
  nc += ".nc";
  return {reads_cl(o) ? std::filesystem::path(o.cage) : cl, nc};
}

std::filesystem::path journal_path(const JobRecord& o) {
  if (!o.journal.empty()) {
    return o.journal;
  }
  auto path = job_files(o).nc;
  return path.replace_extension(".journal");
}

namespace {

// The tilt the plan may use: what was said, checked against the machine, or the machine's.
Expected<double> machine_tilt(const post::MachineConfig& machine, double said_deg) {
  const auto range = post::tilt_range_deg(machine);
  if (!range) {
    return said_deg >= 0.0 ? said_deg : 90.0; // three axes: the tool stays vertical anyway
  }
  if (said_deg > *range + 1e-9) {
    return fail(ErrorCode::usage,
                fmt::format("{:g} degrees is more than {} tilts the tool ({:g} degrees)", said_deg,
                            machine.source, *range),
                {{}, 0, "--max-tilt"});
  }
  return said_deg >= 0.0 ? said_deg : *range;
}

post::PostFileOptions post_options_for(const post::MachineConfig& machine, const JobRecord& o) {
  post::PostFileOptions post;
  post.program = post::program_options_for(machine);
  // A drip-fed job restarts by the block the control shows (resume --block N).
  post.program.line_numbers = machine.controller.protocol == post::Protocol::fanuc;
  if (o.spindle_rpm > 0.0) {
    post.program.spindle_rpm = o.spindle_rpm;
  }
  return post;
}

Expected<JobSpec> cl_job_spec(const JobRecord& o, post::MachineConfig machine) {
  if (!o.plan.tool.empty() || o.plan.scallop != 0.0) {
    return fail(ErrorCode::usage, "plans come from a cage: CL data already has its path and cutter",
                {{}, 0, o.plan.tool.empty() ? "--scallop" : "--tool"});
  }
  if (o.check_cage.empty()) {
    return fail(ErrorCode::usage,
                "CL data reaches the machine only checked against the part: give the cage it "
                "was made for",
                {{}, 0, "--cage"});
  }
  SUBFEED_TRY_ASSIGN(auto reader, cl::ClReader::open(o.cage)); // the header, checked now
  SUBFEED_TRY_ASSIGN(auto gate, gate_for_cl(o.check_cage, reader.header(), o.cage, o.setup,
                                            o.plan.level, o.plan.gate_tolerance));
  auto post = post_options_for(machine, o);
  post.look_ahead = true; // the whole path exists: choose the start as `post` does
  JobSpec spec{.plan = std::nullopt,
               .machine = std::move(machine),
               .post = post,
               .header = reader.header(),
               .files = job_files(o),
               .gate = std::move(gate)};
  return spec;
}

// " setup_up=y setup_scale=10 setup_origin=top-centre", each only where the job's command
// line said it: a CL job's own setup record still decides the rest on resume.
std::string setup_fields(const SetupFlags& said) {
  const auto all = geometry::setup_text(said.with_defaults()); // "up=U scale=S origin=O"
  std::string text;
  std::string_view rest = all;
  for (const bool given : {said.up.has_value(), said.scale.has_value(), said.origin.has_value()}) {
    const auto end = std::min(rest.find(' '), rest.size());
    if (given) {
      const auto field = rest.substr(0, end);
      const auto eq = field.find('=');
      text += " setup_" + std::string(field.substr(0, eq + 1)) + escape(field.substr(eq + 1));
    }
    rest.remove_prefix(std::min(end + 1, rest.size()));
  }
  return text;
}

// Jobs from before setups were recorded have none of these fields: the model as it was.
Expected<SetupFlags> setup_flags_of(const std::map<std::string, std::string, std::less<>>& fields,
                                    const Where& where) {
  SetupFlags said;
  const auto field = [&](const char* key) { return fields.contains(std::string("setup_") + key); };
  if (!field("up") && !field("scale") && !field("origin")) {
    return said;
  }
  // Fill the unsaid fields with defaults so the text parses as a whole.
  const auto whole = geometry::parse_setup_text(
      fmt::format("up={} scale={} origin={}", field("up") ? fields.at("setup_up") : "z",
                  field("scale") ? fields.at("setup_scale") : "1",
                  field("origin") ? fields.at("setup_origin") : "model"));
  if (!whole) {
    return fail(ErrorCode::bad_input, "job record setup: " + whole.error().message, where);
  }
  said.up = field("up") ? std::optional(whole->up) : std::nullopt;
  said.scale = field("scale") ? std::optional(whole->scale) : std::nullopt;
  said.origin = field("origin") ? std::optional(*whole) : std::nullopt;
  return said;
}

} // namespace

Expected<JobSpec> job_spec(const JobRecord& o, Logger& log) {
  SUBFEED_TRY_ASSIGN(auto machine, post::load_machine_config(o.machine));
  if (reads_cl(o)) {
    return cl_job_spec(o, std::move(machine));
  }
  if (o.plan.tool.empty() || o.plan.scallop == 0.0) {
    return fail(ErrorCode::usage, "planning from a cage needs --tool and --scallop",
                {{}, 0, o.plan.tool.empty() ? "--tool" : "--scallop"});
  }
  SUBFEED_TRY_ASSIGN(auto plan, plan_options_from(o.plan));
  if (machine.kinematics == post::KinematicsType::xyz && !plan.fixed_axis) {
    if (plan.lean.any()) {
      return fail(ErrorCode::usage,
                  "a three-axis machine holds the tool vertical: it cannot lead or tilt",
                  {o.machine, 0, o.plan.lead != 0.0 ? "--lead" : "--tilt"});
    }
    plan.fixed_axis = true; // a three-axis machine holds the tool vertical
    log.detail("three-axis machine: the tool axis stays vertical");
  }
  SUBFEED_TRY_ASSIGN(plan.max_tilt_deg, machine_tilt(machine, o.plan.max_tilt));
  const auto setup = o.setup.with_defaults();
  SUBFEED_TRY_ASSIGN(auto cage, geometry::read_part(o.cage, setup));
  SUBFEED_TRY_ASSIGN(auto surface, geometry::LimitSurface::build(cage, o.plan.level));
  auto post = post_options_for(machine, o);
  post.look_ahead = false; // the poses do not exist yet: the start follows the preferred tilt
  cl::ClHeader header{std::filesystem::path(o.cage).stem().string(),
                      {2 * plan.ball_radius, plan.ball_radius},
                      !plan.fixed_axis,
                      geometry::setup_text(setup),
                      {}};
  return JobSpec{.plan = PlanInput{std::move(cage), std::move(surface), plan},
                 .machine = std::move(machine),
                 .post = post,
                 .header = header,
                 .files = job_files(o),
                 .gate = std::nullopt};
}

namespace {

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const auto& w : words) {
    out += (out.empty() ? "" : ",") + w;
  }
  return out;
}

} // namespace

std::string encode_job(const JobRecord& o) {
  const auto& p = o.plan;
  return fmt::format(
      "cage={} machine={} output={} tool={} scallop={} direction={} baseline={} "
      "axis_radius={} axis={} one_way={} feed={} plunge_feed={} clearance={} "
      "tolerance={} level={} refine={} spindle={} stay_down={} check_cage={} "
      "gate_tolerance={} max_tilt={} whole_tool={} flute={} shank={} stickout={} "
      "holder={} floor={} stock_margin={} clearance_min={} lead={} tilt={} mesh_chord={}{}",
      escape(o.cage), escape(o.machine), escape(job_files(o).nc.replace_extension().string()),
      escape(p.tool), number(p.scallop), escape(p.direction), p.baseline ? 1 : 0,
      number(p.axis_radius), escape(p.axis), p.one_way ? 1 : 0, number(p.feed),
      number(p.plunge_feed), number(p.clearance), number(p.tolerance), p.level, p.refine,
      number(o.spindle_rpm), number(p.stay_down), escape(o.check_cage), number(p.gate_tolerance),
      number(p.max_tilt), p.whole_tool ? 1 : 0, number(p.flute), number(p.shank),
      number(p.stickout), escape(joined(p.holder)), escape(p.floor), number(p.stock_margin),
      number(p.clearance_min), number(p.lead), number(p.tilt), number(p.mesh_chord),
      setup_fields(o.setup));
}

Expected<JobRecord> decode_job(std::string_view text, const Where& where) {
  std::map<std::string, std::string, std::less<>> fields;
  while (!text.empty()) {
    const auto end = std::min(text.find(' '), text.size());
    const auto field = text.substr(0, end);
    const auto eq = field.find('=');
    if (eq != std::string_view::npos) {
      fields[std::string(field.substr(0, eq))] = unescape(field.substr(eq + 1));
    }
    text.remove_prefix(std::min(end + 1, text.size()));
  }
  JobRecord o;
  std::string bad_key; // the first key missing or unreadable
  const auto get = [&](const char* key) -> std::string {
    const auto it = fields.find(key);
    if (it == fields.end()) {
      bad_key = bad_key.empty() ? key : bad_key;
      return {};
    }
    return it->second;
  };
  const auto get_or = [&](const char* key, const char* otherwise) -> std::string {
    const auto it = fields.find(key);
    return it == fields.end() ? otherwise : it->second;
  };
  const auto real = [&](const char* key) {
    const auto value = parse_double(get(key));
    if (!value) {
      bad_key = bad_key.empty() ? key : bad_key;
    }
    return value.value_or(0.0);
  };
  const auto integer = [&](const char* key) {
    const auto value = parse_int(get(key));
    if (!value) {
      bad_key = bad_key.empty() ? key : bad_key;
    }
    return value.value_or(0);
  };
  o.cage = get("cage");
  o.machine = get("machine");
  o.output = get("output");
  o.plan.tool = get("tool");
  o.plan.scallop = real("scallop");
  o.plan.direction = get("direction");
  o.plan.baseline = get("baseline") == "1";
  o.plan.axis_radius = real("axis_radius");
  o.plan.axis = get("axis");
  o.plan.one_way = get("one_way") == "1";
  o.plan.feed = real("feed");
  o.plan.plunge_feed = real("plunge_feed");
  o.plan.clearance = real("clearance");
  o.plan.tolerance = real("tolerance");
  o.plan.level = integer("level");
  o.plan.refine = integer("refine");
  o.spindle_rpm = real("spindle");
  // Journals from before stay-down links were planned with every link retracting.
  o.plan.stay_down = fields.contains("stay_down") ? real("stay_down") : 0.0;
  if (fields.contains("gate_tolerance")) {
    o.plan.gate_tolerance = real("gate_tolerance");
  }
  if (fields.contains("mesh_chord")) {
    o.plan.mesh_chord = real("mesh_chord");
  }
  if (fields.contains("max_tilt")) {
    o.plan.max_tilt = real("max_tilt");
  }
  // Jobs recorded before lead and tilt held the tool along the axis the planner chose.
  if (fields.contains("lead")) {
    o.plan.lead = real("lead");
    o.plan.tilt = real("tilt");
  }
  // Jobs recorded before the whole tool was checked re-plan as they were: the ball alone.
  o.plan.whole_tool = get_or("whole_tool", "0") == "1";
  if (o.plan.whole_tool) {
    o.plan.flute = real("flute");
    o.plan.shank = real("shank");
    o.plan.stickout = real("stickout");
    if (const auto holder = get("holder"); !holder.empty()) {
      std::string_view rest = holder;
      while (true) {
        const auto comma = rest.find(',');
        o.plan.holder.emplace_back(rest.substr(0, comma));
        if (comma == std::string_view::npos) {
          break;
        }
        rest.remove_prefix(comma + 1);
      }
    }
    o.plan.floor = get_or("floor", "");
    o.plan.stock_margin = real("stock_margin");
    o.plan.clearance_min = real("clearance_min");
  }
  SUBFEED_TRY_ASSIGN(o.setup, setup_flags_of(fields, where));
  if (const auto it = fields.find("check_cage"); it != fields.end()) {
    o.check_cage = it->second;
  }
  if (!bad_key.empty()) {
    return fail(ErrorCode::bad_input, "job record without a valid '" + bad_key + "'", where);
  }
  return o;
}

} // namespace subfeed::job
