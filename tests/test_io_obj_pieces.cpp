// The OBJ reader's parse in pieces (large files of v, vt, f lines on all
// cores) against the whole-file parse: the same mesh, and errors placed at
// the piece boundaries reported with the same file line. The whole-file
// parse is forced by an unreferenced `vn` line at the end (which the pieces
// leave to it and which adds nothing to the mesh).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "intrinsic/error.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"

namespace intrinsic {
namespace {

// An OBJ of a generated disk, with UVs, in the writer's format, over 8 MB
// (so that the reader cuts it in at least two pieces on two cores).
std::string big_obj() {
  GenerateOptions g;
  g.rings = 190;
  const MeshData d = generate_wavy_patch(g);
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("intrinsic_obj_pieces_" + std::to_string(getpid()) + ".obj");
  write_mesh(path.string(), d.V, d.F, d.V.leftCols(2));
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  std::filesystem::remove(path);
  return bytes.str();
}

MeshData whole_file(const std::string& text, const std::string& name) {
  return read_mesh_from_memory(text + "vn 0 0 1\n", name);
}

void expect_same(const MeshData& a, const MeshData& b) {
  EXPECT_EQ(a.V, b.V);
  EXPECT_EQ(a.F, b.F);
  EXPECT_EQ(a.TC, b.TC);
  EXPECT_EQ(a.FTC, b.FTC);
  EXPECT_EQ(a.face_line, b.face_line);
  EXPECT_EQ(a.had_texcoords, b.had_texcoords);
  EXPECT_EQ(a.path, b.path);
}

// The line starting at byte `at` (1-based number) and its extent.
struct Line {
  int number;
  std::size_t begin, end;  // end: just past its '\n'
};

Line line_at_or_after(const std::string& text, std::size_t at) {
  const std::size_t nl = text.find('\n', at);
  const std::size_t begin = at == 0 ? 0 : nl + 1;
  const int number = 1 + static_cast<int>(std::count(text.begin(), text.begin() + begin, '\n'));
  return {number, begin, text.find('\n', begin) + 1};
}

std::string message_of(const std::string& text, const std::string& name) {
  try {
    read_mesh_from_memory(text, name);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(ObjPieces, SameMeshAsTheWholeFileParse) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core: the file is never cut";
  const std::string text = big_obj();
  ASSERT_GT(text.size(), 8u << 20);
  const MeshData pieces = read_mesh_from_memory(text, "big.obj");
  expect_same(pieces, whole_file(text, "big.obj"));
  // And against the generated mesh itself (shortest round-trip numbers).
  GenerateOptions g;
  g.rings = 190;
  const MeshData d = generate_wavy_patch(g);
  EXPECT_EQ(pieces.V, d.V);
  EXPECT_EQ(pieces.F, d.F);
  EXPECT_EQ(pieces.FTC, d.F);
  EXPECT_EQ(pieces.face_line.back(), static_cast<int>(std::count(text.begin(), text.end(), '\n')));
}

TEST(ObjPieces, CommentsCrlfAndFacesWithoutUvs) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core: the file is never cut";
  std::string text = big_obj();
  // CRLF everywhere, a comment every 1000 lines, the last face without UVs.
  std::string crlf;
  crlf.reserve(text.size() * 2);
  int lines = 0;
  for (char c : text) {
    if (c == '\n') {
      crlf += "\r\n";
      if (++lines % 1000 == 0) crlf += "# a comment\r\n";
    } else {
      crlf += c;
    }
  }
  crlf += "f 1 2 3\r\n";
  const MeshData pieces = read_mesh_from_memory(crlf, "crlf.obj");
  expect_same(pieces, whole_file(crlf, "crlf.obj"));
  EXPECT_EQ(pieces.TC.rows(), 0);  // one face without UVs drops them all
  EXPECT_TRUE(pieces.had_texcoords);
}

// An error on the first line of each piece and on the last line before it,
// for every way of cutting the file in 2 to 4 pieces: the message names the
// same line as the whole-file parse, counted here independently.
TEST(ObjPieces, ErrorsAtPieceBoundariesNameTheirLine) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core: the file is never cut";
  const std::string text = big_obj();
  for (int parts = 2; parts <= 4; ++parts)
    for (int k = 1; k < parts; ++k) {
      const Line first = line_at_or_after(text, text.size() / parts * k);
      const Line before = line_at_or_after(text, text.rfind('\n', first.begin - 2) + 1);
      for (const Line& bad : {first, before}) {
        // Same length, so the pieces are cut at the same places.
        std::string broken = text;
        const std::string face = "f 0";
        broken.replace(bad.begin, bad.end - bad.begin - 1, face + std::string(bad.end - bad.begin - 1 - face.size(), ' '));
        const std::string expected =
            "bad.obj:" + std::to_string(bad.number) + ": face vertex index 0 is invalid (OBJ indices start at 1)";
        EXPECT_EQ(message_of(broken, "bad.obj"), expected) << parts << " pieces, boundary " << k;
      }
    }
}

TEST(ObjPieces, IndicesCountingBackAndOutOfRange) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core: the file is never cut";
  const std::string text = big_obj();
  // Negative indices count back from what is defined so far: whole-file only.
  const std::string relative = text + "f -1/-1 -2/-2 -3/-3\n";
  const MeshData m = read_mesh_from_memory(relative, "rel.obj");
  expect_same(m, whole_file(relative, "rel.obj"));
  const Eigen::Index n = m.V.rows();
  EXPECT_EQ(m.F.row(m.F.rows() - 1), Eigen::RowVector3i(int(n) - 1, int(n) - 2, int(n) - 3));
  // A forward index past the end: the whole-file parse's message and line.
  const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  const std::string beyond = text + "f 1/1 2/2 " + std::to_string(n + 5) + "/3\n";
  EXPECT_EQ(message_of(beyond, "far.obj"), "far.obj:" + std::to_string(lines + 1) + ": face index " +
                                                std::to_string(n + 5) + " out of range (file has " +
                                                std::to_string(n) + " vertices)");
}

}  // namespace
}  // namespace intrinsic
