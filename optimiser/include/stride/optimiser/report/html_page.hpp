// HtmlPage: the skeleton of a self-contained report page (report.html, `stride sim --html`).
// One file, no network: the style sheet and the replay script are compiled into the binary
// from optimiser/src/report/assets/ (report.css, replay.js; embedded by
// cmake/EmbedAssets.cmake) and written inline; charts are inline SVG; the replay's data is
// one JSON block (<script type="application/json" id="replay-data">).
//
// Every section is a <section class="report-section" id=ID data-section=ID> with an <h2>; a
// section with nothing to show says why in a <p class="missing"> (the browser test checks
// that no section is empty). Warnings (what is missing from a run directory) are listed at
// the top in <div id="warnings">.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace stride::opt::report {

/// Escapes &, <, >, ", ' for HTML text and attributes.
std::string html_escape(const std::string& text);
/// A <p class="missing"> saying what is not there.
std::string missing_note(const std::string& text);
/// "%.*g"-formatted number.
std::string format_number(double v, int digits = 4);
/// A signed percentage change "+12.3 %" of v against o ("" if o is 0 or not finite).
std::string percent_change(double v, double o);

class HtmlPage {
 public:
  HtmlPage(std::string title, std::string subtitle);
  void add_warnings(const std::vector<std::string>& warnings);
  void add_section(const std::string& id, const std::string& heading, const std::string& body);
  /// The replay data (see html_replay.hpp); the page then includes the replay script.
  void set_replay_data(const nlohmann::json& data);
  /// A script written inline after the replay script (in the order added), as
  /// <script id=ID>; "</script" inside it is escaped.
  void add_script(const std::string& id, const std::string& code);
  std::string str() const;

 private:
  std::string title_, subtitle_;
  std::vector<std::string> warnings_;
  std::vector<std::pair<std::string, std::string>> nav_;
  std::string sections_;
  std::string replay_json_;
  std::string scripts_;
};

}  // namespace stride::opt::report
