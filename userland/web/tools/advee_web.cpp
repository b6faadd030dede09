// SPDX-License-Identifier: GPL-2.0
// advee-web: the live dashboard of the low level in a browser. Subscribes to
// every LCM channel, forwards each message as JSON over WebSocket and serves
// the page on the same port. docs/web-dashboard.md describes it.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <asio/io_context.hpp>
#include <asio/post.hpp>
#include <asio/signal_set.hpp>
#include <asio/steady_timer.hpp>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <termios.h>
#include <unistd.h>

#include "advee/cli.hpp"
#include "advee/web/bridge_server.hpp"
#include "advee/web/control_publisher.hpp"
#include "advee/web/password_file.hpp"
#include "advee/web/lcm_source.hpp"
#include "advee/web/history.hpp"
#include "advee/web/message_json.hpp"
#include "advee/web/odometry.hpp"
#include "advee/web/scene.hpp"

#ifndef ADVEE_WEB_DATADIR
#define ADVEE_WEB_DATADIR "/usr/share/advee/web"
#endif
#ifndef ADVEE_WEB_OPERATORS
#define ADVEE_WEB_OPERATORS "/etc/advee/web-operators"
#endif
#ifndef ADVEE_ROBOTSIM_SYSCONFDIR
#define ADVEE_ROBOTSIM_SYSCONFDIR "/etc/advee/robotsim"
#endif

namespace {

void log_line(const std::string& s) { std::cerr << "advee-web: " << s << std::endl; }

// HOST:PORT, HOST may be an IPv6 address in brackets.
bool split_listen(const std::string& s, std::string& host, std::uint16_t& port) {
  const auto colon = s.rfind(':');
  if (colon == std::string::npos || colon + 1 == s.size()) return false;
  host = s.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  try {
    std::size_t used = 0;
    const unsigned long p = std::stoul(s.substr(colon + 1), &used);
    if (used != s.size() - colon - 1 || p > 65535) return false;
    port = static_cast<std::uint16_t>(p);
  } catch (const std::exception&) {
    return false;
  }
  return !host.empty();
}

// One line from stdin; without echo when it is a terminal.
std::string read_secret(const char* prompt) {
  termios old{};
  const bool tty = ::isatty(0) && ::tcgetattr(0, &old) == 0;
  if (tty) {
    std::cerr << prompt << std::flush;
    termios quiet = old;
    quiet.c_lflag &= ~static_cast<tcflag_t>(ECHO);
    ::tcsetattr(0, TCSANOW, &quiet);
  }
  std::string line;
  std::getline(std::cin, line);
  if (tty) {
    ::tcsetattr(0, TCSANOW, &old);
    std::cerr << "\n";
  }
  return line;
}

// advee-web passwd: sets (or with --delete removes) one operator's password.
int passwd(const std::string& file, const std::string& name, bool remove, bool random) {
  try {
    advee::web::init_crypto();
    auto f = advee::web::PasswordFile::load(file);
    if (remove) {
      if (!f.remove(name)) {
        std::cerr << "advee-web passwd: no operator " << name << " in " << file << "\n";
        return advee::cli::kExitFailure;
      }
    } else {
      std::string pw;
      if (random) {
        pw = advee::web::random_password();
        std::cout << pw << std::endl;
      } else {
        pw = read_secret("password: ");
        if (::isatty(0) && read_secret("again: ") != pw) {
          std::cerr << "advee-web passwd: the two differ; nothing changed\n";
          return advee::cli::kExitFailure;
        }
      }
      if (pw.size() < 8) {
        std::cerr << "advee-web passwd: at least 8 characters\n";
        return advee::cli::kExitFailure;
      }
      f.set(name, pw);
    }
    f.save(file);
  } catch (const std::exception& e) {
    std::cerr << "advee-web passwd: " << e.what() << "\n";
    return advee::cli::kExitFailure;
  }
  std::cerr << "advee-web passwd: " << file << ": " << name << (remove ? " removed" : " set") << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "advee-web: the Advee low level live in a browser.\n"
      "Subscribes to every LCM channel of the robot (CM_*, LL_*) and to advee-robot-sim's\n"
      "ground truth SIM_DATA_POSE, converts each message to JSON\n"
      "{\"channel\":..,\"utime\":..,<fields>} and pushes it to every WebSocket client;\n"
      "serves the dashboard page (--root) and /scene.json (the robot outline, sensor\n"
      "positions and room from advee-robot-sim's --robot and --map files) over HTTP on the\n"
      "same port. Open http://HOST:PORT/ in a browser; with --tls-cert and --tls-key\n"
      "the port speaks only HTTPS and WSS (TLS 1.2 or 1.3): open https://HOST:PORT/.\n\n"
      "The bridge integrates LL_DATA_ODO itself (from the robot file's start pose) and\n"
      "sends the estimate as WEB_ODO_POSE {x_m, y_m, heading_rad}. A page that connects\n"
      "gets the newest message of every channel first, then the last 120 s of poses,\n"
      "speeds and temperatures in one WEB_HISTORY frame for its trails and plots.\n\n"
      "A slow client never makes the bridge grow: while its socket holds more than\n"
      "--max-buffered bytes unsent, only the newest message per channel (and module)\n"
      "waits for it; replaced ones are counted as dropped and shown on the page.\n\n"
      "Control (driving, module states, power, homing) needs an operator logged in\n"
      "with a password from --operators (set one with `advee-web passwd NAME`) and\n"
      "the control lease; docs/web-dashboard.md describes the security model.\n\n"
      "Signals: SIGINT, SIGTERM close every connection and exit 0.\n"
      "Exit codes: 0 stopped by a signal, 1 LCM, the listening socket or TLS could not be\n"
      "set up (a certificate or key missing, unreadable, not PEM, encrypted, or the key\n"
      "not the certificate's) or LCM failed while running, 2 bad command line (also\n"
      "--tls-cert without --tls-key or the reverse).",
      "advee-web"};
  std::string listen = "127.0.0.1:8080";
  std::string root = ADVEE_WEB_DATADIR;
  std::string lcm_url;
  std::string robot_file = std::string(ADVEE_ROBOTSIM_SYSCONFDIR) + "/robot.yaml";
  std::string map_file = std::string(ADVEE_ROBOTSIM_SYSCONFDIR) + "/room.yaml";
  std::size_t max_buffered = 256 * 1024;
  std::string operators = ADVEE_WEB_OPERATORS;
  std::string view = "open";
  std::vector<std::string> allow_origins;
  double max_speed = 0.5, max_steering_deg = 30;
  bool secure_cookie = false;
  std::string tls_cert, tls_key;
  app.add_flag("--secure-cookie", secure_cookie, "the page is reached over https (a TLS proxy in front): "
                                                 "the session cookie gets Secure (implied by --tls-cert)");
  auto* cert_opt = app.add_option("--tls-cert", tls_cert, "PEM certificate (chain, the server's first): serve "
                                                          "HTTPS and WSS instead of HTTP and WS; the session "
                                                          "cookie gets Secure, only the https Origin is the page's");
  auto* key_opt = app.add_option("--tls-key", tls_key, "the certificate's PEM private key, unencrypted "
                                                       "(mode 0640 root:advee); both read once at start");
  cert_opt->type_name("FILE")->needs(key_opt);
  key_opt->type_name("FILE")->needs(cert_opt);
  app.add_option("--operators", operators, "the operators' password file (NAME:crypto_pwhash "
                                           "hash, mode 0640 root:advee; advee-web passwd sets it)")
      ->capture_default_str();
  app.add_option("--view", view, "open: anyone reaching the port sees the live data; login: only "
                                 "logged-in operators")
      ->capture_default_str()
      ->check(CLI::IsMember({"open", "login"}));
  app.add_option("--allow-origin", allow_origins, "a further Origin the page may be served from "
                                                   "(e.g. https://robot.example behind a proxy)");
  app.add_option("--max-speed", max_speed, "the fastest the page may drive, m/s")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 1.5));
  app.add_option("--max-steering-deg", max_steering_deg, "the largest steering angle the page may ask, degrees")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 30.0));
  auto* pw_cmd = app.add_subcommand("passwd", "set an operator's password in --operators (read "
                                              "from the terminal twice, or one line of stdin) and exit");
  std::string pw_name;
  bool pw_delete = false, pw_random = false;
  pw_cmd->add_option("name", pw_name, "operator name: 1-32 of A-Z a-z 0-9 _ . -")->required();
  pw_cmd->add_flag("--delete", pw_delete, "remove the operator instead");
  pw_cmd->add_flag("--random", pw_random, "generate a random password and print it on stdout");
  app.add_option("--listen", listen, "HOST:PORT for HTTP(S) and WebSocket; 0.0.0.0:PORT for every "
                                     "interface (a VM's port forwarding needs that); PORT 0 picks a free "
                                     "port and prints it")
      ->capture_default_str();
  app.add_option("--root", root, "directory of the page (index.html, dashboard.js, dashboard.css)")
      ->capture_default_str();
  app.add_option("--lcm", lcm_url, "LCM URL (default: LCM_DEFAULT_URL, else /etc/advee/lcm.conf, "
                                   "else LCM's default group)");
  app.add_option("--robot", robot_file, "advee-robot-sim robot file: outline, range finder and beacon "
                                        "scanner positions; \"\" = none")
      ->capture_default_str();
  app.add_option("--map", map_file, "advee-robot-sim map file: walls, obstacles, beacons; \"\" = none")
      ->capture_default_str();
  app.add_option("--max-buffered", max_buffered, "bytes unsent on one client's socket beyond which "
                                                 "its messages are coalesced")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{1024}, std::size_t{64} << 20));
  ADVEE_CLI_PARSE(app, argc, argv);
  if (*pw_cmd) return passwd(operators, pw_name, pw_delete, pw_random);

  advee::web::BridgeOptions opt;
  if (!split_listen(listen, opt.address, opt.port))
    return advee::cli::usage_error(app, "--listen " + listen + ": expected HOST:PORT");
  opt.root = root;
  // A root without the page would serve nothing but 404s.
  if (std::error_code ec; !std::filesystem::is_regular_file(std::filesystem::path(root) / "index.html", ec)) {
    std::cerr << "advee-web: --root " << root << ": no index.html there (the dashboard page)\n";
    return advee::cli::kExitFailure;
  }
  opt.max_buffered_bytes = max_buffered;
  opt.password_file = operators;
  opt.view_requires_login = view == "login";
  opt.allowed_origins = allow_origins;
  opt.secure_cookie = secure_cookie;  // the server adds it by itself with TLS
  opt.tls_cert = tls_cert;
  opt.tls_key = tls_key;
  opt.drive_limits = {max_speed, max_steering_deg * 3.14159265358979323846 / 180};
  const auto scene = advee::web::load_scene(robot_file, map_file);
  if (scene.contains("errors"))
    for (const auto& e : scene["errors"]) log_line("scene: " + e.get<std::string>());
  opt.scene_json = scene.dump();
  // Odometry starts where advee-robot-sim starts the robot (the robot file), or at 0.
  advee::web::Pose2 odo_start;
  if (scene.contains("robot")) {
    const auto& s = scene["robot"]["start"];
    odo_start = {s["x"].get<double>(), s["y"].get<double>(), s["heading_rad"].get<double>()};
  }

  asio::io_context io;
  std::optional<advee::web::ControlPublisher> publisher;  // outlives the server, which may stop the robot
  std::optional<advee::web::BridgeServer> server;
  std::optional<advee::web::LcmSource> source;
  try {
    publisher.emplace(lcm_url, log_line);
    server.emplace(io, opt, log_line,
                   [&publisher](const advee::web::ControlRequest& r, const advee::web::Operator& who, bool audit) {
                     (*publisher)(r, who, audit);
                   });
    // Messages are decoded on the LCM thread and sent on the io thread.
    auto forward = [&io, &server](const nlohmann::json& m) {
      const std::string channel = m.value("channel", "");
      asio::post(io, [&server, k = advee::web::replace_key(m), p = m.dump(),
                      keep = advee::web::kept_in_history(channel)] {
        if (server) server->broadcast(k, p, keep);
      });
    };
    // The odometry estimate lives here, on the LCM thread, for every page alike.
    source.emplace(lcm_url, advee::web::bridged_channels(),
                   [forward, odo = advee::web::OdometryIntegrator(odo_start)](const nlohmann::json& m) mutable {
                     forward(m);
                     if (m.value("channel", "") != "LL_DATA_ODO") return;
                     odo.add(m.value("speed_mps", 0.0), m.value("yaw_rate_radps", 0.0), m.value("interval_s", 0.0));
                     forward(odo.to_json(m.value("utime", 0LL)));
                   });
  } catch (const std::exception& e) {
    log_line(e.what());
    return 1;
  }
  log_line("serving " + root + " on " + (tls_cert.empty() ? "http" : "https") + "://" + opt.address + ":" +
           std::to_string(server->port()) + "/");

  int status = 0;
  asio::steady_timer grace(io), health(io);
  auto stop = [&] {
    source.reset();  // joins the LCM thread: no more posts
    server->shutdown();
    // Closing handshakes get one second; then the loop ends regardless.
    grace.expires_after(std::chrono::seconds(1));
    grace.async_wait([&io](const std::error_code&) { io.stop(); });
    health.cancel();
  };
  asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const std::error_code& ec, int sig) {
    if (ec) return;
    log_line(std::string("signal ") + (sig == SIGINT ? "SIGINT" : "SIGTERM") + ": stopping");
    stop();
  });
  std::function<void()> watch_lcm = [&] {
    health.expires_after(std::chrono::milliseconds(500));
    health.async_wait([&](const std::error_code& ec) {
      if (ec || !source) return;
      if (source->failed()) {
        log_line("LCM receive failed");
        status = 1;
        signals.cancel();
        stop();
        return;
      }
      watch_lcm();
    });
  };
  watch_lcm();
  io.run();
  const auto st = server->stats();
  log_line("stopped: " + std::to_string(st.messages) + " messages, " + std::to_string(st.dropped) +
      " dropped for slow clients");
  return status;
}
