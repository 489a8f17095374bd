// ParameterStore implementation (see the header for the contract).
#include "stride/firmware/parameter_store.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "stride/core/atomic_file.hpp"
#include "stride/core/json_file.hpp"

namespace stride::fw {

std::string_view to_string(ParamType type) {
  switch (type) {
    case ParamType::kReal:
      return "real";
    case ParamType::kInt:
      return "int";
    case ParamType::kBool:
      return "bool";
  }
  return "?";
}

std::string format_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

namespace {

std::string range_text(const ParamSpec& s) {
  if (s.type == ParamType::kBool) return "true|false";
  std::string text = "[" + format_number(s.min) + ", " + format_number(s.max) + "]";
  if (!s.unit.empty() && s.unit != "1") text += " " + s.unit;
  return text;
}

}  // namespace

ParamHandle ParameterStore::add(ParamSpec spec) {
  const std::string& n = spec.name;
  if (n.empty()) throw std::invalid_argument("parameter: empty name");
  if (index_.count(n) != 0) throw std::invalid_argument("parameter " + n + ": registered twice");
  if (spec.type == ParamType::kBool) {
    spec.min = 0.0;
    spec.max = 1.0;
  }
  if (!(spec.min <= spec.max)) {
    throw std::invalid_argument("parameter " + n + ": min " + format_number(spec.min) + " > max " +
                                format_number(spec.max));
  }
  if (!(spec.default_value >= spec.min && spec.default_value <= spec.max)) {
    throw std::invalid_argument("parameter " + n + ": default " +
                                format_number(spec.default_value) + " outside " + range_text(spec));
  }
  if (spec.type != ParamType::kReal && std::floor(spec.default_value) != spec.default_value) {
    throw std::invalid_argument("parameter " + n + ": default must be integral");
  }
  const auto handle = static_cast<ParamHandle>(specs_.size());
  index_.emplace(n, handle);
  live_.emplace_back(spec.default_value);
  std::lock_guard lock(staging_mutex_);
  staged_values_.push_back(spec.default_value);
  staged_dirty_.push_back(0);
  specs_.push_back(std::move(spec));
  return handle;
}

ParamHandle ParameterStore::add_real(std::string name, double default_value, double min, double max,
                                     std::string unit, std::string description) {
  ParamSpec spec;
  spec.name = std::move(name);
  spec.type = ParamType::kReal;
  spec.default_value = default_value;
  spec.min = min;
  spec.max = max;
  spec.unit = std::move(unit);
  spec.description = std::move(description);
  return add(std::move(spec));
}

std::optional<ParamHandle> ParameterStore::find(std::string_view name) const {
  const auto it = index_.find(name);
  if (it == index_.end()) return std::nullopt;
  return it->second;
}

Status ParameterStore::get(std::string_view name, double& out) const {
  const auto handle = find(name);
  if (!handle) return Status::error("unknown parameter '" + std::string(name) + "'");
  out = value(*handle);
  return {};
}

Status ParameterStore::validate(ParamHandle handle, double value) const {
  const ParamSpec& s = specs_[handle];
  if (s.read_only) return Status::error(s.name + ": read-only");
  if (!std::isfinite(value)) return Status::error(s.name + ": value is not a finite number");
  if (s.type == ParamType::kBool && value != 0.0 && value != 1.0) {
    return Status::error(s.name + ": expects a bool (true|false), got " + format_number(value));
  }
  if (s.type == ParamType::kInt && std::floor(value) != value) {
    return Status::error(s.name + ": expects an integer in " + range_text(s) + ", got " +
                         format_number(value));
  }
  if (value < s.min || value > s.max) {
    return Status::error(s.name + ": " + format_number(value) + " outside the allowed range " +
                         range_text(s));
  }
  return {};
}

Status ParameterStore::check(std::string_view name, double value) const {
  const auto handle = find(name);
  if (!handle) return Status::error("unknown parameter '" + std::string(name) + "'");
  return validate(*handle, value);
}

Status ParameterStore::stage(const std::vector<ParamWrite>& batch) {
  for (const auto& [name, value] : batch) {
    if (Status s = check(name, value); !s) return s;
  }
  std::lock_guard lock(staging_mutex_);
  for (const auto& [name, value] : batch) {
    const ParamHandle h = *find(name);
    staged_values_[h] = value;
    staged_dirty_[h] = 1;
  }
  if (!batch.empty()) staged_pending_ = true;
  return {};
}

Status ParameterStore::stage(std::string_view name, double value) {
  return stage(std::vector<ParamWrite>{{std::string(name), value}});
}

bool ParameterStore::apply_staged(ParamChangeSink* changes) noexcept {
  std::unique_lock lock(staging_mutex_, std::try_to_lock);
  if (!lock.owns_lock() || !staged_pending_) return false;
  for (std::size_t i = 0; i < live_.size(); ++i) {
    if (staged_dirty_[i] != 0) {
      live_[i].store(staged_values_[i], std::memory_order_relaxed);
      staged_dirty_[i] = 0;
      if (changes != nullptr)
        changes->on_param_change(static_cast<ParamHandle>(i), staged_values_[i]);
    }
  }
  staged_pending_ = false;
  ++applied_batches_;
  return true;
}

bool ParameterStore::has_staged() const {
  std::lock_guard lock(staging_mutex_);
  return staged_pending_;
}

Status ParameterStore::set_now(const std::vector<ParamWrite>& batch) {
  for (const auto& [name, value] : batch) {
    if (Status s = check(name, value); !s) return s;
  }
  for (const auto& [name, v] : batch) live_[*find(name)].store(v, std::memory_order_relaxed);
  return {};
}

Status ParameterStore::stage_defaults() {
  std::vector<ParamWrite> batch;
  for (const ParamSpec& s : specs_) {
    if (!s.read_only) batch.emplace_back(s.name, s.default_value);
  }
  return stage(batch);
}

std::vector<ParamHandle> ParameterStore::list(std::string_view prefix) const {
  std::vector<ParamHandle> out;
  for (ParamHandle h = 0; h < specs_.size(); ++h) {
    if (std::string_view(specs_[h].name).substr(0, prefix.size()) == prefix) out.push_back(h);
  }
  return out;
}

namespace {

// Flattens nested objects into dotted names; reports non-numeric leaves.
Status flatten(const nlohmann::json& node, const std::string& prefix, std::string_view origin,
               std::vector<std::pair<std::string, const nlohmann::json*>>& out) {
  if (!node.is_object()) {
    return Status::error(std::string(origin) + ": expected a JSON object of parameters");
  }
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string name = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it.value().is_object()) {
      if (Status s = flatten(it.value(), name, origin, out); !s) return s;
    } else {
      out.emplace_back(name, &it.value());
    }
  }
  return {};
}

}  // namespace

Status ParameterStore::parse_json(const nlohmann::json& doc, std::vector<ParamWrite>& out,
                                  std::string_view origin) const {
  std::vector<std::pair<std::string, const nlohmann::json*>> leaves;
  if (Status s = flatten(doc, "", origin, leaves); !s) return s;
  std::vector<ParamWrite> batch;
  batch.reserve(leaves.size());
  for (const auto& [name, node] : leaves) {
    const auto handle = find(name);
    const std::string where = std::string(origin) + ": ";
    if (!handle) return Status::error(where + "unknown parameter '" + name + "'");
    const ParamSpec& spec = specs_[*handle];
    double value = 0.0;
    if (spec.type == ParamType::kBool) {
      if (!node->is_boolean()) {
        return Status::error(where + name + ": expects true or false, got " + node->dump());
      }
      value = node->get<bool>() ? 1.0 : 0.0;
    } else if (node->is_number()) {
      value = node->get<double>();
    } else {
      return Status::error(where + name + ": expects a number (" +
                           std::string(to_string(spec.type)) + "), got " + node->dump());
    }
    if (spec.read_only && value == this->value(*handle)) continue;  // saved files may echo them
    if (Status s = validate(*handle, value); !s) return Status::error(where + s.message());
    batch.emplace_back(name, value);
  }
  out = std::move(batch);
  return {};
}

Status ParameterStore::parse_json_file(const std::filesystem::path& path,
                                       std::vector<ParamWrite>& out) const {
  nlohmann::json doc;
  if (Status s = core::read_json_file(path, doc); !s) return s;
  return parse_json(doc, out, path.string());
}

Status ParameterStore::load_file_now(const std::filesystem::path& path) {
  std::vector<ParamWrite> batch;
  if (Status s = parse_json_file(path, batch); !s) return s;
  return set_now(batch);
}

Status ParameterStore::stage_file(const std::filesystem::path& path) {
  std::vector<ParamWrite> batch;
  if (Status s = parse_json_file(path, batch); !s) return s;
  return stage(batch);
}

nlohmann::json ParameterStore::to_json(std::string_view prefix) const {
  nlohmann::json doc = nlohmann::json::object();
  for (ParamHandle h : list(prefix)) {
    const ParamSpec& s = specs_[h];
    if (s.type == ParamType::kBool) {
      doc[s.name] = value(h) != 0.0;
    } else if (s.type == ParamType::kInt) {
      doc[s.name] = static_cast<long long>(value(h));
    } else {
      doc[s.name] = value(h);
    }
  }
  return doc;
}

nlohmann::json ParameterStore::describe_json(std::string_view prefix) const {
  nlohmann::json doc = nlohmann::json::array();
  for (ParamHandle h : list(prefix)) {
    const ParamSpec& s = specs_[h];
    doc.push_back({{"name", s.name},
                   {"type", to_string(s.type)},
                   {"value", value(h)},
                   {"default", s.default_value},
                   {"min", s.min},
                   {"max", s.max},
                   {"unit", s.unit},
                   {"description", s.description},
                   {"read_only", s.read_only},
                   {"needs_restart", s.needs_restart}});
  }
  return doc;
}

Status ParameterStore::save_file(const std::filesystem::path& path, std::string_view prefix) const {
  return core::write_file_atomically(path, to_json(prefix).dump(2) + "\n");
}

}  // namespace stride::fw
