// The report page's style sheet and script, embedded from optimiser/src/report/assets/ at
// build time (cmake/EmbedAssets.cmake writes report_assets.cpp in the build tree).
#pragma once

namespace stride::opt::report::assets {

extern const char kReportCss[];
extern const char kReplayJs[];
extern const char kReplay3dJs[];

}  // namespace stride::opt::report::assets
