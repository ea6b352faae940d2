#include <panelrad/io/scene_output.hpp>
#include <panelrad/io/text_output.hpp>

#include <Eigen/Geometry>
#include <png.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <new>
#include <set>
#include <sstream>
#include <stdexcept>

namespace panelrad {

using geometry::Vec3;

namespace {

// ---------------------------------------------------------------------------------------------
// Validation

[[noreturn]] void invalid(const char* who, const std::string& what) {
  throw std::invalid_argument(std::string(who) + ": " + what);
}

void check_vec3(const char* who, const Vec3& v, const char* what, std::size_t i) {
  if (!v.allFinite()) {
    std::ostringstream os;
    os << what << " of element " << i << " is not finite (" << v.x() << ", " << v.y() << ", "
       << v.z() << ")";
    invalid(who, os.str());
  }
}

void check_names(const char* who, const std::vector<std::string>& channels) {
  if (channels.empty()) invalid(who, "the field has no channels");
  std::set<std::string> names;
  for (const std::string& c : channels) {
    // Channel names become CSV columns and PLY/VTK property names: one plain token each.
    if (c.empty()) invalid(who, "empty channel name");
    for (const char ch : c)
      if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.'))
        invalid(who, "channel name '" + c + "' has a character other than letters, digits, _ - .");
    if (!names.insert(c).second) invalid(who, "channel name '" + c + "' appears twice");
  }
}

/// Throws std::invalid_argument naming the first problem: sizes, channel names, non-finite values.
void validate(const char* who, const ElementField& f) {
  const std::size_t n = f.triangle.size();
  if (n == 0) invalid(who, "the field has no elements");
  const auto same = [&](std::size_t got, const char* what) {
    if (got != n)
      invalid(who, std::string(what) + " has " + std::to_string(got) + " entries for " +
                       std::to_string(n) + " elements");
  };
  same(f.inner_normal.size(), "inner_normal");
  same(f.centroid.size(), "centroid");
  same(f.area.size(), "area");
  same(f.facet.size(), "facet");
  const std::size_t C = f.channels.size();
  check_names(who, f.channels);
  const auto per_channel = [&](const std::vector<Eigen::VectorXd>& v, const char* what) {
    if (v.size() != C)
      invalid(who, std::string(what) + " has " + std::to_string(v.size()) + " channels for " +
                       std::to_string(C) + " channel names");
    for (std::size_t c = 0; c < C; ++c) {
      if (static_cast<std::size_t>(v[c].size()) != n)
        invalid(who, std::string(what) + "[" + f.channels[c] + "] has " +
                         std::to_string(v[c].size()) + " values for " + std::to_string(n) +
                         " elements");
      for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(v[c][static_cast<Eigen::Index>(i)])) {
          std::ostringstream os;
          os << what << "[" << f.channels[c] << "] of element " << i << " is not finite ("
             << v[c][static_cast<Eigen::Index>(i)] << ")";
          invalid(who, os.str());
        }
    }
  };
  per_channel(f.rho, "rho");
  per_channel(f.emission, "emission");
  per_channel(f.radiosity, "radiosity");
  for (std::size_t i = 0; i < n; ++i) {
    for (const Vec3& p : f.triangle[i]) check_vec3(who, p, "a corner", i);
    check_vec3(who, f.inner_normal[i], "the inner normal", i);
    check_vec3(who, f.centroid[i], "the centroid", i);
    if (!std::isfinite(f.area[i])) {
      std::ostringstream os;
      os << "area of element " << i << " is not finite (" << f.area[i] << ")";
      invalid(who, os.str());
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Text helpers

void append_g17(std::string& out, double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  out += buf;
}

void append_g9(std::string& out, double v) {  // float properties: 9 digits round-trip a float
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(static_cast<float>(v)));
  out += buf;
}

/// True when float32 holds v to its full relative precision: v is zero or a normal float after
/// rounding (FLT_MIN <= |v| <= FLT_MAX). Larger values would become inf, smaller ones subnormal
/// (fewer digits) or 0.
bool fits_float(double v) {
  if (v == 0.0) return true;
  const float f = static_cast<float>(v);
  return std::fpclassify(f) == FP_NORMAL;
}

/// Column/property suffix of channel c: "_<name>", or "" for a single-channel field (rho, E, u).
std::string suffix(const ElementField& f, std::size_t c) {
  return f.channels.size() == 1 ? std::string() : "_" + f.channels[c];
}

double value(const Eigen::VectorXd& v, std::size_t i) { return v[static_cast<Eigen::Index>(i)]; }

/// Corners shared between elements, deduplicated on the bit patterns of their coordinates.
struct SharedVertices {
  std::vector<Vec3> points;
  std::vector<std::array<std::size_t, 3>> corner;  // [element] -> point indices
};

SharedVertices share_vertices(const ElementField& f) {
  SharedVertices s;
  std::map<std::array<std::uint64_t, 3>, std::size_t> index;
  s.corner.resize(f.size());
  for (std::size_t i = 0; i < f.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = f.triangle[i][static_cast<std::size_t>(k)];
      const std::array<std::uint64_t, 3> key = {std::bit_cast<std::uint64_t>(p.x()),
                                                std::bit_cast<std::uint64_t>(p.y()),
                                                std::bit_cast<std::uint64_t>(p.z())};
      const auto [it, inserted] = index.emplace(key, s.points.size());
      if (inserted) s.points.push_back(p);
      s.corner[i][static_cast<std::size_t>(k)] = it->second;
    }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Colours

using Rgb = std::array<unsigned char, 3>;

bool is_rgb(const ElementField& f) {
  return f.channels.size() == 3 && f.channels[0] == "R" && f.channels[1] == "G" &&
         f.channels[2] == "B";
}

unsigned char to_byte(double v) {  // v in [0, 1]
  return static_cast<unsigned char>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

/// Viridis sampled at 9 evenly spaced stops, interpolated linearly (perceptually near-uniform).
Rgb colour_map(double t) {
  static constexpr unsigned char stops[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},
                                                {44, 113, 142}, {33, 144, 141}, {39, 173, 129},
                                                {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
  t = std::clamp(std::isfinite(t) ? t : 0.5, 0.0, 1.0) * 8.0;
  const int k = std::min(7, static_cast<int>(t));
  const double w = t - k;
  Rgb c;
  for (int j = 0; j < 3; ++j)
    c[static_cast<std::size_t>(j)] = static_cast<unsigned char>(
        std::lround((1.0 - w) * stops[k][j] + w * stops[k + 1][j]));
  return c;
}

std::vector<Rgb> colours_of_valid(const ElementField& f) {
  const std::size_t n = f.size();
  std::vector<Rgb> out(n);
  if (is_rgb(f)) {
    // RGB: one exposure for all channels, 1 / (95th percentile of the brightest channel over the
    // elements that emit nothing; over all elements when every one emits), so the walls fill the
    // range and the lights saturate; then clamp to [0, 1] and gamma-encode (v^(1/2.2)).
    std::vector<double> lit, all;
    for (std::size_t i = 0; i < n; ++i) {
      double m = -std::numeric_limits<double>::infinity();
      bool emits = false;
      for (std::size_t c = 0; c < 3; ++c) {
        m = std::max(m, value(f.radiosity[c], i));
        emits = emits || value(f.emission[c], i) != 0.0;
      }
      all.push_back(m);
      if (!emits) lit.push_back(m);
    }
    std::vector<double>& base = lit.empty() ? all : lit;
    std::sort(base.begin(), base.end());
    const std::size_t rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(base.size())));
    double white = base[std::max<std::size_t>(rank, 1) - 1];
    if (!(white > 0.0)) white = *std::max_element(all.begin(), all.end());
    const double exposure = white > 0.0 ? 1.0 / white : 1.0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t c = 0; c < 3; ++c) {
        const double v = std::clamp(value(f.radiosity[c], i) * exposure, 0.0, 1.0);
        out[i][c] = to_byte(std::pow(v, 1.0 / 2.2));
      }
  } else {
    // Other channel sets: the first channel, linear from its minimum to its maximum over the
    // elements that emit nothing (so that the reflected light, not the lamp, fills the map; the
    // emitters are clamped to its top), over all elements when that range is empty; a constant
    // field gets the map's middle colour.
    const Eigen::VectorXd& u = f.radiosity[0];
    const double lo = u.minCoeff();
    double hi = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i)
      if (value(f.emission[0], i) == 0.0) hi = std::max(hi, value(u, i));
    if (!(hi > lo)) hi = u.maxCoeff();
    for (std::size_t i = 0; i < n; ++i)
      out[i] = colour_map(hi > lo ? std::clamp((value(u, i) - lo) / (hi - lo), 0.0, 1.0) : 0.5);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// PNG encoding into memory. No C++ object with a destructor lives in encode_png's frame across
// setjmp; errors come back as a message in the sink.

struct PngSink {
  std::string* out;
  char message[256];
};

void png_fail(png_structp png, png_const_charp msg) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", msg ? msg : "unknown error");
  png_longjmp(png, 1);
}

void png_warn(png_structp, png_const_charp) {}

void png_append(png_structp png, png_bytep data, png_size_t length) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  bool ok = true;
  try {
    sink->out->append(reinterpret_cast<const char*>(data), length);
  } catch (...) {
    ok = false;
  }
  if (!ok) png_error(png, "out of memory");
}

void png_flush(png_structp) {}

bool encode_png(const unsigned char* rgb, int width, int height, PngSink* sink) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, sink, png_fail, png_warn);
  if (!png) {
    std::snprintf(sink->message, sizeof sink->message, "cannot create the PNG writer");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    std::snprintf(sink->message, sizeof sink->message, "cannot create the PNG info");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, sink, png_append, png_flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const std::size_t stride = 3 * static_cast<std::size_t>(width);
  for (int y = 0; y < height; ++y)
    png_write_row(png, rgb + stride * static_cast<std::size_t>(y));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

// ---------------------------------------------------------------------------------------------
// Rasterizer: 2x2 supersampled, vertices snapped to 1/256 of a sample so edge functions are exact
// integers; the top-left fill rule then covers every sample of a shared edge exactly once.

constexpr int kSamples = 2;                  // per pixel and axis
constexpr std::int64_t kSub = 256;           // fixed-point units per sample
constexpr Rgb kBackground = {32, 32, 32};

struct Canvas {
  int w, h;  // in samples
  std::vector<Rgb> colour;
  std::vector<double> depth;  // larger = nearer the viewer
};

struct ScreenPoint {
  std::int64_t x, y;  // fixed point, y downwards
  double z;
};

std::int64_t edge(const ScreenPoint& a, const ScreenPoint& b, std::int64_t px, std::int64_t py) {
  return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
}

bool top_left(const ScreenPoint& a, const ScreenPoint& b) {  // interior on the positive side
  const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
  return dy < 0 || (dy == 0 && dx > 0);
}

void fill_triangle(Canvas& cv, ScreenPoint v0, ScreenPoint v1, ScreenPoint v2, Rgb colour,
                   int x_end) {
  std::int64_t area = edge(v0, v1, v2.x, v2.y);
  if (area == 0) return;
  if (area < 0) {
    std::swap(v1, v2);
    area = -area;
  }
  const std::int64_t xmin = std::min({v0.x, v1.x, v2.x}), xmax = std::max({v0.x, v1.x, v2.x});
  const std::int64_t ymin = std::min({v0.y, v1.y, v2.y}), ymax = std::max({v0.y, v1.y, v2.y});
  // Sample (i, j) sits at ((i + 1/2) kSub, (j + 1/2) kSub).
  const auto first = [](std::int64_t lo) {
    return std::max<std::int64_t>(0, (lo - kSub / 2) / kSub);
  };
  const std::int64_t i0 = first(xmin), j0 = first(ymin);
  const std::int64_t i1 = std::min<std::int64_t>(x_end - 1, xmax / kSub + 1);
  const std::int64_t j1 = std::min<std::int64_t>(cv.h - 1, ymax / kSub + 1);
  const bool tl0 = top_left(v1, v2), tl1 = top_left(v2, v0), tl2 = top_left(v0, v1);
  const double inv = 1.0 / static_cast<double>(area);
  for (std::int64_t j = j0; j <= j1; ++j) {
    const std::int64_t py = j * kSub + kSub / 2;
    for (std::int64_t i = i0; i <= i1; ++i) {
      const std::int64_t px = i * kSub + kSub / 2;
      const std::int64_t w0 = edge(v1, v2, px, py), w1 = edge(v2, v0, px, py),
                         w2 = edge(v0, v1, px, py);
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      if ((w0 == 0 && !tl0) || (w1 == 0 && !tl1) || (w2 == 0 && !tl2)) continue;
      const double z = (static_cast<double>(w0) * v0.z + static_cast<double>(w1) * v1.z +
                        static_cast<double>(w2) * v2.z) * inv;
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(cv.w) +
                            static_cast<std::size_t>(i);
      if (z > cv.depth[k]) {
        cv.depth[k] = z;
        cv.colour[k] = colour;
      }
    }
  }
}

void check_options(const RenderOptions& o) {
  constexpr int kMaxSide = 16384;
  if (o.width < 1 || o.height < 1 || o.width > kMaxSide || o.height > kMaxSide)
    throw std::invalid_argument("write_radiosity_png: image size " + std::to_string(o.width) +
                                " x " + std::to_string(o.height) + " is outside 1.." +
                                std::to_string(kMaxSide));
  if (!o.view_direction.allFinite() || !(o.view_direction.norm() > 0.0))
    throw std::invalid_argument("write_radiosity_png: view_direction must be finite and non-zero");
  if (!o.up.allFinite() || !(o.up.norm() > 0.0))
    throw std::invalid_argument("write_radiosity_png: up must be finite and non-zero");
}

// ---------------------------------------------------------------------------------------------
// The picture's stages: camera, fit of the projected field into the plot area, rasterization of
// the elements, colour bar, and the average of each pixel's samples.

/// Orthographic camera looking along -d; screen right r and up u with r x u = d.
struct OrthoCamera {
  Vec3 d, r, u;
};

OrthoCamera camera_along(const Vec3& view_direction, const Vec3& up) {
  const Vec3 d = view_direction.normalized();
  const Vec3 w = up.normalized();
  // Along `up` itself the screen's up is the next axis after up's largest component.
  int k = 0;
  w.cwiseAbs().maxCoeff(&k);
  const Vec3 up0 = std::abs(d.dot(w)) > 1.0 - 1e-9 ? Vec3::Unit((k + 2) % 3) : w;
  const Vec3 r = up0.cross(d).normalized();
  const Vec3 u = d.cross(r);
  return OrthoCamera{d, r, u};
}

/// Screen position (in samples) = o + (projection - c) * scale, y downwards.
struct ScreenFit {
  double scale, cx, cy, ox, oy;
};

/// Fits the projected box of the field into the plot area (plot_w x H pixels) with a 5% margin,
/// keeping the aspect ratio.
ScreenFit fit_to_plot(const ElementField& field, const OrthoCamera& camera, int plot_w, int H) {
  const Vec3& r = camera.r;
  const Vec3& u = camera.u;
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
  for (const auto& tri : field.triangle)
    for (const Vec3& p : tri) {
      xlo = std::min(xlo, p.dot(r));
      xhi = std::max(xhi, p.dot(r));
      ylo = std::min(ylo, p.dot(u));
      yhi = std::max(yhi, p.dot(u));
    }
  const double sw = kSamples * plot_w * 0.9, sh = kSamples * H * 0.9;
  const double bw = xhi - xlo, bh = yhi - ylo;
  double scale = std::min(bw > 0.0 ? sw / bw : std::numeric_limits<double>::infinity(),
                          bh > 0.0 ? sh / bh : std::numeric_limits<double>::infinity());
  if (!std::isfinite(scale)) scale = 1.0;
  const double cx = 0.5 * (xlo + xhi), cy = 0.5 * (ylo + yhi);
  const double ox = 0.5 * kSamples * plot_w, oy = 0.5 * kSamples * H;
  return ScreenFit{scale, cx, cy, ox, oy};
}

/// A W x H pixel canvas of background samples, none drawn yet.
Canvas blank_canvas(int W, int H) {
  Canvas cv{kSamples * W, kSamples * H, {}, {}};
  const std::size_t samples = static_cast<std::size_t>(cv.w) * static_cast<std::size_t>(cv.h);
  cv.colour.assign(samples, kBackground);
  cv.depth.assign(samples, -std::numeric_limits<double>::infinity());
  return cv;
}

/// Draws every element whose inner side faces the viewer, nearest in front, in the plot area.
void draw_elements(Canvas& cv, const ElementField& field, const std::vector<Rgb>& colour,
                   const OrthoCamera& camera, const ScreenFit& fit, int plot_w) {
  const Vec3& d = camera.d;
  const Vec3& r = camera.r;
  const Vec3& u = camera.u;
  const auto project = [&](const Vec3& p) {
    const double x = fit.ox + (p.dot(r) - fit.cx) * fit.scale, y = fit.oy - (p.dot(u) - fit.cy) * fit.scale;
    return ScreenPoint{std::llround(x * kSub), std::llround(y * kSub), p.dot(d)};
  };
  for (std::size_t i = 0; i < field.size(); ++i) {
    if (!(field.inner_normal[i].dot(d) > 0.0)) continue;  // inner side turned away: a near wall
    const auto& t = field.triangle[i];
    fill_triangle(cv, project(t[0]), project(t[1]), project(t[2]), colour[i], kSamples * plot_w);
  }
}

/// Colour bar right of the plot area: bottom = minimum, top = maximum, with a thin light frame.
void draw_colour_bar(Canvas& cv, int W, int H, int plot_w) {
  const int x0 = kSamples * (plot_w + std::max(4, (W - plot_w) / 3));
  const int x1 = kSamples * (W - std::max(4, (W - plot_w) / 3));
  const int y0 = kSamples * (H / 10), y1 = kSamples * (H - H / 10);
  for (int y = y0 - 2; y < y1 + 2; ++y)
    for (int x = x0 - 2; x < x1 + 2; ++x) {
      const bool inside = y >= y0 && y < y1 && x >= x0 && x < x1;
      const double t = 1.0 - (y + 0.5 - y0) / (y1 - y0);
      cv.colour[static_cast<std::size_t>(y) * static_cast<std::size_t>(cv.w) +
                static_cast<std::size_t>(x)] = inside ? colour_map(t) : Rgb{200, 200, 200};
    }
}

/// The W x H RGB image: each pixel the rounded average of its kSamples x kSamples samples.
std::vector<unsigned char> average_samples(const Canvas& cv, int W, int H) {
  std::vector<unsigned char> image(3 * static_cast<std::size_t>(W) * static_cast<std::size_t>(H));
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (std::size_t c = 0; c < 3; ++c) {
        int sum = 0;
        for (int sy = 0; sy < kSamples; ++sy)
          for (int sx = 0; sx < kSamples; ++sx)
            sum += cv.colour[static_cast<std::size_t>(kSamples * y + sy) *
                                 static_cast<std::size_t>(cv.w) +
                             static_cast<std::size_t>(kSamples * x + sx)][c];
        constexpr int kCount = kSamples * kSamples;
        image[(static_cast<std::size_t>(y) * static_cast<std::size_t>(W) +
               static_cast<std::size_t>(x)) * 3 + c] =
            static_cast<unsigned char>((sum + kCount / 2) / kCount);
      }
  return image;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

void check_channel_names(const std::vector<std::string>& channels) {
  check_names("channel names", channels);
}

void write_radiosity_csv(const std::string& path, const ElementField& field) {
  write_file_atomically(path, radiosity_csv(field));
}

std::string radiosity_csv(const ElementField& field) {
  validate("write_radiosity_csv", field);
  std::string out = "element,facet,x,y,z,area";
  for (std::size_t c = 0; c < field.channels.size(); ++c) {
    const std::string s = suffix(field, c);
    out += ",rho" + s + ",E" + s + ",u" + s;
  }
  out += '\n';
  for (std::size_t i = 0; i < field.size(); ++i) {
    out += std::to_string(i) + ',' + std::to_string(field.facet[i]);
    for (int k = 0; k < 3; ++k) {
      out += ',';
      append_g17(out, field.centroid[i][k]);
    }
    out += ',';
    append_g17(out, field.area[i]);
    for (std::size_t c = 0; c < field.channels.size(); ++c)
      for (const auto* v : {&field.rho[c], &field.emission[c], &field.radiosity[c]}) {
        out += ',';
        append_g17(out, value(*v, i));
      }
    out += '\n';
  }
  return out;
}

namespace {
// One line "x y z" per shared vertex, 17 significant digits (round-trip).
void append_points(std::string& out, const std::vector<Vec3>& points) {
  for (const Vec3& p : points) {
    append_g17(out, p.x());
    out += ' ';
    append_g17(out, p.y());
    out += ' ';
    append_g17(out, p.z());
    out += '\n';
  }
}
}  // namespace

void write_radiosity_ply(const std::string& path, const ElementField& field) {
  write_file_atomically(path, radiosity_ply(field));
}

std::string radiosity_ply(const ElementField& field) {
  validate("write_radiosity_ply", field);
  std::vector<bool> as_float(field.channels.size(), true);
  for (std::size_t c = 0; c < field.channels.size(); ++c)
    for (std::size_t i = 0; i < field.size() && as_float[c]; ++i)
      as_float[c] = fits_float(value(field.radiosity[c], i));
  const SharedVertices sv = share_vertices(field);
  const std::vector<Rgb> colour = colours_of_valid(field);
  std::string out = "ply\nformat ascii 1.0\ncomment panelrad radiosity\n";
  out += "element vertex " + std::to_string(sv.points.size()) + "\n";
  out += "property double x\nproperty double y\nproperty double z\n";
  out += "element face " + std::to_string(field.size()) + "\n";
  out += "property list uchar int vertex_indices\n";
  out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  for (std::size_t c = 0; c < field.channels.size(); ++c)
    out += std::string(as_float[c] ? "property float u" : "property double u") + suffix(field, c) + "\n";
  out += "end_header\n";
  append_points(out, sv.points);
  for (std::size_t i = 0; i < field.size(); ++i) {
    out += "3 " + std::to_string(sv.corner[i][0]) + ' ' + std::to_string(sv.corner[i][1]) + ' ' +
           std::to_string(sv.corner[i][2]);
    for (const unsigned char b : colour[i]) out += ' ' + std::to_string(static_cast<int>(b));
    for (std::size_t c = 0; c < field.channels.size(); ++c) {
      out += ' ';
      if (as_float[c]) append_g9(out, value(field.radiosity[c], i));
      else append_g17(out, value(field.radiosity[c], i));
    }
    out += '\n';
  }
  return out;
}

void write_radiosity_vtk(const std::string& path, const ElementField& field) {
  write_file_atomically(path, radiosity_vtk(field));
}

std::string radiosity_vtk(const ElementField& field) {
  validate("write_radiosity_vtk", field);
  const SharedVertices sv = share_vertices(field);
  const std::size_t n = field.size();
  std::string out = "# vtk DataFile Version 3.0\npanelrad radiosity\nASCII\nDATASET POLYDATA\n";
  out += "POINTS " + std::to_string(sv.points.size()) + " double\n";
  append_points(out, sv.points);
  out += "POLYGONS " + std::to_string(n) + ' ' + std::to_string(4 * n) + '\n';
  for (std::size_t i = 0; i < n; ++i)
    out += "3 " + std::to_string(sv.corner[i][0]) + ' ' + std::to_string(sv.corner[i][1]) + ' ' +
           std::to_string(sv.corner[i][2]) + '\n';
  out += "CELL_DATA " + std::to_string(n) + '\n';
  out += "SCALARS facet int 1\nLOOKUP_TABLE default\n";
  for (std::size_t i = 0; i < n; ++i) out += std::to_string(field.facet[i]) + '\n';
  const auto scalars = [&](const std::string& name, const auto& get) {
    out += "SCALARS " + name + " double 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < n; ++i) {
      append_g17(out, get(i));
      out += '\n';
    }
  };
  scalars("area", [&](std::size_t i) { return field.area[i]; });
  for (std::size_t c = 0; c < field.channels.size(); ++c) {
    const std::string s = suffix(field, c);
    scalars("rho" + s, [&](std::size_t i) { return value(field.rho[c], i); });
    scalars("E" + s, [&](std::size_t i) { return value(field.emission[c], i); });
    scalars("u" + s, [&](std::size_t i) { return value(field.radiosity[c], i); });
  }
  if (is_rgb(field)) {  // the picture's colours, for ParaView's "Map Scalars" off
    out += "COLOR_SCALARS colour 3\n";
    char buf[64];
    for (const Rgb& c : colours_of_valid(field)) {
      std::snprintf(buf, sizeof buf, "%.6g %.6g %.6g\n", c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
      out += buf;
    }
  }
  return out;
}

Vec3 brightest_view_direction(const ElementField& field) {
  validate("brightest_view_direction", field);
  Vec3 best(-1.0, -1.7, 1.2);
  double best_light = -1;
  for (int k = 0; k < 8; ++k) {
    const Vec3 d((k & 1) ? 1.0 : -1.0, (k & 2) ? 1.7 : -1.7, (k & 4) ? -1.2 : 1.2);
    const Vec3 unit = d.normalized();
    double light = 0;
    for (std::size_t i = 0; i < field.size(); ++i) {
      const double facing = field.inner_normal[i].dot(unit);
      if (facing <= 0) continue;  // not visible in the cut-away view
      double u = 0;
      for (const Eigen::VectorXd& r : field.radiosity) u += r[static_cast<Eigen::Index>(i)];
      light += field.area[i] * facing * u;
    }
    if (light > best_light * (1 + 1e-12)) {
      best_light = light;
      best = d;
    }
  }
  return best;
}

std::vector<std::array<unsigned char, 3>> element_colours(const ElementField& field) {
  validate("element_colours", field);
  return colours_of_valid(field);
}

void write_radiosity_png(const std::string& path, const ElementField& field,
                         const RenderOptions& options) {
  write_file_atomically(path, radiosity_png(field, options));
}

std::string radiosity_png(const ElementField& field, const RenderOptions& options) {
  validate("write_radiosity_png", field);
  check_options(options);
  const std::vector<Rgb> colour = colours_of_valid(field);
  const bool scalar = !is_rgb(field);
  const OrthoCamera camera = camera_along(options.view_direction, options.up);

  // Scalar scenes keep the right eighth of the picture for the colour bar.
  const int W = options.width, H = options.height;
  const bool bar = scalar && W >= 24 && H >= 16;
  const int plot_w = bar ? W - std::max(12, W / 8) : W;

  const ScreenFit fit = fit_to_plot(field, camera, plot_w, H);
  Canvas cv = blank_canvas(W, H);
  draw_elements(cv, field, colour, camera, fit, plot_w);
  if (bar) draw_colour_bar(cv, W, H, plot_w);
  const std::vector<unsigned char> image = average_samples(cv, W, H);

  std::string png;
  PngSink sink{&png, {}};
  if (!encode_png(image.data(), W, H, &sink))
    throw std::runtime_error(std::string("write_radiosity_png: libpng: ") + sink.message);
  return png;
}

}  // namespace panelrad
