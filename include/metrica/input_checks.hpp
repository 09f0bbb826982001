// Checks of an input before any work, shared by every command and usable by
// a library caller: what they refuse would otherwise surface late (an
// invalid adapted mesh after minutes) or as a wrong result (NaN, inf).
#pragma once

#include <metrica/io/mesh_data.hpp>
#include <metrica/mesh.hpp>

#include <string>

namespace metrica {

// Coordinates must be finite and within +-kCoordinateLimit: volumes and
// metric lengths then stay far from double's overflow and underflow.
inline constexpr double kCoordinateLimit = 1e12;
// InputError naming `source`, the first offending vertex (1-based) and
// its coordinates.
void check_coordinates(const io::MeshData& data, const std::string& source);

// InputError unless mesh.validate() passes (orientation, adjacency, surface
// ids on boundary faces, a closed manifold boundary, ...); the message lists
// the first problems and points to `metrica check`.
void check_valid_input(const Mesh& mesh, const std::string& source);

}  // namespace metrica
