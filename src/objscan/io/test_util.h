#pragma once
// Helpers for the io tests: a fresh temporary folder per test and small file writers.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "objscan/common/error.h"
#include "objscan/geometry/aabb.h"
#include "objscan/world/scene.h"

namespace objscan::io::testing {

// A temporary folder removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("objscan_io_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
             std::to_string(static_cast<long>(::getpid())));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string File(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Sets an environment variable (nullopt: unsets it) for the scope of a test and puts the old value back.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::optional<std::string>& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    value ? ::setenv(name, value->c_str(), 1) : ::unsetenv(name);
  }
  ~ScopedEnv() { old_ ? ::setenv(name_, old_->c_str(), 1) : ::unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

inline void WriteText(const std::string& path, const std::string& text) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// Runs `fn`, expects an InputError whose message contains `needle`.
template <class Fn>
void ExpectInputError(Fn&& fn, const std::string& needle) {
  try {
    fn();
    ADD_FAILURE() << "expected InputError mentioning '" << needle << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "message: " << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "message is not one line: " << e.what();
  }
}

// The scene object of this name, or null.
inline const world::SceneObject* ByName(const world::Scene& scene, const std::string& name) {
  for (const auto& o : scene.objects()) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

// Expects the box's corners within `tol` of the given ones.
inline void ExpectBox(const geometry::Aabb3& b, const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m,
                      double tol = 1e-4) {
  EXPECT_LT((b.min_m - min_m).norm(), tol) << "min " << b.min_m.transpose() << " expected " << min_m.transpose();
  EXPECT_LT((b.max_m - max_m).norm(), tol) << "max " << b.max_m.transpose() << " expected " << max_m.transpose();
}

}  // namespace objscan::io::testing
