// A one-line progress bar on stderr: done/total, rate and ETA, redrawn in place.
#pragma once

#include <cstdint>
#include <string>

namespace glint {

// "[########            ] 32/64 spp  12.5 spp/s  ETA 0:03"; `done` may be fractional (a pass
// part traced), shown rounded down.
std::string format_progress(double done, int64_t total, double seconds, const char* unit,
                            int bar_width = 24);

// For a time budget: "[####        ] 3.2/10.0 s  45 spp  14.1 spp/s"
std::string format_time_progress(double seconds, double budget, int64_t samples, int bar_width = 24);

// The estimated error after a bar: "  est. relMSE 1.2e-03" and, with a target > 0,
// " (target 1.0e-03)"; "" when the estimate is unknown (negative).
std::string format_error_estimate(double estimated_relmse, double target);

}  // namespace glint
