// libFuzzer target: the robot description loader (YAML text -> validated RobotDescription or
// diagnostics), through load_robot_from_string so no temporary files are involved.
//
// What counts as a failure (the fuzzer stops and saves the input):
//   - any crash, sanitizer report (ASan/UBSan), or hang (-timeout);
//   - an exception escaping load_robot_from_string (it promises diagnostics for every input);
//   - an inconsistent result: ok() with errors, not ok() without errors, a diagnostic without
//     a message, more diagnostics than the sink's cap, diagnostics out of file order,
//     a successful description whose links or references point outside their arrays;
//   - the loader's catch-all firing ("cannot read the description: ..."): that diagnostic means
//     a reader met a YAML shape it did not foresee and the user gets a vague message at 1:1.
//     Set DYNCC_FUZZ_ALLOW_CATCH_ALL=1 to tolerate it (e.g. while such a finding is being fixed).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "robot/description.hpp"
#include "robot/diagnostics.hpp"
#include "robot/load.hpp"
#include "sym/print.hpp"

namespace {

using dyncc::robot::LoadResult;
using dyncc::robot::RobotDescription;

// Hand-written descriptions are a few kB (robots/kraft.yaml is ~7 kB); much larger inputs only
// slow the fuzzer down without reaching new code.
constexpr std::size_t kMaxInput = 64 * 1024;

[[noreturn]] void fail(std::string_view input, const std::string& what) {
  std::fprintf(stderr, "fuzz_robot_yaml: %s\n  input (%zu bytes):\n%.*s\n", what.c_str(), input.size(),
               static_cast<int>(std::min<std::size_t>(input.size(), 2000)), input.data());
  std::abort();
}

bool allow_catch_all() {
  static const bool allow = [] {
    const char* v = std::getenv("DYNCC_FUZZ_ALLOW_CATCH_ALL");
    return v != nullptr && std::string_view(v) == "1";
  }();
  return allow;
}

void check_diagnostics(std::string_view text, const LoadResult& r) {
  if (r.ok() != (r.error_count() == 0)) {
    fail(text,
         "ok() is " + std::string(r.ok() ? "true" : "false") + " with " + std::to_string(r.error_count()) + " errors");
  }
  // The cap plus the one "stopped after N" note.
  if (r.diagnostics.size() > dyncc::robot::DiagnosticSink::kMaxDiagnostics + 1) {
    fail(text, std::to_string(r.diagnostics.size()) + " diagnostics, more than the cap");
  }
  int previous_line = 0;
  int previous_column = 0;
  for (const auto& d : r.diagnostics) {
    if (d.message.empty()) fail(text, "diagnostic without a message: " + d.format());
    if (d.location.line < 0 || d.location.column < 0) fail(text, "negative location: " + d.format());
    const bool truncation_note = &d == &r.diagnostics.back() && d.message.rfind("too many problems", 0) == 0;
    if (!truncation_note && (d.location.line < previous_line ||
                             (d.location.line == previous_line && d.location.column < previous_column))) {
      fail(text, "diagnostics not in file order at: " + d.format());
    }
    previous_line = d.location.line;
    previous_column = d.location.column;
    if (!allow_catch_all() && d.message.rfind("cannot read the description", 0) == 0) {
      fail(text, "loader catch-all fired (a reader did not foresee this input): " + d.format());
    }
    (void)d.format();
  }
}

void check_description(std::string_view text, const RobotDescription& robot) {
  const int n_links = static_cast<int>(robot.links.size());
  const int n_coordinates = static_cast<int>(robot.coordinates.size());
  for (int i = 0; i < n_links; ++i) {
    const auto& link = robot.links[static_cast<std::size_t>(i)];
    if (link.parent < -1 || link.parent >= i) {
      fail(text, "link " + link.name + " has parent index " + std::to_string(link.parent) + " (parents come first)");
    }
    (void)dyncc::sym::to_string(link.joint_expression());
    (void)robot.children(i);
  }
  auto check_coordinate = [&](int c, const char* what) {
    if (c < 0 || c >= n_coordinates) fail(text, std::string(what) + " refers to coordinate " + std::to_string(c));
    (void)robot.coordinate_name(c);
  };
  for (const auto& f : robot.friction) check_coordinate(f.coordinate, "friction");
  for (const auto& r : robot.rotors) {
    check_coordinate(r.coordinate, "rotor");
    (void)r.reflected_inertia();
  }
  for (const auto& l : robot.joint_limits) check_coordinate(l.coordinate, "joint limit");
  for (const auto& p : robot.parameters) {
    if (p.link < -1 || p.link >= n_links)
      fail(text, "parameter " + p.name + " refers to link " + std::to_string(p.link));
    if (p.coordinate < -1 || p.coordinate >= n_coordinates) {
      fail(text, "parameter " + p.name + " refers to coordinate " + std::to_string(p.coordinate));
    }
    if (robot.find_parameter(p.name) == nullptr) fail(text, "parameter " + p.name + " not found by name");
  }
  for (const auto& loop : robot.loops) {
    for (const auto& point : loop.points) {
      if (point.link < -1 || point.link >= n_links) {
        fail(text, "loop " + loop.name + " refers to link " + std::to_string(point.link));
      }
    }
  }
  for (const auto& c : robot.constants) {
    if (robot.find_constant(c.name) == nullptr) fail(text, "constant " + c.name + " not found by name");
  }
  (void)robot.constant_values();
  (void)robot.constant_doubles();
  (void)robot.nominal_values();
  (void)robot.gravity_values();
  (void)robot.children(-1);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxInput) return -1;  // -1: do not add to the corpus
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const LoadResult r = dyncc::robot::load_robot_from_string(text, "fuzz.yaml");  // must not throw
  check_diagnostics(text, r);
  if (r.ok()) check_description(text, *r.robot);
  return 0;
}
