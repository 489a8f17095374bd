// Error code names of the console's `err <code> <message>` replies.
#include "stride/firmware/console/reply.hpp"

namespace stride::fw::console {

std::string_view to_string(ErrorCode code) {
  switch (code) {
    case ErrorCode::kUsage:
      return "usage";
    case ErrorCode::kUnknownCommand:
      return "unknown-command";
    case ErrorCode::kUnknownParameter:
      return "unknown-parameter";
    case ErrorCode::kBadValue:
      return "bad-value";
    case ErrorCode::kReadOnly:
      return "read-only";
    case ErrorCode::kRefused:
      return "refused";
    case ErrorCode::kBadFile:
      return "bad-file";
    case ErrorCode::kIo:
      return "io";
    case ErrorCode::kLineTooLong:
      return "line-too-long";
  }
  return "unknown";
}

}  // namespace stride::fw::console
