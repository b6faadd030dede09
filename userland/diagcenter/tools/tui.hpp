// SPDX-License-Identifier: GPL-2.0
// The ncurses side of advee-diagnostic-center: the terminal (RAII), key
// translation and drawing the controller's current view of the model.
#pragma once

#include "advee/diagcenter/controller.hpp"
#include "advee/diagcenter/model.hpp"

namespace advee::diagcenter::tui {

// initscr() .. endwin(): the terminal is restored however the program leaves
// (exceptions included).
class Screen {
 public:
  Screen();
  ~Screen();
  Screen(const Screen&) = delete;
  Screen& operator=(const Screen&) = delete;
  // Every key waiting (non-blocking), translated; Key::None when there is none.
  Key read_key();
};

void draw(const Model& model, const Controller& ctl, double now, const char* lcm_url);

}  // namespace advee::diagcenter::tui
