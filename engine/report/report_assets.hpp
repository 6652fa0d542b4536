#pragma once
// The files a report inlines, compiled in by engine/report/CMakeLists.txt.
namespace dampbench::report {

extern const char* const kReportJs;   ///< assets/report.js: draws the figures from the embedded JSON
extern const char* const kReportCss;  ///< assets/report.css
extern const char* const kD3Js;       ///< D3 v3 (Debian libjs-d3, BSD licence)

}  // namespace dampbench::report
