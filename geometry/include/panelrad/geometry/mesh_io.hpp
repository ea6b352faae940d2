#pragma once
// Mesh input: OFF, OBJ and STL files (STL: read_stl below). Vertices are shared: vertices with
// exactly the same coordinates are merged (so a "triangle soup" works) and vertices used by no
// face are dropped, each reported in `notes`. Input face i becomes facet i, and
// TriangleMesh::facet_line[i] is the line where it is written; every message names it "input face
// i (line L)", i counted from 0 in every format (as facet ids everywhere, e.g. in a scene's JSON
// sidecar).
//
// Faces are triangulated on their own corners, no point added, every triangle running in the face's
// rotational direction (validation may re-triangulate convex meshes exactly, see validation.hpp).
// A triangle is kept as written. A polygon P = (p_0, ..., p_{n-1}), n >= 4, must be a planar simple
// polygon, else the reader refuses it naming the file, the face and its line:
//   - no vertex twice in one face, and not all vertices on one straight line (zero area);
//   - planar: with c the mean of its vertices and N its Newell normal sum_i (p_i - c) x (p_{i+1} - c),
//     every vertex lies within
//         max(1e-9 * s, 4 * eta)
//     of the plane through c normal to N; s is the diagonal of the polygon's axis-parallel bounding
//     box, eta the per-coordinate rounding of the whole mesh's coordinates (InputRounding::
//     per_coordinate, input_rounding.hpp: 5e-6 M for coordinates of at most 6 significant digits
//     and largest magnitude M, 1.8e-15 M for 17-digit doubles). Rounding moves each coordinate by
//     at most eta, so 4 eta covers a well-shaped planar polygon written with 6 significant digits
//     at any offset (a sliver, much narrower than long, tilts its Newell plane more and may need
//     more digits). Beyond that tolerance but within 1e-4 s (the largest violation ever put down
//     to rounding, kMaxRoundingViolation of input_rounding.hpp: a rounded export rotated and
//     rewritten with more digits, whose digits no longer show its rounding) the polygon is
//     triangulated as projected along N, each triangle in its own plane, with a note naming the
//     face, its line and the distance; beyond 1e-4 s it is refused: a unit square with one corner
//     lifted by 1e-2 is (its corners lie 2.5e-3 from that plane), "split it into planar polygons
//     or triangles";
//   - simple (exact predicates, on P projected to the coordinate plane that drops the largest
//     component of N): sides meet only at the corner two consecutive sides share; a polygon that
//     crosses or touches itself is refused.
// Vertices on a straight side are corners of the triangles (no zero-area triangle is made). When
// the fan (p_0, p_k, p_{k+1}), k = 1..n-2, is a triangulation of P (each fan triangle non-degenerate
// with P's orientation, the fan less than a full turn around p_0; in particular for every convex
// polygon without a straight corner), the fan is the output; otherwise P's constrained Delaunay
// triangulation in that projection (non-convex faces, e.g. an L-shaped wall written as one polygon).
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
#include <panelrad/support/text_file.hpp>

#include <iosfwd>
#include <string>
#include <vector>

namespace panelrad::geometry {

/// Reads an OFF, OBJ or STL file, chosen by extension (case-insensitive). Throws MeshError naming the
/// file, the line and what is wrong: missing/unreadable file, not a regular file, above the size
/// limit, a NUL byte, unknown extension, empty or truncated file, garbage, a face index out of range,
/// a face with fewer than 3 vertices, a non-finite coordinate, a polygon that is not a planar simple
/// polygon (above). Never returns a partial mesh.
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
/// An STL mesh, ASCII or binary (stl_io.cpp: read with CGAL::IO::read_STL), up to the size limit:
/// each triangle one input face; corners with identical coordinates merged; facet_group from the
/// ASCII `solid` names. MeshError naming the file for an empty, truncated or unreadable one, a
/// binary record with a non-finite corner, or bytes that are neither text nor a binary STL.
TriangleMesh read_stl(std::istream& in, const std::string& name, std::vector<std::string>* notes = nullptr,
                      const TextReadOptions& options = {});

}  // namespace panelrad::geometry
