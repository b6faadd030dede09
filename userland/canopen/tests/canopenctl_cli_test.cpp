// SPDX-License-Identifier: GPL-2.0
// advee-canopenctl as a process: every usage error is found before the CAN socket
// is opened (the interface here does not exist, so an I/O attempt ends with
// exit 1 and the socket's error: "socket(PF_CAN)" without CAN support,
// "if_nametoindex nosuchcan0" with it; a usage error is exit 2).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

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
    EXPECT_EQ(r.status, 2) << "advee-canopenctl " << args << ":\n" << r.out;
    EXPECT_FALSE(tried_io(r.out)) << "advee-canopenctl " << args << " opened the socket:\n" << r.out;
  }
}

TEST(CanopenctlCliTest, ValidArgumentsReachTheSocket) {
  for (const char* args : {"-i nosuchcan0 -t 200 write 1 6081 i8 -128", "-i nosuchcan0 block -b 127 read 1 2000 str",
                           "-i nosuchcan0 block write 1 2000 hex 00ff", "-i nosuchcan0 scan 1-3",
                           "-i nosuchcan0 hb 1", "-i nosuchcan0 pdo remap 1 tpdo 4 6041:0/16 --type 254 --disabled",
                           "-i nosuchcan0 pdo 1", "-i nosuchcan0 lss scan --assign 10 --store",
                           "-i nosuchcan0 lss set-id 5 --identity FB:64200000:10000:1", "-i nosuchcan0 lss identify"}) {
    const Outcome r = canopenctl(args);
    EXPECT_EQ(r.status, 1) << "advee-canopenctl " << args << ":\n" << r.out;
    EXPECT_TRUE(tried_io(r.out)) << "advee-canopenctl " << args << ":\n" << r.out;
  }
}

// dcf: the file is read and checked before the socket is opened; an
// unreadable or invalid file is a runtime failure (1), a bad node a usage
// error (2); `dcf concise` needs no bus.
TEST(CanopenctlCliTest, DcfChecksItsFileBeforeAnyIoAndConciseNeedsNoBus) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("canopenctl-dcf-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string eds = std::string(CANOPEN_DATA) + "/epos-70-10.eds";
  const std::string cdcf = (dir / "epos.cdcf").string();
  {
    std::ofstream(dir / "garbled.dcf") << "[MandatoryObjects]\nSupportedObjects=1\n1=0x1000\n[1000]\n"
                                         "ParameterName=Device type\nDataType=0x0007\nAccessType=ro\nDefaultValue=12x\n";
    std::ofstream(dir / "cut.cdcf", std::ios::binary).write("\x02\x00\x00\x00\x17\x10\x00\x02", 8);
  }
  struct Case {
    std::string args;
    int status;
    const char* says;
  };
  const std::vector<Case> cases = {
      {"dcf download 128 " + eds, 2, "128"},
      {"dcf download 1", 2, "file"},
      {"dcf download 1 " + (dir / "missing.dcf").string(), 1, "No such file"},
      {"dcf download 1 " + (dir / "garbled.dcf").string(), 1, "garbled.dcf:8: "},
      {"dcf download 1 " + (dir / "cut.cdcf").string(), 1, "not a valid concise DCF: byte 0: entry count 2"},
      {"dcf download --attempts 0 1 " + eds, 2, "attempts"},
      {"dcf concise 1 " + eds, 2, "out"},
      {"dcf concise 1 " + eds + " " + cdcf, 0, "0 objects, 4 bytes"},
      {"dcf concise 1 " + cdcf + " " + (dir / "again.cdcf").string(), 2, "is a concise DCF already"},
      {"dcf concise 1 " + eds + " " + (dir / "no/such/dir.cdcf").string(), 1, "No such file"},
  };
  for (const Case& c : cases) {
    const Outcome r = canopenctl("-i nosuchcan0 " + c.args);
    EXPECT_EQ(r.status, c.status) << "advee-canopenctl " << c.args << ":\n" << r.out;
    EXPECT_FALSE(tried_io(r.out)) << "advee-canopenctl " << c.args << " opened the socket:\n" << r.out;
    EXPECT_NE(r.out.find(c.says), std::string::npos) << "advee-canopenctl " << c.args << ":\n" << r.out;
  }
  for (const std::string& file : {eds, cdcf}) {
    const Outcome r = canopenctl("-i nosuchcan0 dcf download --no-start 1 " + file);
    EXPECT_EQ(r.status, 1) << r.out;
    EXPECT_TRUE(tried_io(r.out)) << "a valid file reaches the socket: " << file << "\n" << r.out;
  }
  std::filesystem::remove_all(dir);
}

TEST(CanopenctlCliTest, HelpExits0) {
  const Outcome r = canopenctl("--help");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("monitor"), std::string::npos) << r.out;
}

}  // namespace
