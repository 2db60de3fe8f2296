#pragma once
// The motion gate (geometry/motion_gate.hpp) for CL data made elsewhere, which `run` and
// `post --cage` pass every pose through: the cage's limit surface and the CL header's ball,
// and the whole tool and fixture where the header records them (PPRINT TOOL, FIXTURE).

#include "base/error.hpp"
#include "cl/cl_pose.hpp"
#include "geometry/motion_gate.hpp"
#include "job/setup_flags.hpp"

#include <filesystem>

namespace subfeed::job {

// A cutter other than a ball end is refused: the gate cannot yet measure it. A tolerance of
// 0 is the gate's default. The cage is set up as the CL header records (`cl_file` names it
// in errors), or as `setup` says when it records nothing.
[[nodiscard]] Expected<geometry::MotionGate>
gate_for_cl(const std::filesystem::path& cage, const cl::ClHeader& header,
            const std::string& cl_file, const SetupFlags& setup, int level, double tolerance_mm);

} // namespace subfeed::job
