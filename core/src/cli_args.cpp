// CliArgs implementation.
#include "stride/core/cli_args.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace stride::core {

CliArgs& CliArgs::option(const std::string& name, const std::string& help, bool takes_value,
                         std::optional<std::string> default_value) {
  if (specs_.count(name) == 0) order_.push_back(name);
  specs_[name] = Spec{help, takes_value, std::move(default_value)};
  return *this;
}

Status CliArgs::parse(int argc, const char* const* argv, int first) {
  for (int i = first; i < argc; ++i) {
    std::string word = argv[i];
    if (word.size() > 2 && word.rfind("--", 0) == 0) {
      std::string name = word.substr(2);
      std::optional<std::string> inline_value;
      if (const auto eq = name.find('='); eq != std::string::npos) {
        inline_value = name.substr(eq + 1);
        name = name.substr(0, eq);
      }
      const auto it = specs_.find(name);
      if (it == specs_.end()) return Status::error("unknown option --" + name + " (see --help)");
      if (!it->second.takes_value) {
        if (inline_value) return Status::error("option --" + name + " takes no value");
        values_[name] = "1";
        continue;
      }
      if (inline_value) {
        values_[name] = *inline_value;
      } else {
        if (i + 1 >= argc) return Status::error("option --" + name + " needs a value");
        values_[name] = argv[++i];
      }
      every_value_[name].push_back(values_[name]);
    } else {
      positional_.push_back(std::move(word));
    }
  }
  return {};
}

bool CliArgs::has(const std::string& name) const {
  return values_.count(name) != 0;
}

std::string CliArgs::get(const std::string& name, const std::string& fallback) const {
  if (const auto it = values_.find(name); it != values_.end()) return it->second;
  if (const auto it = specs_.find(name); it != specs_.end() && it->second.default_value) {
    return *it->second.default_value;
  }
  return fallback;
}

std::vector<std::string> CliArgs::get_all(const std::string& name) const {
  if (const auto it = every_value_.find(name); it != every_value_.end()) return it->second;
  return {};
}

Status CliArgs::get_double(const std::string& name, double& out) const {
  const std::string text = get(name);
  if (text.empty()) return {};
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || errno != 0 || !std::isfinite(v)) {
    return Status::error("option --" + name + ": '" + text + "' is not a number");
  }
  out = v;
  return {};
}

Status CliArgs::get_int(const std::string& name, std::int64_t& out) const {
  const std::string text = get(name);
  if (text.empty()) return {};
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0' || errno != 0) {
    return Status::error("option --" + name + ": '" + text + "' is not an integer");
  }
  out = v;
  return {};
}

std::string CliArgs::help() const {
  std::string text = "Options:\n";
  for (const std::string& name : order_) {
    const Spec& s = specs_.at(name);
    std::string left = "  --" + name + (s.takes_value ? " VALUE" : "");
    if (left.size() < 26) left.resize(26, ' ');
    text += left + " " + s.help;
    if (s.default_value) text += " (default " + *s.default_value + ")";
    text += "\n";
  }
  return text;
}

}  // namespace stride::core
