// SPDX-License-Identifier: GPL-2.0
// advee-canopenctl lss: the CLI11 description and the run on a master.
#include <CLI/CLI.hpp>

#include <cstdio>

#include "canopenctl_lss.hpp"

namespace advee::canopen::ctl {

void describe_lss(CLI::App& app, LssArgs& a) {
  auto* lss = app.add_subcommand("lss", "CiA 305 layer setting services (node-IDs of nodes by their identity)");
  lss->require_subcommand(1, 1);
  lss->fallthrough();
  lss->add_option("--answer-ms", a.answer_ms, "how long an LSS service waits for an answer")
      ->check(CLI::Range(1, 60000))
      ->capture_default_str();
  lss->add_option("--settle-ms", a.settle_ms, "how long after the first answer others are still collected")
      ->check(CLI::Range(0, 60000))
      ->capture_default_str();
  auto* scan = lss->add_subcommand(
      "scan", "fastscan: print the identity of every node without node-ID; with --assign, give each a node-ID "
              "(FIRST, FIRST+1, ...), with which it boots");
  scan->add_option("--assign", a.assign, "first node-ID to give (1..127)")->type_name("FIRST");
  scan->add_flag("--store", a.store, "have each node store its new node-ID (with --assign)");
  scan->add_option("--vendor", a.vendor, "find only nodes with this vendor-ID (0x1018:1, hex); faster")->type_name("HEX");
  scan->add_option("--product", a.product, "find only nodes with this product code (0x1018:2, hex); faster")
      ->type_name("HEX");
  auto* set_id = lss->add_subcommand(
      "set-id", "configure the node-ID of the node with this identity (--identity), or of the only node on the "
                "bus; a node that had a node-ID takes the new one at its next NMT reset communication");
  set_id->add_option("node", a.node, "new node-ID (1..127)")->required();
  set_id->add_option("--identity", a.identity, "the node's 0x1018:1..4, in hex")
      ->type_name("VENDOR:PRODUCT:REVISION:SERIAL");
  set_id->add_flag("--store", a.store, "have the node store its new node-ID");
  lss->add_subcommand("identify", "count the nodes without node-ID (identify non-configured slaves)");
}

namespace {

// set-id, one service after the other; any failure switches every node
// back to waiting state before it is reported.
struct SetId : std::enable_shared_from_this<SetId> {
  LssMaster& lss;
  LssCommand c;
  std::function<void(int)> end;
  std::uint8_t old_id = kLssUnconfigured;

  SetId(LssMaster& l, LssCommand cmd, std::function<void(int)> e) : lss(l), c(std::move(cmd)), end(std::move(e)) {}

  void fail(const std::string& what, const LssResult& r) {
    std::fprintf(stderr, "advee-canopenctl: lss set-id: %s: %s\n", what.c_str(), describe(r).c_str());
    lss.switch_global(LssMode::kWaiting, [self = shared_from_this()](const LssResult&) { self->end(1); });
  }
  void start() {
    auto self = shared_from_this();
    if (c.identity) {
      lss.switch_selective(*c.identity, [self](const LssResult& r) {
        if (!r.ok()) return self->fail("no node with identity " + to_string(*self->c.identity), r);
        self->inquire();
      });
    } else {
      // Without an identity every node enters configuration state; the
      // inquiry tells whether there is exactly one.
      lss.switch_global(LssMode::kConfiguration, [self](const LssResult&) { self->inquire(); });
    }
  }
  void inquire() {
    lss.inquire(LssInquiry::kNodeId, [self = shared_from_this()](const LssResult& r) {
      if (r.error == LssError::kMultipleAnswers)
        return self->fail("more than one node answered; name one with --identity", r);
      if (!r.ok()) return self->fail("inquire node-ID", r);
      self->old_id = static_cast<std::uint8_t>(r.value);
      self->configure();
    });
  }
  void configure() {
    lss.configure_node_id(c.node, [self = shared_from_this()](const LssResult& r) {
      if (!r.ok()) return self->fail("configure node-ID", r);
      if (!self->c.store) return self->done();
      self->lss.store([self](const LssResult& sr) {
        if (!sr.ok()) return self->fail("store", sr);
        self->done();
      });
    });
  }
  void done() {
    lss.switch_global(LssMode::kWaiting, [self = shared_from_this()](const LssResult&) {
      if (self->old_id == kLssUnconfigured)
        std::printf("node-ID %u configured%s; the node boots with it\n", self->c.node,
                    self->c.store ? " and stored" : "");
      else
        std::printf("node-ID %u configured%s (the node has %u until its next NMT reset communication)\n",
                    self->c.node, self->c.store ? " and stored" : "", self->old_id);
      self->end(0);
    });
  }
};

}  // namespace

std::unique_ptr<LssMaster> run_lss(Master& master, const LssCommand& c, std::function<void(int)> end) {
  auto lss = std::make_unique<LssMaster>(master, c.config);
  if (c.name == "lss scan") {
    lss_scan(*lss, c.assign, c.store, [end](const std::vector<LssFound>& found, const LssResult& r) {
      for (const auto& f : found) std::printf("%s\n", describe_found(f).c_str());
      if (!r.ok()) {
        std::fprintf(stderr, "advee-canopenctl: lss scan: %s\n", describe(r).c_str());
        return end(1);
      }
      if (found.empty()) {
        std::fprintf(stderr, "advee-canopenctl: lss scan: no node without node-ID answered\n");
        return end(1);
      }
      end(0);
    }, c.known);
  } else if (c.name == "lss set-id") {
    std::make_shared<SetId>(*lss, c, end)->start();
  } else if (c.name == "lss identify") {
    lss->identify_non_configured([end](const LssResult& r) {
      std::printf("%u node%s without node-ID answered\n", r.answers, r.answers == 1 ? "" : "s");
      end(0);
    });
  }
  return lss;
}

}  // namespace advee::canopen::ctl
