// ServoTable loading and validation.
#include "stride/firmware/servo_table.hpp"

#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "stride/core/json_file.hpp"

#include "stride/firmware/firmware.hpp"         // data_dir
#include "stride/firmware/parameter_store.hpp"  // format_number

namespace stride::fw {

std::string_view to_string(ServoModel model) {
  return model == ServoModel::kMx64 ? "MX-64" : "MX-106";
}

namespace {

Status field_error(const std::string& where, const std::string& what) {
  return Status::error(where + ": " + what);
}

Status read_number(const nlohmann::json& servo, const std::string& where, const char* key,
                   double& out) {
  if (!servo.contains(key)) return field_error(where + "." + key, "missing");
  const auto& v = servo[key];
  if (!v.is_number()) return field_error(where + "." + key, "must be a number, got " + v.dump());
  out = v.get<double>();
  if (!std::isfinite(out)) return field_error(where + "." + key, "must be finite");
  return {};
}

}  // namespace

Status ServoTable::load(const std::filesystem::path& path, ServoTable& out) {
  const std::string file = path.string();
  nlohmann::json doc;
  if (Status s = core::read_json_file(path, doc); !s) return s;
  if (!doc.is_object() || !doc.contains("servos") || !doc["servos"].is_array()) {
    return Status::error(file + ": servos: missing or not an array");
  }
  const auto& list = doc["servos"];
  if (list.size() != hal::kServoCount) {
    return Status::error(file + ": servos: expected " + std::to_string(hal::kServoCount) +
                         " entries, got " + std::to_string(list.size()));
  }
  ServoTable table;
  std::set<int> ids;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const auto& servo = list[i];
    const std::string where = file + ": servos[" + std::to_string(i) + "]";
    if (!servo.is_object()) return field_error(where, "must be an object");
    double id = 0, direction = 0;
    ServoSpec spec;
    if (Status s = read_number(servo, where, "id", id); !s) return s;
    if (id != std::floor(id) || id < 1 || id > static_cast<double>(hal::kServoCount)) {
      return field_error(where + ".id", "must be an integer 1..20, got " + format_number(id));
    }
    if (!ids.insert(static_cast<int>(id)).second) {
      return field_error(where + ".id", "duplicate id " + format_number(id));
    }
    spec.id = static_cast<std::uint8_t>(id);
    if (!servo.contains("name") || !servo["name"].is_string() ||
        servo["name"].get<std::string>().empty()) {
      return field_error(where + ".name", "missing or not a non-empty string");
    }
    spec.name = servo["name"].get<std::string>();
    if (!names.insert(spec.name).second) {
      return field_error(where + ".name", "duplicate name '" + spec.name + "'");
    }
    const std::string model = servo.value("model", std::string());
    if (model == "MX-64") {
      spec.model = ServoModel::kMx64;
    } else if (model == "MX-106") {
      spec.model = ServoModel::kMx106;
    } else {
      return field_error(where + ".model", "must be \"MX-64\" or \"MX-106\", got '" + model + "'");
    }
    if (Status s = read_number(servo, where, "direction", direction); !s) return s;
    if (direction != 1.0 && direction != -1.0) {
      return field_error(where + ".direction", "must be 1 or -1, got " + format_number(direction));
    }
    spec.direction = static_cast<int>(direction);
    if (Status s = read_number(servo, where, "offset_rad", spec.offset_rad); !s) return s;
    if (std::abs(spec.offset_rad) > std::numbers::pi) {
      return field_error(where + ".offset_rad",
                         "must be within [-pi, pi], got " + format_number(spec.offset_rad));
    }
    if (Status s = read_number(servo, where, "min_rad", spec.min_rad); !s) return s;
    if (Status s = read_number(servo, where, "max_rad", spec.max_rad); !s) return s;
    if (!(spec.min_rad < spec.max_rad)) {
      return field_error(where + ".min_rad", "must be below max_rad (" +
                                                 format_number(spec.min_rad) +
                                                 " >= " + format_number(spec.max_rad) + ")");
    }
    const std::size_t index = hal::servo_index(spec.id);
    table.servos_[index] = std::move(spec);
  }
  out = std::move(table);
  return {};
}

std::filesystem::path ServoTable::default_path() {
  return data_dir() / "config" / "servo_table.json";
}

const ServoTable& ServoTable::defaults() {
  static const ServoTable table = [] {
    ServoTable t;
    if (Status s = load(default_path(), t); !s) throw std::runtime_error(s.message());
    return t;
  }();
  return table;
}

std::optional<std::size_t> ServoTable::index_of(std::string_view name) const {
  for (std::size_t i = 0; i < servos_.size(); ++i) {
    if (servos_[i].name == name) return i;
  }
  return std::nullopt;
}

}  // namespace stride::fw
