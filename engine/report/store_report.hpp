#pragma once
// The HTML report of a sweep's store (`dampbench report STORE`): every stored task group, its records read
// again from the paths the stored sweep file names, and the sweep's tables.
#include <string>

#include <nlohmann/json.hpp>

#include "engine/report/html_report.hpp"
#include "engine/sweep/plan.hpp"
#include "engine/sweep/store.hpp"

namespace dampbench::report {

/// The report's JSON document (report_data) of a store. Records are re-read with `loader`; one that is missing
/// or whose content hash differs from the store's is listed with the reason and its loops are not drawn.
/// InputError for a store without a finished task group.
nlohmann::ordered_json store_report_data(const sweep::Store& store, const sweep::Loader& loader,
                                         const HtmlOptions& options = {});

/// The whole HTML document of a store (render_html of the same input).
std::string store_report_html(const sweep::Store& store, const sweep::Loader& loader, const HtmlOptions& options = {});

}  // namespace dampbench::report
