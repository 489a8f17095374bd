// CliArgs: a small command-line parser shared by stride-fw and the stride subcommands.
//
// Grammar: `--name value`, `--name=value`, `--flag`, and positional words. Options are declared
// first, so an unknown option, a missing value or a bad number is a one-line error naming it.
// An option given more than once keeps its last value for get() and every value for get_all().
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "stride/core/status.hpp"

namespace stride::core {

class CliArgs {
 public:
  /// Declares `--name VALUE` (takes_value) or `--name` (flag) with a help line.
  CliArgs& option(const std::string& name, const std::string& help, bool takes_value = true,
                  std::optional<std::string> default_value = std::nullopt);
  /// Parses argv[first..argc). Returns an error naming the bad word.
  Status parse(int argc, const char* const* argv, int first = 1);

  bool has(const std::string& name) const;
  std::string get(const std::string& name, const std::string& fallback = {}) const;
  /// Every value given for `name`, in order (a repeatable option such as --push); the default
  /// is not included. get() returns the last one.
  std::vector<std::string> get_all(const std::string& name) const;
  /// Typed getters: the error names the option and the bad text.
  Status get_double(const std::string& name, double& out) const;
  Status get_int(const std::string& name, std::int64_t& out) const;
  const std::vector<std::string>& positional() const { return positional_; }

  /// "Options:" help text listing every declared option.
  std::string help() const;

 private:
  struct Spec {
    std::string help;
    bool takes_value = true;
    std::optional<std::string> default_value;
  };
  std::map<std::string, Spec> specs_;
  std::vector<std::string> order_;
  std::map<std::string, std::string> values_;
  std::map<std::string, std::vector<std::string>> every_value_;
  std::vector<std::string> positional_;
};

}  // namespace stride::core
