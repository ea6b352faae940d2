#pragma once
// Mesh input: OFF and OBJ files. Polygonal faces are fan-triangulated here (validation may
// re-triangulate them exactly, see validation.hpp); vertices are shared: vertices with exactly the
// same coordinates are merged (so a "triangle soup" works) and vertices used by no face are
// dropped, each reported in `notes`. Input face i becomes facet i.
//
// Accepted OFF: optional header keyword OFF / COFF / NOFF / CNOFF / STOFF ... (counts may follow on
// the same line), "#" comments, one vertex per line (x y z, then any extra numbers such as normals
// or colours), one face per line ("k i1 .. ik" then up to four colour numbers). Accepted OBJ: "v x y
// z [w | r g b]", "f" with v, v/vt, v//vn, v/vt/vn and negative (relative) indices, line
// continuation by a trailing backslash; vt, vn, vp, l, o, g, s, usemtl, mtllib are ignored. OBJ
// statements are case-sensitive: a miscased one (`V`, `F`) is an error naming the line, as are
// free-form geometry (curv, surf, ...) and unknown statements.
//
// Files are read by the bounded reader (text_file.hpp): regular files only (no FIFO, device or
// directory), at most TextReadOptions::max_bytes (default 1 GiB), no NUL byte (refused at the first
// with its line and byte offset, after reading at most its 64 KiB chunk). A leading UTF-8
// byte-order mark is removed. Streams (read_off, read_obj) are read the same way up to the limit.
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/geometry/text_file.hpp>

#include <iosfwd>
#include <string>
#include <vector>

namespace panelrad::geometry {

/// Reads an OFF or OBJ file, chosen by extension (case-insensitive). Throws MeshError naming the
/// file, the line and what is wrong: missing/unreadable file, not a regular file, above the size
/// limit, a NUL byte, unknown extension, empty or truncated file, garbage, a face index out of range, a face with fewer than 3 vertices, a
/// non-finite coordinate. Never returns a partial mesh.
/// Notes (merged duplicate vertices, dropped unused vertices) are appended to `notes` when given.
/// What an OBJ file says about materials (for scene files, which give rho and E per material):
/// its `mtllib` statements and, per input face (= facet), the `usemtl` name in force. Geometry
/// ignores them; the reader records them so that faces are counted in one place only.
struct ObjMaterialUse {
  struct Library {
    std::string file;  ///< as written in the OBJ (relative to its folder)
    long line = 0;
  };
  std::vector<Library> libraries;          ///< every `mtllib` file name, in order
  std::vector<std::string> face_material;  ///< per face: the last `usemtl` name before it, "" if none
  std::vector<long> face_line;             ///< per face: its line
  std::vector<long> usemtl_line;           ///< per face: the line of that `usemtl` (0 if none)
};

/// `options`: the reader's size limit (and byte-order mark removal).
TriangleMesh read_mesh(const std::string& path, std::vector<std::string>* notes = nullptr,
                       const TextReadOptions& options = {});
/// read_mesh of an OBJ file that also returns its material statements in `materials`.
TriangleMesh read_obj_with_materials(const std::string& path, ObjMaterialUse& materials,
                                     std::vector<std::string>* notes = nullptr, const TextReadOptions& options = {});

/// The same from a stream; `name` is used in messages. The stream is read up to the size limit.
TriangleMesh read_off(std::istream& in, const std::string& name, std::vector<std::string>* notes = nullptr,
                      const TextReadOptions& options = {});
TriangleMesh read_obj(std::istream& in, const std::string& name, std::vector<std::string>* notes = nullptr,
                      const TextReadOptions& options = {});

}  // namespace panelrad::geometry
