#include "relief/image_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>

#include "core/atomic_write.h"
#include "core/error.h"

namespace rl {
namespace {

struct Image {
  int width = 0, height = 0, channels = 0;
  bool eight_bit = false;
  double integer_max = 0;     // ImageHeader's: an integer format's largest value, else 0
  std::vector<float> pixels;  // row 0 = top of the file
  float at(int x, int y, int c) const {
    return pixels[(static_cast<size_t>(y) * width + x) * channels + std::min(c, channels - 1)];
  }
  // A read value as the file stores it: an int16 DEM's -32768, not the -1.00003 it reads as.
  // What nodata and the usual nodata values are compared with.
  double stored(float v) const {
    return integer_max > 0 ? std::round(double(v) * integer_max) : double(v);
  }
};

Image read_image(const std::string& path) {
  if (!std::filesystem::exists(path)) throw ConfigError("relief image not found: " + path);
  const ImageBackend& files = image_backend();
  ImageHeader spec;
  std::string error;
  if (!files.read_header(path, spec, error))
    throw ConfigError("cannot read image " + path + ": " + one_line(error));
  // Checked before anything is allocated: a header may claim any size.
  constexpr int kLargestSide = 16384;
  if (spec.width > kLargestSide || spec.height > kLargestSide || spec.channels > 16)
    throw ConfigError(path + ": image is " + std::to_string(spec.width) + "x" +
                      std::to_string(spec.height) + " with " + std::to_string(spec.channels) +
                      " channels; relief images are at most " + std::to_string(kLargestSide) + "x" +
                      std::to_string(kLargestSide) + " with 16 channels");
  Image img;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.channels;
  img.eight_bit = spec.eight_bit;
  img.integer_max = spec.integer_max;
  if (!files.read_pixels(path, spec, img.pixels, error))
    throw ConfigError("cannot decode image " + path + ": " + one_line(error));
  if (img.width < 2 || img.height < 2) throw ConfigError("image too small: " + path);
  // A NaN or infinite texel (float formats such as EXR) would leave every truth ray through it
  // unresolved and the row published; refuse it, naming where it is.
  for (size_t i = 0; i < img.pixels.size(); ++i)
    if (!std::isfinite(img.pixels[i])) {
      const size_t texel = i / size_t(img.channels);
      throw ConfigError(path + ": texel (" + std::to_string(texel % size_t(img.width)) + ", " +
                        std::to_string(texel / size_t(img.width)) + ") channel " +
                        std::to_string(i % size_t(img.channels)) +
                        " is not a finite number (NaN or infinity)");
    }
  return img;
}

// Whether channel `c` takes more than one 8-bit step of values over the image.
bool channel_varies(const Image& img, int c) {
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      lo = std::min(lo, img.at(x, y, c));
      hi = std::max(hi, img.at(x, y, c));
    }
  return hi - lo > 1.5f / 255;
}

// Whether some texel's red, green and blue differ by more than an 8-bit step (not a grey image).
bool has_colour(const Image& img) {
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (std::abs(img.at(x, y, 0) - img.at(x, y, 1)) > 1.5f / 255 ||
          std::abs(img.at(x, y, 1) - img.at(x, y, 2)) > 1.5f / 255)
        return true;
  return false;
}

// Bilinear resample of one image to (w, h), used only for colour maps of a different size.
Image resized(const Image& img, int w, int h) {
  if (img.width == w && img.height == h) return img;
  Image r = img;
  r.width = w;
  r.height = h;
  r.eight_bit = false;
  r.pixels.resize(static_cast<size_t>(w) * h * img.channels);
  image_backend().resize(img.pixels.data(), img.width, img.height, img.channels, r.pixels.data(), w,
                         h);
  return r;
}

// The depths a map's file holds, in ReliefLab's convention (0 = top). A float image (EXR, TIFF,
// PFM) may hold any value: one outside [0, 1] was clamped silently, and normalize, applied
// after the clamp, could not undo it. Out-of-range depths are now rescaled by normalize or
// refused, naming the file and the values it holds (read_image refuses non-finite texels).
// Texels at the source's nodata value are left out; without one, a usual nodata value of a
// GeoTIFF at the edge of the range is refused rather than folded into it.
struct DepthRange {
  float lo = 0, hi = 0;
  long nodata = 0;  // texels at the nodata value
};

// Values that mark texels without data in elevation rasters (GDAL's and ESRI's usual ones).
bool usual_nodata_value(float v) {
  for (float x : {-9999.0f, -32768.0f, -32767.0f, -99999.0f, std::numeric_limits<float>::lowest(),
                  std::numeric_limits<float>::max()})
    if (v == x) return true;
  return false;
}

std::string file_of(const ReliefImageSource& src) {
  return src.depth_path.empty() ? src.normal_path : src.depth_path;
}

// With normalize and no nodata given: a usual nodata value at an end of the file's values would
// squeeze the terrain into a sliver of the depth and show its missing texels as pits.
void refuse_unnamed_nodata(const ReliefImageSource& src, const Image& depth, int channel,
                           float file_lo, float file_hi) {
  for (float end : {file_lo, file_hi}) {
    const double sentinel = depth.stored(end);
    if (!usual_nodata_value(float(sentinel))) continue;
    long count = 0;
    double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
    for (int y = 0; y < depth.height; ++y)
      for (int x = 0; x < depth.width; ++x) {
        const double v = depth.stored(depth.at(x, y, channel));
        if (v == sentinel)
          ++count;
        else
          lo = std::min(lo, v), hi = std::max(hi, v);
      }
    if (lo > hi) continue;  // every texel holds it: a flat map, nothing to squeeze
    char text[384];
    std::snprintf(text, sizeof text,
                  ": %ld texel(s) hold %.9g, the usual nodata value of a GeoTIFF; normalize would "
                  "fold it into the range, squeezing the other values (%.6g to %.6g) into %.2g%% "
                  "of the depth: give nodata = %.9g to fill them at the deepest valid depth",
                  count, sentinel, lo, hi,
                  100.0 * (hi - lo) / (depth.stored(file_hi) - depth.stored(file_lo)), sentinel);
    throw ConfigError(file_of(src) + text);
  }
}

DepthRange depth_range(const Image& depth, int channel, const ReliefImageSource& src) {
  DepthRange r{std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()};
  float file_lo = std::numeric_limits<float>::max(), file_hi = std::numeric_limits<float>::lowest();
  long outside = 0;
  for (int y = 0; y < depth.height; ++y)
    for (int x = 0; x < depth.width; ++x) {
      const float v = depth.at(x, y, channel);
      if (depth.stored(v) == src.nodata) {  // never true for NaN (none given)
        ++r.nodata;
        continue;
      }
      const float d = src.height_convention ? 1.0f - v : v;
      file_lo = std::min(file_lo, v);
      file_hi = std::max(file_hi, v);
      r.lo = std::min(r.lo, d);
      r.hi = std::max(r.hi, d);
      outside += d < -1e-6f || d > 1.0f + 1e-6f;
    }
  if (r.nodata == long(depth.width) * depth.height) {
    char text[128];
    std::snprintf(text, sizeof text, ": every texel holds the nodata value %.9g: no data",
                  src.nodata);
    throw ConfigError(file_of(src) + text);
  }
  if (src.normalize && std::isnan(src.nodata))
    refuse_unnamed_nodata(src, depth, channel, file_lo, file_hi);
  if (outside && !src.normalize) {
    char range[96];
    std::snprintf(range, sizeof range, "%.6g to %.6g", file_lo, file_hi);
    throw ConfigError(file_of(src) + ": " + std::to_string(outside) +
                      " texel(s) lie outside [0, 1] (its values span " + range +
                      "): set normalize = true to rescale the map to [0, 1], or rescale the file "
                      "(a GeoTIFF's nodata value shows as one too: name it with nodata = V)");
  }
  return r;
}

}  // namespace

ReliefMap load_relief_images(const ReliefImageSource& src, double depth_per_texel) {
  if (src.normal_path.empty() && src.depth_path.empty())
    throw ConfigError("relief image source needs a normal map with depth in alpha, or a depth map");
  Image normal, depth;
  if (!src.normal_path.empty()) normal = read_image(src.normal_path);
  if (!src.depth_path.empty()) {
    depth = read_image(src.depth_path);
  } else {
    if (normal.channels < 4)
      throw ConfigError(src.normal_path +
                        ": a normal map holds RGB normals and depth in alpha (4 " +
                        "channels); this image has " + std::to_string(normal.channels) +
                        (normal.channels == 2 ? " (grey + alpha)" : "") +
                        "; give its depth as a separate depth image");
    depth = normal;
  }
  const int w = depth.width, h = depth.height;
  const bool has_normals = !src.normal_path.empty();
  if (has_normals && (normal.width != w || normal.height != h)) normal = resized(normal, w, h);

  ReliefMap map;
  map.name = std::filesystem::path(src.normal_path.empty() ? src.depth_path : src.normal_path)
                 .stem()
                 .string();
  map.width = w;
  map.height = h;
  map.relief.resize(static_cast<size_t>(w) * h);
  map.color.assign(map.relief.size(), glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  const int depth_channel = src.depth_path.empty() ? 3 : 0;
  const DepthRange range = depth_range(depth, depth_channel, src);
  for (int y = 0; y < h; ++y) {
    const int file_row = h - 1 - y;  // file's top row is v = 1
    for (int x = 0; x < w; ++x) {
      const float v = depth.at(x, file_row, depth_channel);
      // A texel without data sits at the deepest valid depth (the lowest valid height).
      float d = depth.stored(v) == src.nodata ? range.hi : src.height_convention ? 1.0f - v : v;
      glm::vec4 t(0.5f, 0.5f, 1.0f, std::clamp(d, 0.0f, 1.0f));
      if (src.normalize && range.hi > range.lo) t.a = (d - range.lo) / (range.hi - range.lo);
      if (has_normals) {
        t.r = normal.at(x, file_row, 0);
        t.g = normal.at(x, file_row, 1);
        t.b = normal.at(x, file_row, 2);
        if (src.flip_green) t.g = 1.0f - t.g;
      }
      map.relief[map.index(x, y)] = t;
    }
  }
  if (!has_normals) normals_from_depth(map, depth_per_texel);
  if (!src.color_path.empty()) {
    Image color = resized(read_image(src.color_path), w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        map.color[map.index(x, y)] = glm::vec4(color.at(x, h - 1 - y, 0), color.at(x, h - 1 - y, 1),
                                               color.at(x, h - 1 - y, 2), 1.0f);
  }
  map.quantized = false;  // set only by quantize_8bit(), which makes every channel exact
  return map;
}

std::string depth_file_alpha_problem(const std::string& depth_path) {
  ImageHeader header;
  std::string error;
  if (image_backend().read_header(depth_path, header, error) && header.channels < 4) return "";
  const Image img = read_image(depth_path);
  if (img.channels < 4 || !channel_varies(img, 3) || !has_colour(img)) return "";
  const std::string name = std::filesystem::path(depth_path).filename().string();
  return name +
         " is read as a depth map from its first channel (red), but its red, green and blue "
         "differ and its alpha channel holds a surface of its own: it looks like a normal map "
         "with height in alpha; did you mean `normal = \"" +
         name + "\"` (normals from RGB, the depth from alpha)?";
}

void write_png(const std::string& path, int width, int height, int channels,
               const std::vector<float>& pixels) {
  std::vector<unsigned char> bytes(static_cast<size_t>(width) * height * channels);
  for (int y = 0; y < height; ++y) {
    const float* src = &pixels[static_cast<size_t>(height - 1 - y) * width * channels];
    unsigned char* dst = &bytes[static_cast<size_t>(y) * width * channels];
    for (int i = 0; i < width * channels; ++i) {
      float v = std::isfinite(src[i]) ? std::clamp(src[i], 0.0f, 1.0f) : 0.0f;
      dst[i] = static_cast<unsigned char>(v * 255.0f + 0.5f);
    }
  }
  ImageWriteSpec spec;
  spec.width = width;
  spec.height = height;
  spec.channels = channels;
  write_image_file(path, spec, bytes.data());
}

void write_image_file(const std::string& path, const ImageWriteSpec& spec, const void* pixels) {
  const std::filesystem::path final_path(path);
  if (final_path.has_parent_path()) std::filesystem::create_directories(final_path.parent_path());
  const std::string tmp = unique_temp_path(path);
  std::string failure;
  if (!image_backend().write(tmp, spec, pixels, failure)) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error("cannot write image " + path + ": " + failure);
  }
  commit_temp(tmp, path);
}

}  // namespace rl
