// The run's first page, DIR/index.html: one row per scene that fits the page (its verdict, the
// headline metrics, where its error comes from and its time), the devices the times were
// measured on, and every overview metric a click away in a table that scrolls under its
// scene column.
#pragma once

#include <string>

#include "report/report.h"

namespace twinrender::report {

// The headline metrics of the index's table, in its order: the picture, the shape, the surface.
inline constexpr const char* INDEX_HEADLINE[] = {"beauty.flip", "coverage.iou", "normal.mean_deg"};

std::string indexPage(const RunReport& run);

}  // namespace twinrender::report
