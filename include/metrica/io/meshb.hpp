// libMeshb files: meshes (.mesh ASCII, .meshb binary) and solutions
// (.sol ASCII, .solb binary), format versions 1-4, both byte orders on read.
//
// Version 1: 32-bit reals; 2: 64-bit reals; 3: also 64-bit keyword offsets
// (files over 2 GB); 4: also 64-bit integers. Unknown keywords are skipped
// (binary files say where the next keyword starts; in ASCII the reader
// skips to the next keyword name). Every error is an IoError naming the
// file, the keyword and the byte offset (binary) or line (ASCII).
#pragma once

#include <metrica/io/mesh_data.hpp>
#include <metrica/part_runner.hpp>

#include <string>
#include <string_view>

namespace metrica::io {

enum class Encoding { ascii, binary };

// Reads a .mesh or .meshb file (the extension decides the encoding).
MeshData read_meshb(const std::string& path);
// Reads a .sol or .solb file: its SolAtVertices keyword.
SolData read_sol(const std::string& path);

// Parses a file already in memory; `name` is used in error messages.
MeshData parse_mesh(std::string_view bytes, Encoding encoding, const std::string& name);
SolData parse_sol(std::string_view bytes, Encoding encoding, const std::string& name);

// Writes through a temporary file renamed on success. `version` 0 keeps
// data.version; a binary version-2 file that would pass 2 GB is written as
// version 3 (64-bit offsets), which every libMeshb reader accepts. ASCII
// rows are formatted on run's parts (the same bytes for any number).
void write_meshb(const std::string& path, const MeshData& data, int version = 0, const PartRunner& run = {});
void write_sol(const std::string& path, const SolData& data, int version = 0, const PartRunner& run = {});

// Serialises to memory (the writers' core, and handy in tests).
std::string format_mesh(const MeshData& data, Encoding encoding, int version = 0, const PartRunner& run = {});
std::string format_sol(const SolData& data, Encoding encoding, int version = 0, const PartRunner& run = {});

// The encoding a path's extension asks for (`ascii_ext` or `binary_ext`,
// e.g. ".mesh" / ".meshb"); IoError for any other extension.
Encoding encoding_of(const std::string& path, std::string_view ascii_ext, std::string_view binary_ext);

// Reads a whole file into memory; IoError if it is missing or unreadable.
std::string read_file_bytes(const std::string& path);

}  // namespace metrica::io
