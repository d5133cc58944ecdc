// check_input_file / read_input_file: what a mesh reader refuses before reading.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include "core/mesh/file_check.h"
#include "core/mesh/mesh_io.h"
#include "mesh_test_util.h"
#include "tests/error_field.h"

namespace trispline::core {
namespace {

using test::TempDir;
using test::write_text;

std::string check_error(const std::filesystem::path& p, std::uintmax_t max_bytes) {
  return trispline::test::message_of<MeshIoError>([&] { check_input_file(p, max_bytes, "mesh files"); });
}

std::string read_error(const std::filesystem::path& p, std::uintmax_t max_bytes) {
  return trispline::test::message_of<MeshIoError>([&] { read_input_file(p, max_bytes, "mesh files"); });
}

TEST(FileCheck, RegularFileWithinBudgetPasses) {
  TempDir dir;
  write_text(dir / "a.obj", "v 0 0 0\n");
  EXPECT_NO_THROW(check_input_file(dir / "a.obj", 8, "mesh files"));
  EXPECT_EQ(read_input_file(dir / "a.obj", 8, "mesh files").size(), 8u);
}

TEST(FileCheck, SaysWhatThePathIs) {
  TempDir dir;
  const std::string missing = (dir / "nope.obj").string();
  EXPECT_EQ(check_error(dir / "nope.obj", 100), "'" + missing + "': file not found");
  EXPECT_EQ(read_error(dir / "nope.obj", 100), "'" + missing + "': file not found");
  EXPECT_EQ(check_error(dir.path(), 100), "'" + dir.path().string() + "': is a directory");
  EXPECT_EQ(read_error(dir.path(), 100), "'" + dir.path().string() + "': is a directory");
  EXPECT_EQ(check_error("/dev/zero", 100), "'/dev/zero': is a character device, not a regular file");
  EXPECT_EQ(read_error("/dev/zero", 100), "'/dev/zero': is a character device, not a regular file");
  // Symlinks are followed: a link to /dev/zero is a character device.
  std::filesystem::create_symlink("/dev/zero", dir / "zero.glb");
  EXPECT_NE(read_error(dir / "zero.glb", 100).find("zero.glb': is a character device"), std::string::npos);
  // A FIFO without a writer: refused at once (opening it must not block).
  ASSERT_EQ(::mkfifo((dir / "pipe.obj").c_str(), 0600), 0);
  EXPECT_NE(check_error(dir / "pipe.obj", 100).find("pipe.obj': is a FIFO"), std::string::npos);
  EXPECT_NE(read_error(dir / "pipe.obj", 100).find("pipe.obj': is a FIFO"), std::string::npos);
}

TEST(FileCheck, RefusesFilesOverTheBudget) {
  TempDir dir;
  write_text(dir / "big.obj", std::string(1536, 'x'));
  const std::string expected =
      "'" + (dir / "big.obj").string() + "': 1.5 KiB (1536 bytes) is over the 1 KiB limit for mesh files";
  EXPECT_EQ(check_error(dir / "big.obj", 1024), expected);
  EXPECT_EQ(read_error(dir / "big.obj", 1024), expected);
  EXPECT_EQ(check_error(dir / "big.obj", 1536), "");
  EXPECT_EQ(read_input_file(dir / "big.obj", 1536, "mesh files").size(), 1536u);
}

TEST(FileCheck, FormatsByteCounts) {
  EXPECT_EQ(format_bytes(0), "0 bytes");
  EXPECT_EQ(format_bytes(1), "1 byte");
  EXPECT_EQ(format_bytes(1023), "1023 bytes");
  EXPECT_EQ(format_bytes(2048), "2 KiB");
  EXPECT_EQ(format_bytes(kMaxMeshFileBytes), "2 GiB");
  EXPECT_EQ(format_bytes(std::uintmax_t(3435973837)), "3.2 GiB");
}

}  // namespace
}  // namespace trispline::core
