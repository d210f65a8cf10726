#pragma once
// A fresh folder per test, removed afterwards, and small file helpers.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include <gtest/gtest.h>

namespace contour_reg::test {

class TempDir {
 public:
  TempDir() {
    const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device device;
    path_ = std::filesystem::temp_directory_path() /
            ("contour_reg_" + std::string(info ? info->name() : "test") + "_" + std::to_string(device()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code error;
    std::filesystem::remove_all(path_, error);
  }
  TempDir(const TempDir &) = delete;
  TempDir &operator=(const TempDir &) = delete;

  std::string file(const std::string &name) const { return (path_ / name).string(); }
  std::string write(const std::string &name, const std::string &text) const {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }
  const std::filesystem::path &path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// The bytes of the file at `path` ("" when it cannot be read).
inline std::string readBytes(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The folder of the shared datasets, or "" (and the test is skipped by the caller).
inline std::string sharedDataset(const std::string &relative) {
  const std::filesystem::path path = std::filesystem::path(CONTOUR_REG_SHARED_DIR) / "datasets" / relative;
  return std::filesystem::exists(path) ? path.string() : std::string();
}

}  // namespace contour_reg::test
