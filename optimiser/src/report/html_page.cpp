// HtmlPage: skeleton, style sheet and scripts of the self-contained report pages.
#include "stride/optimiser/report/html_page.hpp"

#include "stride/core/text_escape.hpp"

#include <cmath>
#include <cstdio>

#include "assets.hpp"
#include "stride/optimiser/report/svg_chart.hpp"

namespace stride::opt::report {

std::string html_escape(const std::string& text) {
  return core::xml_escape(text);
}

std::string missing_note(const std::string& text) {
  return "<p class=\"missing\">" + html_escape(text) + "</p>\n";
}

std::string format_number(double v, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string percent_change(double v, double o) {
  if (!(std::abs(o) > 0) || !std::isfinite(o) || !std::isfinite(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+.1f %%", 100.0 * (v - o) / o);
  return buf;
}

HtmlPage::HtmlPage(std::string title, std::string subtitle)
    : title_(std::move(title)), subtitle_(std::move(subtitle)) {}

void HtmlPage::add_warnings(const std::vector<std::string>& warnings) {
  warnings_.insert(warnings_.end(), warnings.begin(), warnings.end());
}

void HtmlPage::add_section(const std::string& id, const std::string& heading,
                           const std::string& body) {
  nav_.emplace_back(id, heading);
  sections_ += "<section class=\"report-section\" id=\"" + id + "\" data-section=\"" + id +
               "\">\n<h2>" + html_escape(heading) + "</h2>\n" + body + "</section>\n";
}

void HtmlPage::set_replay_data(const nlohmann::json& data) {
  // "</" would end the <script> element; "<\/" is the same JSON string.
  const std::string text = data.dump();
  replay_json_.clear();
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') {
      replay_json_ += "<\\/";
      ++i;
    } else {
      replay_json_ += text[i];
    }
  }
}

void HtmlPage::add_script(const std::string& id, const std::string& code) {
  std::string safe;
  safe.reserve(code.size());
  for (std::size_t i = 0; i < code.size(); ++i) {
    if (code.compare(i, 8, "</script") == 0) {
      safe += "<\\/script";
      i += 7;
    } else {
      safe += code[i];
    }
  }
  scripts_ += "<script id=\"" + html_escape(id) + "\">\n" + safe + "\n</script>\n";
}

std::string HtmlPage::str() const {
  std::string out =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" +
      html_escape(title_) + "</title>\n<style>\n" + assets::kReportCss +
      "</style>\n</head>\n<body>\n";
  out += "<header><h1>" + html_escape(title_) + "</h1><p class=\"subtitle\">" +
         html_escape(subtitle_) + "</p>\n<nav>";
  for (const auto& [id, heading] : nav_)
    out += "<a href=\"#" + id + "\">" + html_escape(heading) + "</a> ";
  out += "</nav></header>\n<main>\n";
  out += "<div id=\"warnings\"" + std::string(warnings_.empty() ? " hidden" : "") + ">";
  if (!warnings_.empty()) {
    out += "<strong>Missing or damaged in this run directory:</strong><ul>";
    for (const auto& w : warnings_) out += "<li>" + html_escape(w) + "</li>";
    out += "</ul>";
  }
  out += "</div>\n" + sections_ + "</main>\n";
  if (!replay_json_.empty()) {
    out += "<script type=\"application/json\" id=\"replay-data\">" + replay_json_ +
           "</script>\n<script>\n" + assets::kReplayJs + "</script>\n" + scripts_;
  }
  out += "</body>\n</html>\n";
  return out;
}

}  // namespace stride::opt::report
