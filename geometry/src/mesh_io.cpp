// Mesh input: strict OFF and OBJ readers with file:line error messages.
//
// OpenMesh's readers (OpenMesh::IO) are not used for the actual read: they drop faces that would
// make the mesh non-manifold ("complex edge") with a message on stderr instead of an error, accept
// truncated files silently and give no line numbers, so a bad file could become a silently wrong
// mesh. The own tokenizer below knows the line of every token and refuses anything it does not
// understand; the shared vertex structure is built here directly, and each polygon is triangulated
// on its own corners or refused (polygon_triangulation.hpp). Measured with Debian's OpenMesh
// 9.0 (tests/geometry/test_mesh_io.cpp, AgreesWithOpenMeshReader): an OFF with '#' comment lines is read
// as an empty mesh, an OFF with per-face colours stops after its first face, both without an
// error, and coordinates are parsed in single precision. OpenMesh's reader stays as an independent
// cross-check (read_mesh_with_openmesh, openmesh_io.cpp): both agree on well-formed files.
#include <panelrad/geometry/mesh_io.hpp>

#include "stl_io.hpp"

#include "polygon_triangulation.hpp"

#include <panelrad/geometry/input_rounding.hpp>
#include <panelrad/support/text_file.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <istream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>

namespace panelrad::geometry {
namespace {

constexpr long long kMaxCount = std::numeric_limits<Index>::max();

[[noreturn]] void fail(const std::string& name, long line, const std::string& what) {
  if (line > 0) throw MeshError(name + ":" + std::to_string(line) + ": " + what);
  throw MeshError(name + ": " + what);
}

/// How every message names a face: its 0-based number, which is its facet id, and its line.
std::string input_face(long long f, long line) {
  return "input face " + std::to_string(f) + " (line " + std::to_string(line) + ")";
}

std::string show(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string s(token.substr(0, kMax));
  if (token.size() > kMax) s += "...";
  return "'" + s + "'";
}

/// One non-blank line of content (comment removed), split into tokens (views into the text).
struct Line {
  long number = 0;
  std::vector<std::string_view> tokens;
};

/// The content lines of `text`, one at a time (the text is not copied and no list of all lines is
/// built, so memory stays at the text plus the mesh): '#' starts a comment, blank lines are
/// skipped, bytes that cannot belong to a text mesh file are refused with their line and column.
/// With `continuation`, a trailing backslash joins a line with the next (OBJ).
class LineCursor {
 public:
  LineCursor(std::string_view text, const std::string& name, bool continuation)
      : text_(text), name_(name), continuation_(continuation) {}

  /// The next content line into `out`; false at the end of the text.
  bool next(Line& out) {
    bool continued = false;  // the physical line before ended with a backslash
    out.tokens.clear();
    out.number = 0;
    while (pos_ < text_.size()) {
      std::size_t end = text_.find('\n', pos_);
      if (end == std::string_view::npos) end = text_.size();
      ++number_;
      std::string_view line = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      const std::size_t hash = line.find('#');
      if (hash != std::string_view::npos) line = line.substr(0, hash);
      check_bytes(line);
      bool continues = false;
      if (continuation_) {
        const std::size_t last = line.find_last_not_of(" \t\r\f\v");
        if (last != std::string_view::npos && line[last] == '\\') {
          continues = true;
          line = line.substr(0, last);
        }
      }
      if (!continued) {
        out.tokens.clear();
        out.number = number_;
      }
      std::size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        std::size_t j = i;
        while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
        if (j > i) out.tokens.push_back(line.substr(i, j - i));
        i = j;
      }
      continued = continues;
      if (!continues && !out.tokens.empty()) break;
    }
    if (out.tokens.empty()) return false;
    last_content_line_ = out.number;
    return true;
  }

  /// The line of the last content line returned (after the end: the file's last content line).
  long last_content_line() const { return last_content_line_; }

 private:
  void check_bytes(std::string_view line) const {
    for (std::size_t c = 0; c < line.size(); ++c) {
      const auto b = static_cast<unsigned char>(line[c]);
      const bool ok = (b >= 0x20 && b < 0x7f) || b == '\t' || b == '\r' || b == '\f' || b == '\v';
      if (!ok) {
        std::ostringstream os;
        os << "unexpected byte 0x" << std::hex << static_cast<int>(b) << std::dec << " at column " << c + 1
           << " (binary data or garbage; only text meshes are read)";
        fail(name_, number_, os.str());
      }
    }
  }

  std::string_view text_;
  const std::string& name_;
  bool continuation_;
  std::size_t pos_ = 0;
  long number_ = 0;
  long last_content_line_ = 0;
};

enum class NumberStatus { ok, bad, out_of_range };

NumberStatus parse_number(std::string_view token, double& value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  const char* first = token.data();
  const char* last = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(first, last, value, std::chars_format::general);
  if (ec == std::errc::result_out_of_range) return NumberStatus::out_of_range;
  if (ec != std::errc() || ptr != last) return NumberStatus::bad;
  return NumberStatus::ok;
}

bool parse_integer(std::string_view token, long long& value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  const char* last = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), last, value);
  return ec == std::errc() && ptr == last;
}

/// A coordinate: a number that must be finite.
double coordinate(std::string_view token, const std::string& name, long line, const char* what) {
  double v = 0;
  switch (parse_number(token, v)) {
    case NumberStatus::bad:
      fail(name, line, std::string("bad number ") + show(token) + " in " + what);
    case NumberStatus::out_of_range:
      fail(name, line, std::string("non-finite coordinate ") + show(token) + " in " + what +
                           " (outside the range of double)");
    case NumberStatus::ok:
      break;
  }
  if (!std::isfinite(v))
    fail(name, line, std::string("non-finite coordinate ") + show(token) + " in " + what);
  return v;
}

/// Any number (colours, normals, weights): must parse, may be anything finite or not.
void any_number(std::string_view token, const std::string& name, long line, const char* what) {
  double v = 0;
  if (parse_number(token, v) == NumberStatus::bad)
    fail(name, line, std::string("bad number ") + show(token) + " in " + what);
}

/// Faces as read: vertex indices (0-based, into the file's vertex list) and the line of each face.
struct RawMesh {
  std::vector<Vec3> vertices;
  std::vector<Index> face_offsets{0};
  std::vector<Index> face_indices;
  std::vector<long> face_lines;
};

/// Appends the triangles of face f (vertex numbers of the mesh) as facet f: a triangle as is, a
/// polygon triangulated on its own corners (polygon_triangulation.hpp) or refused with its line.
/// `eta` is the per-coordinate rounding of the mesh's coordinates, computed at the first polygon.
void triangulate_face(TriangleMesh& mesh, const std::vector<Index>& face, std::size_t f, long line,
                      std::optional<double>& eta, std::vector<Vec3>& corners, const std::string& name,
                      std::vector<std::string>* notes) {
  const auto facet = static_cast<Index>(f);
  if (face.size() == 3) {
    mesh.triangles.push_back({face[0], face[1], face[2]});
    mesh.facet_of_triangle.push_back(facet);
    return;
  }
  if (!eta) eta = input_rounding(mesh).per_coordinate;
  corners.clear();
  for (Index v : face) corners.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
  const polygon_detail::PolygonTriangulation t = polygon_detail::triangulate_polygon(corners, *eta);
  if (!t.refusal.empty()) fail(name, line, input_face(static_cast<long long>(f), line) + " " + t.refusal);
  if (!t.note.empty() && notes) notes->push_back(name + ":" + std::to_string(line) + ": " + input_face(static_cast<long long>(f), line) + " " + t.note);
  for (const auto& c : t.triangles) {
    mesh.triangles.push_back({face[static_cast<std::size_t>(c[0])], face[static_cast<std::size_t>(c[1])],
                              face[static_cast<std::size_t>(c[2])]});
    mesh.facet_of_triangle.push_back(facet);
  }
}

/// Builds the triangle mesh: merges vertices with identical coordinates, drops unused vertices,
/// triangulates each face (face i -> facet i, its line kept in facet_line).
TriangleMesh build_mesh(const RawMesh& raw, const std::string& name, std::vector<std::string>* notes) {
  const std::size_t nv = raw.vertices.size();
  std::vector<char> used(nv, 0);
  for (Index v : raw.face_indices) used[static_cast<std::size_t>(v)] = 1;

  TriangleMesh mesh;
  mesh.source = name;
  std::vector<Index> new_index(nv, -1);
  std::map<std::array<double, 3>, Index> by_position;  // value comparison: -0.0 merges with 0.0
  std::size_t merged = 0;
  std::size_t dropped = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    if (!used[v]) {
      ++dropped;
      continue;
    }
    const Vec3& p = raw.vertices[v];
    const auto [it, inserted] =
        by_position.try_emplace({p.x(), p.y(), p.z()}, static_cast<Index>(mesh.vertices.size()));
    if (inserted)
      mesh.vertices.push_back(p);
    else
      ++merged;
    new_index[v] = it->second;
  }

  const std::size_t nf = raw.face_lines.size();
  mesh.num_facets = static_cast<Index>(nf);
  mesh.facet_line = raw.face_lines;
  std::optional<double> eta;
  std::vector<Index> face;
  std::vector<Vec3> corners;
  for (std::size_t f = 0; f < nf; ++f) {
    const auto begin = static_cast<std::size_t>(raw.face_offsets[f]);
    const auto end = static_cast<std::size_t>(raw.face_offsets[f + 1]);
    face.clear();
    for (std::size_t k = begin; k < end; ++k) face.push_back(new_index[static_cast<std::size_t>(raw.face_indices[k])]);
    triangulate_face(mesh, face, f, raw.face_lines[f], eta, corners, name, notes);
  }
  if (notes) {
    if (merged > 0)
      notes->push_back(name + ": merged " + std::to_string(merged) +
                       " vertices with identical coordinates (vertex numbers in later messages "
                       "refer to the merged list)");
    if (dropped > 0)
      notes->push_back(name + ": dropped " + std::to_string(dropped) + " vertices used by no face" +
                       (merged > 0 ? "" : " (vertex numbers in later messages refer to the rest)"));
  }
  return mesh;
}

void add_face(RawMesh& raw, const std::vector<Index>& face, long line) {
  raw.face_indices.insert(raw.face_indices.end(), face.begin(), face.end());
  raw.face_offsets.push_back(static_cast<Index>(raw.face_indices.size()));
  raw.face_lines.push_back(line);
}

/// OFF header keyword: [ST][C][N][4][n]OFF. Returns false when `token` is not one.
bool off_keyword(std::string_view token, const std::string& name, long line) {
  if (token.size() < 3 || token.substr(token.size() - 3) != "OFF") return false;
  std::string_view prefix = token.substr(0, token.size() - 3);
  if (prefix.substr(0, 2) == "ST") prefix.remove_prefix(2);
  if (!prefix.empty() && prefix[0] == 'C') prefix.remove_prefix(1);
  if (!prefix.empty() && prefix[0] == 'N') prefix.remove_prefix(1);
  if (!prefix.empty() && (prefix[0] == '4' || prefix[0] == 'n'))
    fail(name, line, "OFF variant " + show(token) + " (4-D or n-D vertices) is not supported");
  if (!prefix.empty()) fail(name, line, "unknown OFF header keyword " + show(token));
  return true;
}

/// The counts of an OFF header: vertices, faces, and the line they stand on.
struct OffCounts {
  long long vertices = 0;
  long long faces = 0;
  long line = 0;
};

/// The header: the optional keyword [ST][C][N]OFF and the counts 'vertices faces [edges]', on
/// the keyword's line or the next content line. `first` is the file's first content line.
OffCounts read_off_header(LineCursor& cursor, Line& first, const std::string& name) {
  Line& l = first;
  std::vector<std::string_view> counts;
  long counts_line = l.number;
  if (off_keyword(l.tokens[0], name, l.number)) {
    counts.assign(l.tokens.begin() + 1, l.tokens.end());
    if (!counts.empty() && counts[0] == "BINARY")
      fail(name, l.number, "binary OFF is not supported; write it as text");
    if (counts.empty()) {
      const long header_line = l.number;
      if (!cursor.next(l)) fail(name, header_line, "truncated file: nothing after the OFF header");
      counts = l.tokens;
      counts_line = l.number;
    }
  } else {
    long long probe = 0;
    if (!parse_integer(l.tokens[0], probe))
      fail(name, l.number, "not an OFF file: expected the header 'OFF' or the counts, found " + show(l.tokens[0]));
    counts = l.tokens;
  }
  if (counts.size() < 2 || counts.size() > 3)
    fail(name, counts_line,
         "expected the counts 'vertices faces [edges]', found " + std::to_string(counts.size()) + " values");
  long long count[3] = {0, 0, 0};
  for (std::size_t i = 0; i < counts.size(); ++i)
    if (!parse_integer(counts[i], count[i]) || count[i] < 0 || count[i] > kMaxCount)
      fail(name, counts_line, "bad count " + show(counts[i]) + " (expected a non-negative integer)");
  if (count[0] == 0) fail(name, counts_line, "empty mesh: the header declares 0 vertices");
  if (count[1] == 0) fail(name, counts_line, "empty mesh: the header declares 0 faces");
  return {count[0], count[1], counts_line};
}

/// The vertex list: one line 'x y z' per vertex, optionally followed by normal, colour and
/// texture values (checked to be numbers, not used).
void read_off_vertices(LineCursor& cursor, const OffCounts& counts, const std::string& name, RawMesh& raw) {
  Line l;
  for (long long v = 0; v < counts.vertices; ++v) {
    if (!cursor.next(l))
      fail(name, cursor.last_content_line(),
           "truncated file: the header (line " + std::to_string(counts.line) + ") declares " +
               std::to_string(counts.vertices) + " vertices, the file ends after " + std::to_string(v));
    const std::string what = "vertex " + std::to_string(v);
    if (l.tokens.size() < 3)
      fail(name, l.number, what + " has " + std::to_string(l.tokens.size()) + " values, needs x y z");
    if (l.tokens.size() > 12)
      fail(name, l.number, what + " has " + std::to_string(l.tokens.size()) +
                               " values (x y z plus at most normal, colour and texture coordinates); "
                               "is the vertex count in the header right?");
    Vec3 p;
    for (int c = 0; c < 3; ++c) p[c] = coordinate(l.tokens[static_cast<std::size_t>(c)], name, l.number, what.c_str());
    for (std::size_t t = 3; t < l.tokens.size(); ++t) any_number(l.tokens[t], name, l.number, what.c_str());
    raw.vertices.push_back(p);
  }
}

/// Face f on line l: 'k i_1 .. i_k' with k >= 3 indices into the nv vertices, optionally followed
/// by a colour (at most 4 numbers, checked, not used); the indices go into `face`.
void read_off_face(const Line& l, long long f, long long nv, const std::string& name, std::vector<Index>& face) {
  const std::string what = input_face(f, l.number);
  long long k = 0;
  if (!parse_integer(l.tokens[0], k))
    fail(name, l.number, what + ": bad vertex count " + show(l.tokens[0]));
  if (k < 3) fail(name, l.number, what + " has " + std::to_string(k) + " vertices; a face needs at least 3");
  if (static_cast<long long>(l.tokens.size()) - 1 < k)
    fail(name, l.number, what + " declares " + std::to_string(k) + " vertices but lists " +
                             std::to_string(l.tokens.size() - 1));
  const std::size_t extra = l.tokens.size() - 1 - static_cast<std::size_t>(k);
  if (extra > 4)
    fail(name, l.number, what + " has " + std::to_string(extra) +
                             " values after its indices (a colour takes at most 4)");
  face.clear();
  for (long long i = 1; i <= k; ++i) {
    const std::string_view tok = l.tokens[static_cast<std::size_t>(i)];
    long long idx = 0;
    if (!parse_integer(tok, idx)) fail(name, l.number, what + ": bad vertex index " + show(tok));
    if (idx < 0 || idx >= nv)
      fail(name, l.number, what + ": vertex index " + std::to_string(idx) + " out of range [0, " +
                               std::to_string(nv - 1) + "]");
    face.push_back(static_cast<Index>(idx));
  }
  for (std::size_t t = 1 + static_cast<std::size_t>(k); t < l.tokens.size(); ++t)
    any_number(l.tokens[t], name, l.number, (what + " colour").c_str());
}

/// The face list: one line per face, in file order (face i -> facet i).
void read_off_faces(LineCursor& cursor, const OffCounts& counts, const std::string& name, RawMesh& raw) {
  Line l;
  std::vector<Index> face;
  for (long long f = 0; f < counts.faces; ++f) {
    if (!cursor.next(l))
      fail(name, cursor.last_content_line(),
           "truncated file: the header (line " + std::to_string(counts.line) + ") declares " +
               std::to_string(counts.faces) + " faces, the file ends after " + std::to_string(f));
    read_off_face(l, f, counts.vertices, name, face);
    add_face(raw, face, l.number);
  }
}

TriangleMesh parse_off(const std::string& text, const std::string& name, std::vector<std::string>* notes) {
  if (text.empty()) fail(name, 0, "empty file");
  LineCursor cursor(text, name, false);
  Line l;
  if (!cursor.next(l)) fail(name, 0, "empty file (no data, only blank lines or comments)");
  const OffCounts counts = read_off_header(cursor, l, name);

  RawMesh raw;
  read_off_vertices(cursor, counts, name, raw);
  read_off_faces(cursor, counts, name, raw);
  if (cursor.next(l))
    fail(name, l.number,
         "unexpected data after the last face (the header declares " + std::to_string(counts.vertices) +
             " vertices and " + std::to_string(counts.faces) + " faces): " + show(l.tokens[0]));
  return build_mesh(raw, name, notes);
}

/// Tokens from `first` on, joined by single spaces (material and library names).
std::string join_from(const std::vector<std::string_view>& tokens, std::size_t first) {
  std::string s;
  for (std::size_t t = first; t < tokens.size(); ++t) {
    if (!s.empty()) s += ' ';
    s += tokens[t];
  }
  return s;
}

/// Why an OBJ statement is refused: a miscased statement (OBJ is case-sensitive: `V` is not `v`,
/// and reading it as `v` or skipping it would both be guesses), free-form geometry and other
/// statements this reader does not implement, or an unknown keyword.
std::string unknown_obj_statement(std::string_view key) {
  static const char* const kRead[] = {"v", "vt", "vn", "vp", "f", "l", "p", "o", "g", "s", "usemtl", "mtllib"};
  static const char* const kUnsupported[] = {"cstype", "deg",    "bmat",    "step",     "curv",       "curv2",
                                             "surf",   "parm",   "trim",    "hole",     "scrv",       "sp",
                                             "end",    "con",    "mg",      "bevel",    "c_interp",   "d_interp",
                                             "lod",    "maplib", "usemap",  "ctech",    "stech",      "shadow_obj",
                                             "trace_obj", "res",  "call",   "csh"};
  std::string lower(key);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const char* k : kRead)
    if (lower == k)
      return "unknown OBJ statement " + show(key) + " (OBJ statements are case-sensitive: did you mean '" + k + "'?)";
  for (const char* k : kUnsupported)
    if (lower == k)
      return "unsupported OBJ statement " + show(key) +
             " (free-form curves and surfaces, and display statements, are not read: only v and f polygons)";
  return "unknown OBJ statement " + show(key);
}

/// Vertex references of the faces read so far, each checked against the final vertex count once
/// the whole file is read (0-based, negative references already resolved), with their lines.
struct ObjPendingIndices {
  std::vector<long long> index;
  std::vector<long> line;
};

/// A "v x y z [w | r g b]" line: the vertex's coordinates (the other values must be numbers).
void read_obj_vertex(const Line& l, const std::string& name, RawMesh& raw) {
  const std::string what = "vertex " + std::to_string(raw.vertices.size() + 1);
  const std::size_t n = l.tokens.size() - 1;
  if (n < 3 || n > 7) fail(name, l.number, what + " has " + std::to_string(n) + " values (expected x y z [w | r g b])");
  Vec3 p;
  for (int c = 0; c < 3; ++c) p[c] = coordinate(l.tokens[static_cast<std::size_t>(c) + 1], name, l.number, what.c_str());
  for (std::size_t t = 4; t < l.tokens.size(); ++t) any_number(l.tokens[t], name, l.number, what.c_str());
  raw.vertices.push_back(p);
}

/// One vertex reference of a face, v, v/vt, v//vn or v/vt/vn: the 0-based vertex index (-1 is the
/// last vertex defined before this line); texture and normal indices must be integers.
long long obj_vertex_index(std::string_view ref, const Line& l, const std::string& name, const std::string& what,
                           long long defined) {
  std::array<std::string_view, 3> parts{};
  std::size_t np = 0;
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = ref.find('/', start);
    if (np == 3) fail(name, l.number, what + ": bad vertex reference " + show(ref));
    parts[np++] = ref.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  long long idx = 0;
  if (!parse_integer(parts[0], idx) || idx == 0)
    fail(name, l.number, what + ": bad vertex reference " + show(ref) +
                             " (expected v, v/vt, v//vn or v/vt/vn with a non-zero integer v)");
  for (std::size_t p = 1; p < np; ++p) {
    long long other = 0;
    if (!parts[p].empty() && !parse_integer(parts[p], other)) fail(name, l.number, what + ": bad vertex reference " + show(ref));
  }
  if (idx < 0) {
    if (-idx > defined)
      fail(name, l.number, what + ": relative vertex index " + std::to_string(idx) + " but only " +
                               std::to_string(defined) + " vertices are defined before this line");
    return defined + idx;
  }
  --idx;
  if (idx > kMaxCount) fail(name, l.number, what + ": vertex index " + show(parts[0]) + " out of range");
  return idx;
}

/// An "f v1 v2 v3 ..." line: the face, its references kept for the final range check.
void read_obj_face(const Line& l, const std::string& name, RawMesh& raw, ObjPendingIndices& pending,
                   std::vector<Index>& face) {
  const std::string what = input_face(static_cast<long long>(raw.face_lines.size()), l.number);
  const std::size_t n = l.tokens.size() - 1;
  if (n < 3) fail(name, l.number, what + " has " + std::to_string(n) + " vertices; a face needs at least 3");
  face.clear();
  const auto defined = static_cast<long long>(raw.vertices.size());
  for (std::size_t t = 1; t <= n; ++t) {
    const long long idx = obj_vertex_index(l.tokens[t], l, name, what, defined);
    face.push_back(static_cast<Index>(idx));
    pending.index.push_back(idx);
    pending.line.push_back(l.number);
  }
  add_face(raw, face, l.number);
}

/// The material statements of a line (mtllib, usemtl), when the caller asks for them.
void read_obj_material_statement(const Line& l, const std::string& name, ObjMaterialUse& materials,
                                 std::string& usemtl, long& usemtl_line) {
  const std::string_view key = l.tokens[0];
  if (key == "mtllib") {
    if (l.tokens.size() < 2) fail(name, l.number, "mtllib without a file name");
    for (std::size_t t = 1; t < l.tokens.size(); ++t) materials.libraries.push_back({std::string(l.tokens[t]), l.number});
  } else if (key == "usemtl") {
    if (l.tokens.size() < 2) fail(name, l.number, "usemtl without a material name");
    usemtl = join_from(l.tokens, 1);
    usemtl_line = l.number;
  }
}

/// After the last line: some geometry, and every vertex reference within [1, vertex count].
void check_obj_complete(const RawMesh& raw, const ObjPendingIndices& pending, const std::string& name) {
  if (raw.vertices.empty()) fail(name, 0, "empty mesh: no vertices ('v' lines)");
  if (raw.face_lines.empty()) fail(name, 0, "empty mesh: no faces ('f' lines)");
  const auto nv = static_cast<long long>(raw.vertices.size());
  for (std::size_t i = 0; i < pending.index.size(); ++i)
    if (pending.index[i] >= nv)
      fail(name, pending.line[i], "vertex index " + std::to_string(pending.index[i] + 1) + " out of range [1, " +
                                      std::to_string(nv) + "]");
}

TriangleMesh parse_obj(const std::string& text, const std::string& name, std::vector<std::string>* notes,
                       ObjMaterialUse* materials = nullptr) {
  if (text.empty()) fail(name, 0, "empty file");
  LineCursor cursor(text, name, true);
  Line l;
  if (!cursor.next(l)) fail(name, 0, "empty file (no data, only blank lines or comments)");

  RawMesh raw;
  ObjPendingIndices pending;
  std::vector<Index> face;
  std::string usemtl;  // the material in force (materials only)
  long usemtl_line = 0;
  std::string group;   // the object or group in force (`o` or `g`, the later one)
  std::vector<std::string> face_group;
  bool named = false;
  do {
    const std::string_view key = l.tokens[0];
    if (materials) read_obj_material_statement(l, name, *materials, usemtl, usemtl_line);
    if (key == "o" || key == "g") {
      group = join_from(l.tokens, 1);
      named = named || !group.empty();
    }
    if (key == "v") {
      read_obj_vertex(l, name, raw);
    } else if (key == "f") {
      read_obj_face(l, name, raw, pending, face);
      face_group.push_back(group);
      if (materials) {
        materials->face_material.push_back(usemtl);
        materials->face_line.push_back(l.number);
        materials->usemtl_line.push_back(usemtl_line);
      }
    } else if (!(key == "vt" || key == "vn" || key == "vp" || key == "l" || key == "p" || key == "o" || key == "g" ||
                 key == "s" || key == "usemtl" || key == "mtllib")) {
      // vt, vn, vp, l, p, o, g, s and the material statements: not geometry here
      fail(name, l.number, unknown_obj_statement(key));
    }
  } while (cursor.next(l));
  check_obj_complete(raw, pending, name);
  TriangleMesh mesh = build_mesh(raw, name, notes);
  if (named) mesh.facet_group = std::move(face_group);
  return mesh;
}

/// The bounded reader (text_file.hpp) with its errors as MeshError.
std::string read_all(std::istream& in, const std::string& name, const TextReadOptions& options) {
  try {
    return read_text_stream(in, name, options);
  } catch (const TextFileError& e) {
    throw MeshError(e.what());
  }
}

}  // namespace

TriangleMesh read_off(std::istream& in, const std::string& name, std::vector<std::string>* notes,
                      const TextReadOptions& options) {
  return parse_off(read_all(in, name, options), name, notes);
}

TriangleMesh read_obj(std::istream& in, const std::string& name, std::vector<std::string>* notes,
                      const TextReadOptions& options) {
  return parse_obj(read_all(in, name, options), name, notes);
}

namespace {
std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

/// The whole text of an .off or .obj file (by extension, case-insensitive), read by the bounded
/// reader (text_file.hpp: regular files only, size limit, no NUL byte, byte-order mark removed).
std::string read_mesh_file(const std::string& path, const TextReadOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) fail(path, 0, "cannot open: no such file");
  const std::string ext = lower_extension(path);
  if (!fs::is_directory(status) && ext != ".off" && ext != ".obj")
    fail(path, 0, "unknown mesh format " + show(ext.empty() ? std::string("(no extension)") : ext) +
                      ": expected .off, .obj or .stl");
  try {
    return read_text_file(path, "", options);
  } catch (const TextFileError& e) {
    throw MeshError(e.what());
  }
}

bool is_off(const std::string& path) { return lower_extension(path) == ".off"; }
}  // namespace

TriangleMesh read_mesh(const std::string& path, std::vector<std::string>* notes, const TextReadOptions& options) {
  if (lower_extension(path) == ".stl") return read_stl_file(path, notes, options);
  const std::string text = read_mesh_file(path, options);
  return is_off(path) ? parse_off(text, path, notes) : parse_obj(text, path, notes);
}

TriangleMesh read_obj_with_materials(const std::string& path, ObjMaterialUse& materials,
                                     std::vector<std::string>* notes, const TextReadOptions& options) {
  if (is_off(path) || lower_extension(path) == ".stl")
    fail(path, 0, "an " + std::string(is_off(path) ? "OFF" : "STL") + " file has no materials: expected an .obj file");
  const std::string text = read_mesh_file(path, options);
  materials = ObjMaterialUse{};
  return parse_obj(text, path, notes, &materials);
}

}  // namespace panelrad::geometry
