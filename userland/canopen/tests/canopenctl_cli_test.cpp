// SPDX-License-Identifier: GPL-2.0
// canopenctl as a process: every usage error is found before the CAN socket
// is opened (the interface here does not exist, so an I/O attempt ends with
// exit 1 and the socket's error: "socket(PF_CAN)" without CAN support,
// "if_nametoindex nosuchcan0" with it; a usage error is exit 2).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace {

bool tried_io(const std::string& out) {
  return out.find("PF_CAN") != std::string::npos || out.find("nosuchcan0") != std::string::npos;
}

struct Outcome {
  int status = -1;
  std::string out;  // stdout and stderr
};

Outcome canopenctl(const std::string& args) {
  Outcome r;
  const std::string cmd = std::string(CANOPENCTL) + " " + args + " 2>&1";
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) r.out += buf;
  const int w = ::pclose(p);
  r.status = WIFEXITED(w) ? WEXITSTATUS(w) : -1;
  return r;
}

TEST(CanopenctlCliTest, UsageErrorsExit2BeforeAnyIo) {
  for (const char* args : {"-i nosuchcan0 write 1 6081 i8 300", "-i nosuchcan0 write 1 6081 u16 -1",
                           "-i nosuchcan0 -t 10x read 1 1000", "-i nosuchcan0 -t 0 read 1 1000",
                           "-i nosuchcan0 read 1 1000 u33", "-i nosuchcan0 read 128 1000",
                           "-i nosuchcan0 read 1 1000:300", "-i nosuchcan0 nmt jump all",
                           "-i nosuchcan0 monitor 1x", "-i nosuchcan0 bogus", "-i nosuchcan0 pdo",
                           "-i nosuchcan0", "-i nosuchcan0 block read 1", "-i nosuchcan0 block",
                           "-i nosuchcan0 block write 1 2000 i8 300", "-i nosuchcan0 block -b 128 read 1 2000",
                           "-i nosuchcan0 block -b 0 read 1 2000", "-i nosuchcan0 scan 0-5",
                           "-i nosuchcan0 scan 9-3", "-i nosuchcan0 scan 1-128", "-i nosuchcan0 hb 0",
                           "-i nosuchcan0 hb x", "-i nosuchcan0 pdo remap 1 xpdo 1",
                           "-i nosuchcan0 pdo remap 1 tpdo 5", "-i nosuchcan0 pdo remap 1 tpdo 1 6041:0/65",
                           "-i nosuchcan0 pdo remap 1 tpdo 1 --type 256", "-i nosuchcan0 pdo remap 1",
                           "-i nosuchcan0 lss", "-i nosuchcan0 lss scan --assign 0", "-i nosuchcan0 lss scan --store",
                           "-i nosuchcan0 lss set-id", "-i nosuchcan0 lss set-id 128",
                           "-i nosuchcan0 lss set-id 5 --identity 1:2:3", "-i nosuchcan0 lss --answer-ms 0 identify",
                           "-i nosuchcan0 lss --settle-ms 100 identify", "-i nosuchcan0 lss bogus"}) {
    const Outcome r = canopenctl(args);
    EXPECT_EQ(r.status, 2) << "canopenctl " << args << ":\n" << r.out;
    EXPECT_FALSE(tried_io(r.out)) << "canopenctl " << args << " opened the socket:\n" << r.out;
  }
}

TEST(CanopenctlCliTest, ValidArgumentsReachTheSocket) {
  for (const char* args : {"-i nosuchcan0 -t 200 write 1 6081 i8 -128", "-i nosuchcan0 block -b 127 read 1 2000 str",
                           "-i nosuchcan0 block write 1 2000 hex 00ff", "-i nosuchcan0 scan 1-3",
                           "-i nosuchcan0 hb 1", "-i nosuchcan0 pdo remap 1 tpdo 4 6041:0/16 --type 254 --disabled",
                           "-i nosuchcan0 pdo 1", "-i nosuchcan0 lss scan --assign 10 --store",
                           "-i nosuchcan0 lss set-id 5 --identity FB:64200000:10000:1", "-i nosuchcan0 lss identify"}) {
    const Outcome r = canopenctl(args);
    EXPECT_EQ(r.status, 1) << "canopenctl " << args << ":\n" << r.out;
    EXPECT_TRUE(tried_io(r.out)) << "canopenctl " << args << ":\n" << r.out;
  }
}

TEST(CanopenctlCliTest, HelpExits0) {
  const Outcome r = canopenctl("--help");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("monitor"), std::string::npos) << r.out;
}

}  // namespace
