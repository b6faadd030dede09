// SPDX-License-Identifier: GPL-2.0
// advee-test-module NAME [--crash-after-ms N] [--exit-code C] [--log FILE]:
// a module with no work of its own. It follows the state machine, announces
// its state, and with --crash-after-ms exits with code C (default 0x41) after
// N ms, to exercise the supervisor's restart and back-off. With --log it
// appends one line per state change ("<pid> <state>") for the tests.
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <unistd.h>

#include "advee/module/module.hpp"

using namespace advee::module;

int main(int argc, char** argv) {
  return guarded_main("advee-test-module", [&] {
    if (argc < 2) {
      std::cerr << "usage: advee-test-module NAME [--crash-after-ms N] [--exit-code C] [--log FILE]\n";
      return 2;
    }
    ModuleOptions o;
    o.name = argv[1];
    o.errors.print_severity = kSeverityNone;
    long crash_ms = -1;
    int code = exit_code(ExitKind::Other, 1);
    std::string log;
    for (int i = 2; i + 1 < argc; i += 2) {
      const std::string a = argv[i];
      if (a == "--crash-after-ms") crash_ms = std::stol(argv[i + 1]);
      else if (a == "--exit-code") code = std::stoi(argv[i + 1], nullptr, 0);
      else if (a == "--log") log = argv[i + 1];
      else throw std::invalid_argument("unknown option " + a);
    }
    Module m(o);
    std::ofstream out;
    if (!log.empty()) out.open(log, std::ios::app);
    m.on_state_change([&](State, State to) {
      if (out) out << ::getpid() << " " << to_string(to) << std::endl;
    });
    if (crash_ms >= 0)
      m.every(std::chrono::milliseconds(crash_ms), [code] { std::_Exit(code); }, false);
    return m.run();
  });
}
