// Outputs as one transaction (io/output_set.hpp, io/atomic_file.hpp): the
// targets change together on commit and not at all otherwise; no temporary
// is left behind; the checks before work refuse what cannot be replaced.
#include "test_support.hpp"

#include <metrica/error.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/output_set.hpp>

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sys/stat.h>

using namespace metrica;
namespace fs = std::filesystem;

namespace {

std::string text_of(const std::string& path) { return io::read_file_bytes(path); }

std::size_t entries(const fs::path& folder) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(folder)) ++n;
  return n;
}

}  // namespace

TEST_SUITE("unit") {
  TEST_CASE("an output set renames every staged file on commit - none when dropped") {
    test::TempDir dir;
    std::ofstream(dir / "a.txt") << "old a";
    {
      io::OutputSet set;
      io::write_file_atomically(dir / "a.txt", "new a");
      io::write_file_atomically(dir / "b.txt", "new b");
      CHECK(set.staged() == 2);
      CHECK(text_of(dir / "a.txt") == "old a");  // nothing replaced before the commit
      CHECK_FALSE(fs::exists(dir / "b.txt"));
      // Dropped: as if the run failed after writing.
    }
    CHECK(text_of(dir / "a.txt") == "old a");
    CHECK_FALSE(fs::exists(dir / "b.txt"));
    CHECK(entries(dir.path()) == 1);  // no temporary left
    {
      io::OutputSet set;
      io::write_file_atomically(dir / "a.txt", "first");
      io::write_file_atomically(dir / "a.txt", "second");  // a later write to a target wins
      io::write_file_atomically(dir / "b.txt", "new b");
      CHECK(set.staged() == 2);
      set.commit();
    }
    CHECK(text_of(dir / "a.txt") == "second");
    CHECK(text_of(dir / "b.txt") == "new b");
    CHECK(entries(dir.path()) == 2);
  }

  TEST_CASE("without an output set a file is replaced at once - its mode kept - a new one takes the umask") {
    test::TempDir dir;
    std::ofstream(dir / "a.txt") << "old";
    ::chmod((dir / "a.txt").c_str(), 0600);
    io::write_file_atomically(dir / "a.txt", "new");
    CHECK(text_of(dir / "a.txt") == "new");
    struct stat st {};
    REQUIRE(::stat((dir / "a.txt").c_str(), &st) == 0);
    CHECK((st.st_mode & 0777) == 0600);
    const mode_t mask = ::umask(0);
    ::umask(mask);
    io::write_file_atomically(dir / "n.txt", "new");
    REQUIRE(::stat((dir / "n.txt").c_str(), &st) == 0);
    CHECK((st.st_mode & 0777) == (0666 & ~mask));
  }

  TEST_CASE("writable_target follows symlinks and refuses what cannot be replaced") {
    test::TempDir dir;
    std::ofstream(dir / "real.txt") << "x";
    fs::create_symlink("real.txt", dir / "link.txt");
    fs::create_symlink("link.txt", dir / "link2.txt");
    CHECK(io::writable_target(dir / "link2.txt") == (dir / "real.txt"));
    CHECK(io::writable_target(dir / "new.txt") == (dir / "new.txt"));
    fs::create_symlink("loop.txt", dir / "loop.txt");
    CHECK_THROWS_AS(io::writable_target(dir / "loop.txt"), IoError);
    ::chmod((dir / "real.txt").c_str(), 0444);
    CHECK_THROWS_WITH_AS(io::writable_target(dir / "link.txt"), doctest::Contains("read-only"), IoError);
    fs::create_directory(dir / "sub");
    CHECK_THROWS_WITH_AS(io::writable_target(dir / "sub"), doctest::Contains("is a folder"), IoError);
    CHECK_THROWS_WITH_AS(io::writable_target(dir / "none/x.txt"), doctest::Contains("cannot write into folder"),
                         IoError);
    REQUIRE(::mkfifo((dir / "fifo").c_str(), 0644) == 0);
    CHECK_THROWS_WITH_AS(io::writable_target(dir / "fifo"), doctest::Contains("not a regular file"), IoError);
    CHECK_THROWS_AS(io::writable_target(""), IoError);
  }

  TEST_CASE("every writer refuses a non-finite value - nothing is written") {
    test::TempDir dir;
    io::MeshData m;
    m.vertices = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, std::nan(""))};
    m.tets = {{0, 1, 2, 3}};
    m.tet_refs = {0};
    m.vertex_refs = {0, 0, 0, 0};
    for (const char* name : {"m.meshb", "m.mesh", "m.vtu", "m.su2"}) {
      CAPTURE(name);
      CHECK_THROWS_WITH_AS(io::write_mesh_file(dir / name, m), doctest::Contains("vertex 4"), IoError);
    }
    io::SolData s;
    s.count = 2;
    s.types = {io::SolType::scalar};
    s.values = {1.0, std::numeric_limits<double>::infinity()};
    CHECK_THROWS_WITH_AS(io::write_sol(dir / "s.solb", s), doctest::Contains("vertex 2"), IoError);
    CHECK(entries(dir.path()) == 0);
  }
}
