#pragma once
// The fixture of the skyrender command-line tests: runs the binary as a user would, in a
// private folder, and captures its exit code and both output streams. The binary inherits
// SKY_VALIDATION=1 from ctest; any validation message on its stderr fails the test.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/files.h"

namespace sky {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

struct CliRun {
  int rc;
  std::string out, err;
};

class SkyrenderCli : public ::testing::Test {
protected:
  void SetUp() override {
    mDir = fs::temp_directory_path() /
           ("skyrender-cli-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(mDir);
    fs::create_directories(mDir / "out");
  }
  void TearDown() override { fs::remove_all(mDir); }

  // `env` is prepended to the command line ("NAME=value ..."), for tests that change the
  // environment of skyrender alone.
  CliRun run(const std::string& args, const std::string& env = "") {
    const char* exe = std::getenv("SKY_SKYRENDER");
    EXPECT_NE(exe, nullptr) << "tests/support sets SKY_SKYRENDER";
    std::string cmd = env + " " + std::string(exe) + " " + args + " >" +
                      (mDir / "stdout").string() + " 2>" + (mDir / "stderr").string();
    int status = std::system(cmd.c_str());
    CliRun r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, readTextFile(mDir / "stdout"),
             readTextFile(mDir / "stderr")};
    EXPECT_THAT(r.err, Not(HasSubstr("validation"))) << "Vulkan validation messages on stderr";
    return r;
  }
  fs::path write(const std::string& name, const std::string& text) {
    fs::path p = mDir / name;
    std::ofstream(p) << text;
    return p;
  }
  std::string out() const { return (mDir / "out").string(); }
  bool outEmpty() const { return fs::is_empty(mDir / "out"); }

  // Runs a render that must fail with exit code 2, one error line containing every fragment,
  // and no file in the output folder.
  void expectBadInput(const std::string& args, std::vector<std::string> fragments) {
    CliRun r = run("render " + args + " --out " + out());
    EXPECT_EQ(r.rc, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_THAT(r.err, HasSubstr("error: "));
    for (const std::string& f : fragments) EXPECT_THAT(r.err, HasSubstr(f));
    EXPECT_TRUE(outEmpty()) << "a failed render left files behind";
  }

  fs::path mDir;
};

}  // namespace sky
