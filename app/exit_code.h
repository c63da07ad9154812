// The exit codes of every twinrender command, as OpenImageIO's idiff gives them (docs/cli.md).
#pragma once

#include "compare/thresholds.h"

namespace twinrender::app {

enum class ExitCode {
    Pass = 0,           // every check passed
    Warn = 1,           // some check is past a warning bound, none past a failing one
    Fail = 2,           // some check failed (or a measurement could not be made)
    NotComparable = 3,  // the images cannot be compared (sizes, channels)
    BadInput = 4,       // bad input or environment: unreadable file, invalid scene, no usable GL
};

// The exit code of a verdict.
constexpr ExitCode exitCodeOf(compare::Status status) {
    switch (status) {
        case compare::Status::Pass:
            return ExitCode::Pass;
        case compare::Status::Warn:
            return ExitCode::Warn;
        case compare::Status::Fail:
            return ExitCode::Fail;
    }
    return ExitCode::Fail;
}

// What the process returns.
constexpr int exitStatus(ExitCode code) {
    return static_cast<int>(code);
}

}  // namespace twinrender::app
