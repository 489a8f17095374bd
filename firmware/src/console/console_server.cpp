// ConsoleServer implementation: the console thread's read-edit-execute-reply loop.
#include "stride/firmware/console/console_server.hpp"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <cstdio>

namespace stride::fw::console {

ConsoleServer::ConsoleServer(std::unique_ptr<ConsoleTransport> transport, ConsoleContext context,
                             ServerOptions options)
    : transport_(std::move(transport)),
      interpreter_(std::move(context)),
      editor_(options.max_line, transport_->wants_echo()),
      options_(options),
      prompt_(transport_->wants_echo() ? "> " : ""),
      line_end_(transport_->wants_echo() ? "\r\n" : "\n") {}

ConsoleServer::~ConsoleServer() {
  stop();
}

void ConsoleServer::start() {
  if (thread_.joinable()) return;
  thread_ = std::thread([this] { run(); });
}

void ConsoleServer::stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
  transport_->close();
}

void ConsoleServer::sleep_interruptible(std::chrono::milliseconds duration) {
  const auto deadline = std::chrono::steady_clock::now() + duration;
  while (!stop_.load() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::min(duration, std::chrono::milliseconds(10)));
  }
}

void ConsoleServer::serve_bytes(std::string_view bytes) {
  std::vector<EditedLine> lines;
  std::string out;
  const std::uint64_t noise_before = editor_.dropped_bytes();
  // One byte at a time, so that each line's echo is followed by its own reply.
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    editor_.feed(bytes.substr(i, 1), lines, out);
    for (const EditedLine& line : lines) {
      Reply reply;
      if (line.kind == EditedLine::Kind::kOverlong) {
        ++counters_.overlong_lines;
        reply = Reply::error(
            ErrorCode::kLineTooLong,
            "line longer than " + std::to_string(editor_.max_line()) + " bytes discarded");
      } else if (line.kind == EditedLine::Kind::kCancelled ||
                 line.text.find_first_not_of(' ') == std::string::npos) {
        out += prompt_;  // abandoned or empty line: just a new prompt
        continue;
      } else {
        reply = interpreter_.execute(line.text);
      }
      ++counters_.lines;
      if (!reply.ok()) ++counters_.errors;
      for (const std::string& data : reply.data) out += data + line_end_;
      out += reply.final_line + line_end_ + prompt_;
    }
    lines.clear();
  }
  counters_.noise_bytes += editor_.dropped_bytes() - noise_before;
  if (!out.empty()) (void)transport_->write(out);
}

void ConsoleServer::run() {
  // Threads inherit the creator's policy: leave SCHED_FIFO to the control thread.
  sched_param normal{};
  normal.sched_priority = 0;
  (void)pthread_setschedparam(pthread_self(), SCHED_OTHER, &normal);

  auto backoff = options_.min_backoff;
  bool reported_failure = false;
  char buffer[4096];
  while (!stop_.load()) {
    if (!transport_->is_open()) {
      if (Status s = transport_->open(); !s) {
        ++counters_.failed_opens;
        if (!transport_->reopenable()) break;
        if (!reported_failure) {
          std::fprintf(stderr, "stride-fw: console: %s (retrying)\n", s.message().c_str());
          reported_failure = true;
        }
        sleep_interruptible(backoff);
        backoff = std::min(backoff * 2, options_.max_backoff);
        continue;
      }
      ++counters_.opens;
      reported_failure = false;
      editor_.reset();
      if (options_.banner && transport_->wants_echo()) {
        (void)transport_->write("\r\nstride console on " + transport_->name() + ": type help\r\n" +
                                prompt_);
      }
    }
    const long n = transport_->read(buffer, sizeof buffer, 100);
    if (n > 0) {
      backoff = options_.min_backoff;
      serve_bytes(std::string_view(buffer, static_cast<std::size_t>(n)));
    } else if (n < 0) {
      ++counters_.link_losses;
      transport_->close();
      if (!transport_->reopenable()) break;
      sleep_interruptible(backoff);  // never reopen straight away: no spinning on a flaky link
      backoff = std::min(backoff * 2, options_.max_backoff);
    }
  }
  finished_.store(true);
}

std::unique_ptr<ConsoleServer> make_console(const std::string& where, ConsoleContext context,
                                            ServerOptions options) {
  std::unique_ptr<ConsoleTransport> transport =
      where == "stdio" ? make_stdio_transport() : make_serial_transport(where);
  return std::make_unique<ConsoleServer>(std::move(transport), std::move(context), options);
}

}  // namespace stride::fw::console
