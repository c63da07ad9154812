// The collision study (docs/studies.md): bleeding across the contact of two bodies.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/studies/common.h"
#include "app/studies/study_list.h"

namespace twinrender::app::study {

std::vector<StudyPoint> collisionPoints(bool quick) {
    // Gap between the two surfaces (radius 0.6 each), scene units; < 0 overlapping.
    const std::vector<double> gaps =
        quick ? std::vector<double>{0.2, 0.0, -0.15}
              : std::vector<double>{0.3, 0.15, 0.05, 0.0, -0.1, -0.2, -0.3};
    std::vector<StudyPoint> pts;
    for (const bool ssss : {true, false})
        for (double g : gaps) {
            const double c = 0.6 + 0.5 * g;
            pts.push_back(
                {ssss ? "SSSS on" : "SSSS off",
                 g,
                 {set("realtime.ssss.enabled", ssss ? "true" : "false"),
                  set("bodies.cold.center", vec(-c, 0, 0)), set("bodies.hot.center", vec(c, 0, 0))},
                 ""});
        }
    return pts;
}

void collisionConclude(StudyResult& s) {
    s.chart = seriesChart(s, "contact.uv_mean");
    const auto all = bySeries(s);
    const auto* on = seriesRows(all, "SSSS on");
    const auto* off = seriesRows(all, "SSSS off");
    if (!on || !off) {
        s.finding = "no pair of SSSS on/off renders to compare";
        return;
    }
    // In contact: touching or overlapping (gap <= 0).
    auto touching = [](const std::vector<const StudyRow*>& rows) {
        std::vector<const StudyRow*> t;
        for (const StudyRow* r : rows)
            if (r->x <= 0.0) t.push_back(r);
        return t.empty() ? rows : t;
    };
    const double uvOn = meanOf(touching(*on), "contact.uv_mean"),
                 uvOff = meanOf(touching(*off), "contact.uv_mean");
    const double eOn = meanOf(touching(*on), "contact.emission_rmse"),
                 eOff = meanOf(touching(*off), "contact.emission_rmse");
    const double interior = meanOf(touching(*on), "uv.mean");
    s.facts["contact_uv"] = {{"ssss_on", jsonOrNull(uvOn)}, {"ssss_off", jsonOrNull(uvOff)}};
    s.facts["contact_emission"] = {{"ssss_on", jsonOrNull(eOn)}, {"ssss_off", jsonOrNull(eOff)}};
    s.facts["interior_uv"] = jsonOrNull(interior);
    auto change = [](double a, double b) {
        return std::isfinite(a) && std::isfinite(b) && b > 0
                   ? fmt::format("{:+.0f} %", 100.0 * (a / b - 1.0))
                   : std::string("n/a");
    };
    // Emission is constant per body here: a band error below this is rounding, not bleeding.
    constexpr double EMISSION_FLOOR = 1e-4;
    const std::string emission =
        std::max(eOn, eOff) < EMISSION_FLOOR
            ? fmt::format("emission does not bleed (band error below {:g} either way)",
                          EMISSION_FLOOR)
            : fmt::format("emission error {} with SSSS, {} without ({} from smoothing)", num(eOn),
                          num(eOff), change(eOn, eOff));
    s.facts["contact_over_interior"] = jsonOrNull(uvOn / interior);
    s.finding = fmt::format(
        "in contact, the uv error along the bodies' boundary is {} with SSSS and {} without ({} "
        "from smoothing), {}x the "
        "interior's {}; {}",
        num(uvOn), num(uvOff), change(uvOn, uvOff), num(uvOn / interior), num(interior), emission);
}

}  // namespace twinrender::app::study
