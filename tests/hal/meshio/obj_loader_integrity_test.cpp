// The strict OBJ reader and the atomic writer against bad input (issue 11, item 8):
// every malformed number and index is a clear error naming the line (also with
// leading blanks and beyond 32 bits), polygons are triangulated or refused, never
// dropped, a file is read in bounded memory, and writers never replace anything but
// a regular file. Generators refuse non-finite sizes.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "twister/meshio/mesh_generator.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister::meshio {
namespace {

namespace fs = std::filesystem;
constexpr const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

// The error message of parsing `text`, or "" when it loads.
std::string error_of(const std::string& text) {
  const auto r = parse_obj(text);
  if (r) return "";
  EXPECT_EQ(r.error().status.code(), StatusCode::invalid_argument);
  return r.error().message;
}

#define EXPECT_REFUSED(text, words)                                                          \
  do {                                                                                       \
    const std::string m = error_of(text);                                                    \
    EXPECT_NE(m.find(words), std::string::npos) << "text: " << (text) << "\nmessage: " << m; \
  } while (0)

TEST(ObjLoaderIntegrity, LeadingBlanksDoNotHideBadNumbers) {
  EXPECT_REFUSED("  v nan nan nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "line 1: v value 'nan'");
  EXPECT_REFUSED("\tv 1 inf 0\n", "line 1");
  const auto ok = parse_obj("  v 1 2 3\n\t v 4 5 6\n v 7 8 9\n  f 1 2 3\n");
  ASSERT_TRUE(ok) << ok.error().message;
  EXPECT_EQ(ok->buffer->mesh().position(1), glm::vec3(4, 5, 6));
  EXPECT_EQ(ok->buffer->mesh().triangle_count(), 1u);
}

TEST(ObjLoaderIntegrity, EveryMalformedNumberIsRefused) {
  for (const char* bad : {"nan", "-inf", "infinity", "1e39", "-1e400", "1.0.0", "1x", "0x1p3",
                          "--1", "+-1", "1,5", "+", ".", "e5"}) {
    std::string text = "v 0 0 ";
    text += bad;
    text += '\n';
    EXPECT_REFUSED(text, "is not a finite number");
  }
  EXPECT_REFUSED("v 1 2\n", "a vertex needs x y z");
  EXPECT_REFUSED("v 1 2 3 4 5\n", "a vertex needs x y z");
  EXPECT_REFUSED("v 1 2 3 4 5 6 7 8\n", "a vertex needs x y z");
  EXPECT_REFUSED("v 1 2 3\nvn 0 0 nan\n", "line 2: vn value 'nan'");
  EXPECT_REFUSED("v 1 2 3\nvt\n", "line 2: vt needs 1 to 3 numbers");
  // Accepted forms: w, colours, '+', exponents, subnormals.
  EXPECT_TRUE(parse_obj("v +1 -2e-3 3E2\nv 1 2 3 1\nv 1 2 3 0.5 0.5 0.5\nv 1e-40 0 0\n"));
}

TEST(ObjLoaderIntegrity, EveryMalformedIndexIsRefused) {
  const std::string v = kTriangle;
  EXPECT_REFUSED(v + "f 1 2 4294967297\n", "line 4: vertex index 4294967297 is beyond 32 bits");
  EXPECT_REFUSED(v + "f 1 2 -4294967297\n", "beyond 32 bits");
  EXPECT_REFUSED(v + "f 1 2 99999999999999999999999\n", "beyond 32 bits");
  EXPECT_REFUSED(v + "f 1 2 0\n", "is 0 (indices start at 1)");
  EXPECT_REFUSED(v + "f 1 2 3x\n", "is not a whole number");
  EXPECT_REFUSED(v + "f 1 2 +3\n", "is not a whole number");
  EXPECT_REFUSED(v + "f 1 2 3.0\n", "is not a whole number");
  EXPECT_REFUSED(v + "f 1 2 4\n", "does not exist");
  EXPECT_REFUSED(v + "f 1 2 -4\n", "does not exist");
  EXPECT_REFUSED(v + "f 1 2\n", "a face needs at least 3 vertices");
  EXPECT_REFUSED(v + "f 1/ 2 3\n", "is incomplete");
  EXPECT_REFUSED(v + "f 1/1/ 2 3\n", "is incomplete");
  EXPECT_REFUSED(v + "f 1/1 2/1 3/1\n", "texture index 1 refers to a texture that does not exist");
  EXPECT_REFUSED(v + "vn 0 0 1\nf 1//2 2//1 3//1\n", "normal index 2");
  // Accepted: every reference form, relative indices, a face naming later vertices.
  const auto ok = parse_obj("f 1 2 3\n" + v + "vt 0 0\nvn 0 0 1\nf 1/1 2/1/1 3//1\nf -3 -2 -1\n");
  ASSERT_TRUE(ok) << ok.error().message;
  EXPECT_EQ(ok->buffer->mesh().triangle_count(), 3u);
}

TEST(ObjLoaderIntegrity, PolygonsAreTriangulatedOrClearlyRefused) {
  std::string ring;
  for (int i = 0; i < 36; ++i) {
    const double a = 2.0 * 3.14159265358979 * i / 36.0;
    ring += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
  }
  std::string face = "f";
  for (int i = 1; i <= 36; ++i) {
    face += ' ';
    face += std::to_string(i);
  }
  const auto fan = parse_obj(ring + face + "\n");
  ASSERT_TRUE(fan) << fan.error().message;
  EXPECT_EQ(fan->buffer->mesh().triangle_count(), 34u);  // never silently 0
  EXPECT_EQ(fan->polygons, 1u);
  // An arrowhead (reflex corner) and a degenerate (collinear) polygon are refused.
  EXPECT_REFUSED("v 0 0 0\nv 2 0 0\nv 1 0.2 0\nv 1 2 0\nf 1 2 3 4\n", "not a convex polygon");
  EXPECT_REFUSED("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3 4\n", "not a convex polygon");
  const auto big = parse_obj(ring + face + "\n", {.max_polygon = 10});
  ASSERT_FALSE(big);
  EXPECT_NE(big.error().message.find("more than 10 vertices"), std::string::npos);
}

TEST(ObjLoaderIntegrity, UnsupportedStatementsAreSkippedAndCounted) {
  const auto r = parse_obj(std::string(kTriangle) + "l 1 2\np 3\nfoo bar\no name\ng\nf 1 2 3\n");
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->skipped_lines, 3u);
  EXPECT_FALSE(parse_obj("# nothing\n"));  // no vertices
  EXPECT_FALSE(parse_obj(std::string(kTriangle), {.max_vertices = 2}));
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class ObjFiles : public ::testing::Test {
 protected:
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_ = fs::temp_directory_path() / ("obj_integrity_" + std::to_string(::getpid()));
};

TEST_F(ObjFiles, AFileIsReadInBoundedLinesAndOnlyWhenRegular) {
  const fs::path longline = dir_ / "long.obj";
  std::ofstream(longline) << kTriangle << "# " << std::string(70000, 'x') << "\nf 1 2 3\n";
  const auto r = load_obj(longline);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("line 4: longer than"), std::string::npos) << r.error().message;
  const fs::path fifo = dir_ / "fifo.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(load_obj(fifo).error().status.code(), StatusCode::io_error);  // never blocks
  EXPECT_EQ(load_obj("/dev/zero").error().status.code(), StatusCode::io_error);
  EXPECT_EQ(load_obj(dir_).error().status.code(), StatusCode::io_error);
  const fs::path crlf = dir_ / "crlf.obj";
  std::ofstream(crlf) << "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3";  // no final newline
  const auto ok = load_obj(crlf);
  ASSERT_TRUE(ok) << ok.error().message;
  EXPECT_EQ(ok->buffer->mesh().triangle_count(), 1u);
}

TEST_F(ObjFiles, WritersReplaceOnlyRegularFiles) {
  MeshBuffer grid(grid_vertices(3), grid_triangles(3));
  ASSERT_TRUE(make_grid(grid.mesh(), 3, 1.0f).ok());
  const fs::path fifo = dir_ / "fifo.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto to_fifo = save_obj(fifo, grid.mesh());
  ASSERT_FALSE(to_fifo);
  EXPECT_NE(to_fifo.error().message.find("is a FIFO; it is not replaced"), std::string::npos);
  EXPECT_TRUE(fs::is_fifo(fifo));
  const fs::path target = dir_ / "target.obj";
  std::ofstream(target) << "precious\n";
  const fs::path link = dir_ / "link.obj";
  fs::create_symlink(target, link);
  EXPECT_FALSE(save_obj(link, grid.mesh()));
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_FALSE(save_obj(dir_, grid.mesh()));
  EXPECT_TRUE(fs::is_directory(dir_));
  // An existing file only with force, and only when it is an OBJ (issue 21); then it
  // is replaced atomically; no temporary file is left behind.
  EXPECT_FALSE(save_obj(target, grid.mesh()));
  EXPECT_FALSE(save_obj(target, grid.mesh(), true));  // "precious": not an OBJ
  EXPECT_EQ(slurp(target), "precious\n");
  std::ofstream(target) << "# an OBJ\nv 0 0 0\n";
  EXPECT_FALSE(save_obj(target, grid.mesh()));
  ASSERT_TRUE(save_obj(target, grid.mesh(), true));
  EXPECT_EQ(load_obj(target)->buffer->mesh().checksum(), grid.mesh().checksum());
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir_)) entries += e.exists() ? 1 : 1;
  EXPECT_EQ(entries, 3u);  // fifo, target, link
}

TEST(ObjLoaderIntegrity, GeneratorsRefuseNonFiniteSizes) {
  MeshBuffer m(100, 200);
  EXPECT_EQ(make_grid(m.mesh(), 3, std::nanf("")), StatusCode::invalid_argument);
  EXPECT_EQ(make_grid(m.mesh(), 3, INFINITY), StatusCode::invalid_argument);
  EXPECT_EQ(make_sphere(m.mesh(), 3, 4, std::nanf("")), StatusCode::invalid_argument);
  EXPECT_EQ(make_sphere(m.mesh(), 3, 4, -INFINITY), StatusCode::invalid_argument);
}

}  // namespace
}  // namespace twister::meshio
