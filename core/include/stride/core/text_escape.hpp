// Escaping text for XML, SVG and HTML (element text and attribute values in either quotes).
#pragma once

#include <string>

namespace stride::core {

/// `text` with & < > " ' replaced by their entities.
std::string xml_escape(const std::string& text);

}  // namespace stride::core
