// libFuzzer target: the readers on arbitrary bytes. The first byte picks
// the reader (modulo 7: 0 .mesh, 1 .meshb, 2 .sol, 3 .solb, 4 .vtu, 5 .su2,
// 6 .msh); a mesh that parses is also built and validated, as every
// command does. Any outcome but a
// result or an InputError (a crash, a sanitizer report, another exception)
// is a finding.
#include <metrica/error.hpp>
#include <metrica/input_checks.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/io/msh.hpp>
#include <metrica/io/su2.hpp>
#include <metrica/io/vtu.hpp>
#include <metrica/log.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/validate.hpp>

#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace metrica;
  if (size < 1) return 0;
  log::set_level(log::Level::quiet);
  const int mode = data[0] % 7;
  const std::string_view bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  const auto enc = (mode & 1) ? io::Encoding::binary : io::Encoding::ascii;
  try {
    if (mode < 2 || mode > 3) {
      const auto m = mode < 2    ? io::parse_mesh(bytes, enc, "fuzz")
                     : mode == 4 ? io::parse_vtu(std::string(bytes), "fuzz")
                     : mode == 5 ? io::parse_su2(std::string(bytes), "fuzz")
                                 : io::parse_msh(bytes, "fuzz");
      check_coordinates(m, "fuzz");
      if (m.tets.size() > 100000) return 0;  // keep each input fast
      const Mesh mesh = build_mesh(m, {.source = "fuzz"});
      static_cast<void>(mesh.validate());
    } else {
      static_cast<void>(io::parse_sol(bytes, enc, "fuzz"));
    }
  } catch (const InputError&) {
  }
  return 0;
}
