#pragma once
// Helpers shared by the test files: a fresh temporary directory per test, whether this build
// runs under AddressSanitizer (which reserves terabytes of address space, so tests that lower
// RLIMIT_AS cannot run there), and the message of a refused argument.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include <filesystem>
#include <random>
#include <stdexcept>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__)
#define PANELRAD_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PANELRAD_ASAN 1
#endif
#endif

namespace panelrad::testing {

/// n values uniform in [0, 1) from a fixed seed (std::mt19937): a reproducible test vector v >= 0.
inline Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = U(gen);
  return v;
}

/// The message of the std::invalid_argument `f` throws ("" when it does not throw).
template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

/// A refusal's message names every one of `parts` (the data and the rule).
inline void expect_names(const std::string& msg, const std::vector<std::string>& parts) {
  ASSERT_FALSE(msg.empty()) << "not refused";
  for (const std::string& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
}

/// A fixture with a fresh directory per test (temp/PREFIX_PID_TESTNAME), removed afterwards.
class TempDirTest : public ::testing::Test {
 protected:
  explicit TempDirTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (prefix_ + "_" + std::to_string(::getpid()) + "_" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  /// Writes `text` byte for byte to dir/name and returns the path.
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  std::filesystem::path dir_;

 private:
  std::string prefix_;
};

}  // namespace panelrad::testing
