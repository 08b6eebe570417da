#pragma once
// The fixture of the skyview tests: a private Xvfb display per test process (started with
// -displayfd, so it takes a free display number itself), skyview run to completion or in the
// background while the test edits files under it, and its output streams. The binary inherits
// SKY_VALIDATION=1 from tests/support; any validation message on its stderr fails the test.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/io/image_metrics.h"
#include "engine/io/png.h"

namespace sky {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

struct ViewRun {
  int rc;
  std::string out, err;
};

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The colour channels of an 8-bit image as values in [0, 1] (alpha left out).
inline std::vector<float> rgbValues(const Image8& image) {
  std::vector<float> v;
  const size_t channels = static_cast<size_t>(image.channels);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    if (channels < 3 || i % channels < 3) v.push_back(image.pixels[i] / 255.0f);
  return v;
}

// One Xvfb for the test process; ctest runs each test in its own process.
class XvfbDisplay {
public:
  static const std::string& display() {
    static XvfbDisplay instance;
    return instance.mDisplay;
  }
  ~XvfbDisplay() {
    if (mPid > 0) {
      kill(mPid, SIGTERM);
      waitpid(mPid, nullptr, 0);
    }
  }

private:
  XvfbDisplay() {
    int fds[2];
    if (pipe(fds) != 0) return;
    mPid = fork();
    if (mPid == 0) {
      close(fds[0]);
      const int devnull = open("/dev/null", O_WRONLY);
      dup2(devnull, 1);
      dup2(devnull, 2);
      const std::string fd = std::to_string(fds[1]);
      execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1024x768x24", "-nolisten",
             "tcp", static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    std::string number;
    char c;
    while (read(fds[0], &c, 1) == 1 && c != '\n') number += c;
    close(fds[0]);
    if (!number.empty()) mDisplay = ":" + number;
  }
  pid_t mPid = -1;
  std::string mDisplay;
};

class SkyviewTest : public ::testing::Test {
protected:
  void SetUp() override {
    mDir = fs::temp_directory_path() /
           ("skyview-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(mDir);
    fs::create_directories(mDir);
    mDisplay = XvfbDisplay::display();
    ASSERT_FALSE(mDisplay.empty()) << "Xvfb did not start (apt-get install xvfb)";
  }
  void TearDown() override {
    if (mPid > 0) {
      kill(mPid, SIGKILL);
      waitpid(mPid, nullptr, 0);
    }
    fs::remove_all(mDir);
  }

  static std::string skyview() {
    const char* exe = std::getenv("SKY_SKYVIEW");
    return exe ? exe : SKY_TEST_SKYVIEW;
  }

  std::string command(const std::string& args, const std::string& env) const {
    // An empty display runs skyview without one.
    const std::string display = mDisplay.empty() ? "-u DISPLAY" : "DISPLAY=" + mDisplay;
    return "exec env " + display + " " + env + " " + skyview() + " " + args + " >" +
           (mDir / "stdout").string() + " 2>" + (mDir / "stderr").string();
  }

  // Runs skyview to the end.
  ViewRun run(const std::string& args, const std::string& env = "") {
    const int status = std::system(command(args, env).c_str());
    ViewRun r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(mDir / "stdout"),
              slurp(mDir / "stderr")};
    EXPECT_THAT(r.err, Not(HasSubstr("alidation"))) << "Vulkan validation messages on stderr";
    return r;
  }

  // Starts skyview in the background; out() follows its stdout.
  void start(const std::string& args, const std::string& env = "") {
    const std::string cmd = command(args, env);
    mPid = fork();
    if (mPid == 0) {
      execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
  }
  std::string out() const { return slurp(mDir / "stdout"); }
  // Waits until stdout holds `text` (after `from` characters); false after `seconds`.
  bool waitFor(const std::string& text, double seconds, size_t from = 0) const {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      const std::string o = out();
      if (o.size() > from && o.find(text, from) != std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }
  // The number of "skyview: frame" lines so far.
  size_t frames() const {
    const std::string o = out();
    size_t n = 0;
    for (size_t p = o.find("skyview: frame "); p != std::string::npos;
         p = o.find("skyview: frame ", p + 1))
      ++n;
    return n;
  }
  // SIGTERM (the window closes as if by its close button), then the exit code and stderr.
  ViewRun stop() {
    kill(mPid, SIGTERM);
    int status = 0;
    waitpid(mPid, &status, 0);
    mPid = -1;
    ViewRun r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, out(), slurp(mDir / "stderr")};
    EXPECT_THAT(r.err, Not(HasSubstr("alidation"))) << "Vulkan validation messages on stderr";
    return r;
  }

  // skyrender, as a user runs it.
  int skyrender(const std::string& args) const {
    const std::string cmd = std::string(std::getenv("SKY_SKYRENDER")) + " " + args + " >" +
                            (mDir / "skyrender.out").string() + " 2>&1";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  fs::path mDir;
  std::string mDisplay;
  pid_t mPid = -1;
};

}  // namespace sky
